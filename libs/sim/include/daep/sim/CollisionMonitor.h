#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/common/Types.h"
#include "daep/world/People.h"

namespace daep::world {
class StaticCollisionChecker;
}

namespace daep::sim {

struct CollisionEvent {
    int personIndex = -1;  ///< -1 for static geometry
    double start = 0.0;
    double end = -1.0;  ///< -1 while ongoing
};

/**
 * Counts collisions: a new overlap of the drone box with a person box counts once per person
 * (it must separate before it counts again). Contact with static geometry is counted apart.
 */
class CollisionMonitor {
public:
    CollisionMonitor(Eigen::Vector3d droneBoxSize, Eigen::Vector3d personBoxSize,
                     const world::StaticCollisionChecker* staticChecker);

    void update(double time, const FlatPose& drone, const std::vector<world::PersonState>& people);

    int personCollisions() const { return personCollisions_; }
    int staticCollisions() const { return staticCollisions_; }
    const std::vector<CollisionEvent>& events() const { return events_; }

    /** Overlap of the drone box (yaw) with one person box (heading), both boxes solid. */
    static bool droneTouchesPerson(const FlatPose& drone, const Eigen::Vector3d& droneSize,
                                   const world::PersonState& person,
                                   const Eigen::Vector3d& personSize);

private:
    /** Opens or closes one contact episode; true when a new one starts. */
    bool updateContact(double time, bool touching, int personIndex, int& openEvent);

    Eigen::Vector3d droneSize_;
    Eigen::Vector3d personSize_;
    const world::StaticCollisionChecker* staticChecker_;
    std::vector<int> openEventOfPerson_;  ///< index into events_, -1 if not touching
    int openStaticEvent_ = -1;
    int personCollisions_ = 0;
    int staticCollisions_ = 0;
    std::vector<CollisionEvent> events_;
};

}  // namespace daep::sim
