#pragma once

#include <random>
#include <string>
#include <vector>

#include "daep/common/Types.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/FrameSource.h"
#include "daep/perception/PeopleDetector.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/People.h"

namespace mrpt::config {
class CConfigFileBase;
}
namespace mrpt::obs {
class CObservation3DRangeScan;
}
namespace daep::mapping {
class ExplorationMap;
}
namespace daep::world {
class RayCaster;
}

namespace daep::mission {

/** [tracking] people_source: where the planner's people come from. */
enum class PeopleSource {
    GroundTruth,  ///< every person, exactly
    Sensed,       ///< only people the camera really sees, with noise
    Detected,     ///< people found in the depth frames by the detector
};

/** The ini word of a people source (ground_truth, sensed, detected). */
const char* peopleSourceName(PeopleSource source);

/** Section [tracking]: where the planner's people come from and how they are tracked. */
struct PeopleInputParams {
    PeopleSource source = PeopleSource::GroundTruth;
    double sensedRange = 10.0;       ///< m from the camera
    double sensedNoiseSigma = 0.05;  ///< m, Gaussian on each sensed position
    /** Depth returns on the people tracked lately are kept out of the map (see mapFootprints). */
    bool excludeFromMap = true;
    perception::TrackerParams tracker;
    perception::DetectorParams detector;

    static PeopleInputParams fromConfig(const mrpt::config::CConfigFileBase& config);
};

/** A depth frame and the robot pose it was taken from. */
struct DepthView {
    const mrpt::obs::CObservation3DRangeScan* frame = nullptr;
    FlatPose robot;
};

/** What people_source = sensed needs besides the truth: the simulated scene and the camera in it.
 */
struct CameraSight {
    const world::RayCaster* scene = nullptr;
    FlatPose sensor;  ///< the camera's pose (x forward, z up)
    sim::CameraParams camera;
};

/**
 * The people a people-aware planner sees: at every camera frame, measurements from the
 * chosen source go into one Kalman track per person (kept across frames), and forecasts()
 * gives the tracks' closed-form predictions.
 */
class PeopleInput {
public:
    PeopleInput(const PeopleInputParams& params, std::uint64_t seed);

    /**
     * With people_source = ground_truth or sensed: one frame at time t, the people measured
     * from the simulator's truth as seen by the camera at `sensor` (x forward, z up). With a
     * depth view, tracks whose predicted body it sees past are missed (PeopleTracker).
     */
    void observe(double t, const std::vector<world::PersonState>& truth,
                 const world::RayCaster& scene, const FlatPose& sensor,
                 const sim::CameraParams& camera, const Eigen::Vector3d& bodySize,
                 const DepthView& view = {});

    /**
     * One frame of any source, before it goes into the map: people_source = detected finds
     * people in it (detect), ground_truth and sensed measure the frame's true people (observe;
     * sensed needs `sight`, the simulator's scene). InputError naming `sourceName` when the
     * source cannot give what the setting asks for.
     */
    void update(const Frame& frame, const mapping::ExplorationMap& map,
                const Eigen::Vector3d& bodySize, const CameraSight* sight,
                const std::string& sourceName);

    /** InputError naming `sourceName` when its frames cannot feed this people_source. */
    void checkSourceCanFeed(const Frame& first, bool hasSight, const std::string& sourceName) const;

    bool detects() const { return params_.source == PeopleSource::Detected; }
    /** Whether people are known only where the camera looks (sensed or detected). */
    bool fromCamera() const { return params_.source != PeopleSource::GroundTruth; }
    /** How far (m) the source finds people: sensed_range, the detector's max_range, or all. */
    double seeingRange() const;
    bool excludesFromMap() const { return params_.excludeFromMap; }
    /**
     * With people_source = detected: finds people in the frame seen from `robot`; call it
     * before the frame goes into the map (the detector looks for what the map contradicts).
     */
    void detect(double t, const mrpt::obs::CObservation3DRangeScan& frame, const FlatPose& robot,
                const mapping::ExplorationMap& map, const Eigen::Vector3d& bodySize);

    const std::vector<perception::PersonForecast>& forecasts() const { return forecasts_; }
    /** What the detector found in the last frame (people_source = detected). */
    const std::vector<perception::PersonMeasurement>& detections() const { return detections_; }

    /**
     * Where the people measured within the last half second stand at `t`, with a margin: the
     * depth returns the map should not take as walls. Empty unless excludeFromMap.
     */
    std::vector<mapping::PersonFootprint> mapFootprints(double t,
                                                        const Eigen::Vector3d& bodySize) const;

    /**
     * Whether the camera at `sensor` sees person `index`: some ray from it to a point of the
     * body, inside the field of view and range, hits that person first.
     */
    static bool visible(const world::RayCaster& scene, const FlatPose& sensor,
                        const sim::CameraParams& camera, double range,
                        const world::PersonState& person, const Eigen::Vector3d& bodySize,
                        int index);

private:
    void measure(double t, const std::vector<world::PersonState>& truth, const CameraSight* sight,
                 const Eigen::Vector3d& bodySize, const DepthView& view);

    PeopleInputParams params_;
    perception::PeopleTracker tracker_;
    perception::PeopleDetector detector_;
    std::mt19937_64 rng_;
    std::vector<perception::PersonForecast> forecasts_;
    std::vector<perception::PersonMeasurement> detections_;
};

}  // namespace daep::mission
