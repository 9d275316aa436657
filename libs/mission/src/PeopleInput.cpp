#include "daep/mission/PeopleInput.h"

#include <cmath>
#include <limits>
#include <memory>

#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/perception/PeopleDetector.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/world/RayCaster.h"

namespace daep::mission {
namespace {

/** Points of a body a camera may see: three heights, across the body as seen from the camera. */
std::vector<Eigen::Vector3d> bodySamples(const world::PersonState& person,
                                         const Eigen::Vector3d& bodySize,
                                         const Eigen::Vector3d& camera) {
    Eigen::Vector2d across = (person.position - camera.head<2>());
    across = across.norm() > 1e-6 ? Eigen::Vector2d(-across.y(), across.x()).normalized()
                                  : Eigen::Vector2d(1, 0);
    std::vector<Eigen::Vector3d> points;
    for (const double h : {0.25, 0.5, 0.8})
        for (const double side : {-0.3, 0.0, 0.3}) {
            const Eigen::Vector2d xy = person.position + side * bodySize.x() * across;
            points.emplace_back(xy.x(), xy.y(), h * bodySize.z());
        }
    return points;
}

}  // namespace

const char* peopleSourceName(PeopleSource source) {
    switch (source) {
        case PeopleSource::GroundTruth:
            return "ground_truth";
        case PeopleSource::Sensed:
            return "sensed";
        case PeopleSource::Detected:
            return "detected";
    }
    return "?";
}

PeopleInputParams PeopleInputParams::fromConfig(const mrpt::config::CConfigFileBase& config) {
    const ConfigReader r(config, "tracking");
    PeopleInputParams p;
    p.source = requireEnum<PeopleSource>(r, "people_source",
                                         {{"ground_truth", PeopleSource::GroundTruth},
                                          {"sensed", PeopleSource::Sensed},
                                          {"detected", PeopleSource::Detected}});
    p.sensedRange = requirePositive(r, "sensed_range");
    p.sensedNoiseSigma = requireNonNegative(r, "sensed_noise_sigma");
    p.excludeFromMap = r.requireBool("exclude_from_map");
    p.tracker = perception::TrackerParams::fromConfig(config);
    p.detector = perception::DetectorParams::fromConfig(config);
    return p;
}

namespace {

/** A track is still where the depth frame sees its person this long after its measurement (s). */
constexpr double kFootprintFreshness = 0.5;
/** Room around the body for the track's error and the body's turn (m). */
constexpr double kFootprintMargin = 0.2;

}  // namespace

std::vector<mapping::PersonFootprint> PeopleInput::mapFootprints(
    double t, const Eigen::Vector3d& bodySize) const {
    std::vector<mapping::PersonFootprint> out;
    if (!params_.excludeFromMap)
        return out;
    const float radius = float(0.5 * bodySize.head<2>().norm() + kFootprintMargin);
    for (const perception::PersonForecast& f : forecasts_) {
        if (t - f.time > kFootprintFreshness)
            continue;
        mapping::PersonFootprint p;
        p.centre = f.at(t).mean.cast<float>();
        p.radius = radius;
        p.top = float(bodySize.z() + kFootprintMargin);
        out.push_back(p);
    }
    return out;
}

PeopleInput::PeopleInput(const PeopleInputParams& params, std::uint64_t seed)
    : params_(params), tracker_(params.tracker), detector_(params.detector), rng_(seed) {}

void PeopleInput::detect(double t, const mrpt::obs::CObservation3DRangeScan& frame,
                         const FlatPose& robot, const mapping::ExplorationMap& map,
                         const Eigen::Vector3d& bodySize) {
    detections_ = detector_.detect(frame, robot, map);
    tracker_.update(t, detections_, perception::seenEmptyIn(&frame, robot, bodySize));
    forecasts_ = tracker_.forecasts();
}

double PeopleInput::seeingRange() const {
    switch (params_.source) {
        case PeopleSource::Sensed:
            return params_.sensedRange;
        case PeopleSource::Detected:
            return params_.detector.maxRange;
        case PeopleSource::GroundTruth:
            break;
    }
    return std::numeric_limits<double>::infinity();
}

bool PeopleInput::visible(const world::RayCaster& scene, const FlatPose& sensor,
                          const sim::CameraParams& camera, double range,
                          const world::PersonState& person, const Eigen::Vector3d& bodySize,
                          int index) {
    const double c = std::cos(sensor.yaw), s = std::sin(sensor.yaw);
    for (const Eigen::Vector3d& p : bodySamples(person, bodySize, sensor.position)) {
        const Eigen::Vector3d d = p - sensor.position;
        const double distance = d.norm();
        const double forward = c * d.x() + s * d.y();
        const double left = -s * d.x() + c * d.y();
        if (distance > range || forward <= 0.0 ||
            std::abs(std::atan2(left, forward)) > 0.5 * camera.hfovRad ||
            std::abs(std::atan2(d.z(), forward)) > 0.5 * camera.vfovRad())
            continue;
        const Eigen::Vector3f dir = (d / distance).cast<float>();
        if (scene.firstPersonHit(sensor.position.cast<float>(), dir,
                                 static_cast<float>(distance + 1.0)) == index)
            return true;
    }
    return false;
}

void PeopleInput::observe(double t, const std::vector<world::PersonState>& truth,
                          const world::RayCaster& scene, const FlatPose& sensor,
                          const sim::CameraParams& camera, const Eigen::Vector3d& bodySize,
                          const DepthView& view) {
    const CameraSight sight{&scene, sensor, camera};
    measure(t, truth, &sight, bodySize, view);
}

void PeopleInput::checkSourceCanFeed(const Frame& first, bool hasSight,
                                     const std::string& sourceName) const {
    if (detects())
        return;
    if (params_.source == PeopleSource::Sensed && !hasSight)
        throw InputError(sourceName +
                         ": [tracking] people_source = sensed needs the simulator's scene; "
                         "recorded frames can give detected or ground_truth");
    if (!first.truePeople)
        throw InputError(sourceName +
                         ": [tracking] people_source = " + peopleSourceName(params_.source) +
                         " needs the true people (PERSON_<i> poses), and the frames have none; "
                         "use people_source = detected");
}

void PeopleInput::update(const Frame& frame, const mapping::ExplorationMap& map,
                         const Eigen::Vector3d& bodySize, const CameraSight* sight,
                         const std::string& sourceName) {
    if (detects()) {
        detect(frame.time, *frame.depth, frame.robot, map, bodySize);
        return;
    }
    checkSourceCanFeed(frame, sight != nullptr, sourceName);
    measure(frame.time, *frame.truePeople, sight, bodySize, {frame.depth.get(), frame.robot});
}

void PeopleInput::measure(double t, const std::vector<world::PersonState>& truth,
                          const CameraSight* sight, const Eigen::Vector3d& bodySize,
                          const DepthView& view) {
    std::vector<perception::PersonMeasurement> seen;
    const bool sensed = params_.source == PeopleSource::Sensed;
    const double sigma = sensed ? params_.sensedNoiseSigma : 0.0;
    const double r = std::max(sigma, params_.tracker.predictor.measurementSigma);
    std::normal_distribution<double> noise(0.0, 1.0);
    for (std::size_t i = 0; i < truth.size(); ++i) {
        const int id = static_cast<int>(i);
        if (sensed && !visible(*sight->scene, sight->sensor, sight->camera, params_.sensedRange,
                               truth[i], bodySize, id))
            continue;
        perception::PersonMeasurement m;
        m.id = id;
        m.position = truth[i].position;
        if (sigma > 0)
            m.position += sigma * Eigen::Vector2d(noise(rng_), noise(rng_));
        m.covariance = Eigen::Matrix2d::Identity() * r * r;
        seen.push_back(m);
    }
    tracker_.update(t, seen, perception::seenEmptyIn(view.frame, view.robot, bodySize));
    forecasts_ = tracker_.forecasts();
}

}  // namespace daep::mission
