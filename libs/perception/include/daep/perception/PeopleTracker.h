#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "daep/common/Types.h"
#include "daep/perception/PersonMeasurement.h"
#include "daep/perception/PersonTrack.h"

namespace mrpt::config {
class CConfigFileBase;
}
namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace daep::perception {

struct TrackerParams {
    PredictorParams predictor;
    /** A track not measured for this long (s) is dropped; until then it is predicted on. */
    double dropAfter = 20.0;
    /**
     * A confirmed track is dropped sooner when the sensor saw, this many updates in a row,
     * that nobody stands where it predicts the person (see update's seenEmpty).
     */
    int dropAfterMissesInView = 3;
    /**
     * Gate for anonymous measurements: squared Mahalanobis distance of the innovation, chi-square
     * with 2 degrees of freedom (9.21 = 99 %). A measurement outside every track's gate starts a
     * new track instead of updating one.
     */
    double gateChi2 = 9.21;
    /** Measurements a new anonymous track needs before it is confirmed (shown in forecasts()). */
    int confirmHits = 3;
    /** A tentative track not measured for this long (s) is dropped (clutter dies fast). */
    double tentativeDropAfter = 1.0;
    /**
     * An anonymous track whose measurements stay within staticRadius (m) of one spot for
     * staticAfter seconds, and which is predicted to be there still, is static clutter (a wall
     * the detector took for a person), not a person: it is dropped, and anonymous
     * measurements within staticRadius of that spot are ignored for staticMemory seconds,
     * while the map takes the surface in. 0: off.
     */
    double staticAfter = 5.0;
    double staticRadius = 0.4;
    double staticMemory = 10.0;

    /** Reads and validates [tracker]; throws InputError naming the key. */
    static TrackerParams fromConfig(const mrpt::config::CConfigFileBase& cfg);
};

/** One track as the tracker sees it (for display and evaluation). */
struct TrackInfo {
    PersonForecast forecast;
    int hits = 0;            ///< measurements so far
    bool confirmed = false;  ///< known id, or anonymous with >= confirmHits hits
    double lastSeen = 0.0;
};

/**
 * The people the drone knows of: one constant-velocity Kalman track per person, kept across
 * updates (never rebuilt), predicted on with growing uncertainty while unseen, dropped after
 * `dropAfter` seconds without a measurement, or sooner when the sensor sees the predicted
 * position empty.
 *
 * Measurements with a known id update the track of that id (created on first sight, confirmed
 * at once). Anonymous measurements (id = -1, e.g. from PeopleDetector) are associated with the
 * anonymous tracks: each pair inside the chi-square gate costs the negative log-likelihood of
 * the innovation (d^2 + ln det S), and the Hungarian method picks the assignment of least total
 * cost. A measurement left over starts a tentative track, unless it lies inside the gate of a
 * confirmed track (a person seen twice, e.g. split by an occluder, must not become two). A
 * tentative track is confirmed after confirmHits measurements and dropped after
 * tentativeDropAfter seconds unseen.
 */
class PeopleTracker {
public:
    explicit PeopleTracker(const TrackerParams& params);

    /** Whether the sensor saw, at this instant, that nobody stands at an x/y position. */
    using EmptyTest = std::function<bool(const Eigen::Vector2d&)>;

    /**
     * Feeds the measurements of one instant (time non-decreasing across calls). With
     * seenEmpty, a confirmed track left unmeasured whose predicted position the sensor saw
     * empty counts a miss; dropAfterMissesInView misses in a row drop it. Tracks predicted
     * where the sensor did not look live on up to dropAfter.
     */
    void update(double time, const std::vector<PersonMeasurement>& measurements,
                const EmptyTest& seenEmpty = {});

    /** A closed-form forecast of every live confirmed track. */
    std::vector<PersonForecast> forecasts() const;
    /** Forecasts of the anonymous tracks still waiting for confirmation. */
    std::vector<PersonForecast> tentativeForecasts() const;
    /** Every live track, confirmed or not. */
    std::vector<TrackInfo> tracks() const;

    /** Tracks dropped as static clutter so far. */
    int staticClutterDropped() const { return staticDropped_; }

    /** Live tracks, confirmed and tentative. */
    std::size_t size() const { return tracks_.size(); }
    std::size_t confirmedCount() const;
    const TrackerParams& params() const { return params_; }

private:
    struct Track {
        int id = -1;
        PersonTrack filter;
        double lastSeen = 0.0;
        int hits = 1;
        bool anonymous = false;
        int missesInView = 0;  ///< updates in a row that saw its predicted position empty
        Eigen::Vector2d stillAt = Eigen::Vector2d::Zero();  ///< where its measurements stay...
        double stillSince = 0.0;                            ///< ...since this time
    };
    /** Where static clutter was found, and when. */
    struct ClutterSpot {
        Eigen::Vector2d position;
        double time = 0.0;
    };

    bool confirmed(const Track& t) const { return !t.anonymous || t.hits >= params_.confirmHits; }
    Track* findById(int id);
    void updateOrStart(double time, int id, const PersonMeasurement& m);
    void associateAnonymous(double time, const std::vector<PersonMeasurement>& anonymous);
    void startAnonymous(double time, const PersonMeasurement& m);
    void dropStale(double time);
    void countMisses(double time, const EmptyTest& seenEmpty);
    /** Measured at `m`: a track that stays put long enough becomes a clutter spot. */
    void noteStill(Track& t, double time, const Eigen::Vector2d& m);
    void dropStaticClutter(double time);
    /** Clutter spots older than staticMemory are forgotten. */
    void forgetOldClutter(double time);
    /** Within staticRadius of a clutter spot still remembered. */
    bool inClutter(const Eigen::Vector2d& p) const;

    TrackerParams params_;
    std::vector<Track> tracks_;
    std::vector<ClutterSpot> clutter_;
    int nextAnonymousId_ = 1000000;
    int staticDropped_ = 0;
};

/**
 * The tracker's empty-place test for a depth frame taken from `robot`: nobody stands at xy
 * when the frame sees past the middle of a body there, across its width (a person a little
 * off still blocks one of the three rays). Empty without a frame. The frame must outlive the
 * test.
 */
PeopleTracker::EmptyTest seenEmptyIn(const mrpt::obs::CObservation3DRangeScan* frame,
                                     const FlatPose& robot, const Eigen::Vector3d& bodySize);

}  // namespace daep::perception
