#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/world/WorldSpec.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace daep::world {

struct PeopleParams {
    double speed = 0.35;    ///< m/s
    double turnRate = 1.0;  ///< rad/s; people turn on the spot towards the next waypoint
    Eigen::Vector3d bodySize{1.0, 1.0, 1.8};  ///< box standing on z = 0, rotated by heading

    /** Reads and validates [people]; throws InputError naming the key. */
    static PeopleParams fromConfig(const mrpt::config::CConfigFileBase& cfg);
};

struct PersonState {
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
    Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  ///< zero while turning
    double heading = 0.0;
    std::size_t nextWaypoint = 1;
};

/** Deterministic people motion: each person starts at its first waypoint facing the second. */
class PeopleSimulator {
public:
    PeopleSimulator(std::vector<PersonRoute> routes, PeopleParams params);

    /** Advances all people by dt seconds (any dt, exact piecewise motion). */
    void advance(double dt);

    double time() const { return time_; }
    const std::vector<PersonState>& states() const { return states_; }
    const std::vector<PersonRoute>& routes() const { return routes_; }
    const PeopleParams& params() const { return params_; }

private:
    void advancePerson(std::size_t i, double dt);

    std::vector<PersonRoute> routes_;
    PeopleParams params_;
    std::vector<PersonState> states_;
    double time_ = 0.0;
};

}  // namespace daep::world
