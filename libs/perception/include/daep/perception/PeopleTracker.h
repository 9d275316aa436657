#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/perception/PersonTrack.h"

namespace daep::perception {

/**
 * One measured person position. `id` >= 0 when the source knows who it is (the simulator's
 * ground truth, or its "sensed" camera model); -1 for an anonymous detection, which the
 * tracker associates with its tracks itself.
 */
struct PersonMeasurement {
    int id = -1;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity() * 1e-4;  ///< of the position, m^2
};

struct TrackerParams {
    PredictorParams predictor;
    /** A track not measured for this long (s) is dropped; until then it is predicted on. */
    double dropAfter = 5.0;
};

/**
 * The people the drone knows of: one constant-velocity Kalman track per person, kept across
 * updates (never rebuilt), predicted on with growing uncertainty while unseen, dropped after
 * `dropAfter` seconds without a measurement.
 */
class PeopleTracker {
public:
    explicit PeopleTracker(const TrackerParams& params);

    /** Feeds the measurements of one instant (time non-decreasing across calls). */
    void update(double time, const std::vector<PersonMeasurement>& measurements);

    /** A closed-form forecast of every live track. */
    std::vector<PersonForecast> forecasts() const;

    std::size_t size() const { return tracks_.size(); }
    const TrackerParams& params() const { return params_; }

private:
    struct Track {
        int id = -1;
        PersonTrack filter;
        double lastSeen = 0.0;
    };

    Track* findById(int id);
    void updateOrStart(double time, int id, const PersonMeasurement& m);
    void dropStale(double time);

    TrackerParams params_;
    std::vector<Track> tracks_;
    int nextAnonymousId_ = 1000000;
};

}  // namespace daep::perception
