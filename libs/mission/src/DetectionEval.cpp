#include "daep/mission/DetectionEval.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <ostream>

#include "FrameStep.h"
#include "StageClock.h"
#include "daep/common/Config.h"
#include "daep/common/Error.h"
#include "daep/mapping/DepthRays.h"
#include "daep/mapping/DepthUnprojection.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/PeopleInput.h"
#include "daep/mission/RawlogSource.h"
#include "daep/world/People.h"

namespace daep::mission {
namespace {

/** A depth frame's sensor in the world and its rays. */
struct View {
    mapping::SensorFrame frame;
    mapping::DepthRays rays;

    View(const mrpt::obs::CObservation3DRangeScan& obs, const FlatPose& robot)
        : frame(mapping::sensorFrameInWorld(obs, robot)), rays(obs) {}

    Eigen::Vector3d origin() const { return frame.origin.cast<double>(); }

    /** Ray through pixel (u, v), in the image or beyond it, per metre of depth. */
    Eigen::Vector3d ray(double u, double v) const {
        return (frame.forward + rays.upAt(float(v)) * frame.up + rays.leftAt(float(u)) * frame.left)
            .cast<double>();
    }

    double horizontalDistance(const Eigen::Vector2d& p) const {
        return (p - origin().head<2>()).norm();
    }
};

/** A person's body box: centre, half extents and heading. */
struct Body {
    Eigen::Vector3d centre, half;
    double yaw = 0.0;

    /** Depth of the first hit of ray o + t d (t > 0), or -1 for a miss. */
    double hit(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
        const double c = std::cos(yaw), s = std::sin(yaw);
        const auto local = [&](const Eigen::Vector3d& w) {
            return Eigen::Vector3d(c * w.x() + s * w.y(), -s * w.x() + c * w.y(), w.z());
        };
        const Eigen::Vector3d lo = local(o - centre), ld = local(d);
        double tMin = -1e18, tMax = 1e18;
        for (int a = 0; a < 3; ++a) {
            if (std::abs(ld[a]) < 1e-12) {
                if (std::abs(lo[a]) > half[a])
                    return -1.0;
                continue;
            }
            const double t1 = (-half[a] - lo[a]) / ld[a], t2 = (half[a] - lo[a]) / ld[a];
            tMin = std::max(tMin, std::min(t1, t2));
            tMax = std::min(tMax, std::max(t1, t2));
        }
        return tMin > 0.0 && tMax >= tMin ? tMin : -1.0;
    }

    Eigen::Vector3d corner(int i) const {
        const Eigen::Vector3d sign(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
        const Eigen::Vector3d l = sign.cwiseProduct(half);
        const double c = std::cos(yaw), s = std::sin(yaw);
        return centre + Eigen::Vector3d(c * l.x() - s * l.y(), s * l.x() + c * l.y(), l.z());
    }
};

/**
 * Share of the body's projection (over an image extended past its borders) whose pixels return
 * the body itself: 1 for a fully visible person, lower when occluded or cut by the image
 * border, 0 when behind the camera.
 */
double visibleFraction(const View& view, const Body& body) {
    double uMin = 1e9, uMax = -1e9, vMin = 1e9, vMax = -1e9;
    for (int i = 0; i < 8; ++i) {
        const auto p = view.rays.project(view.frame, body.corner(i).cast<float>(), 0.05f);
        if (!p)
            return 0.0;
        uMin = std::min(uMin, p->col), uMax = std::max(uMax, p->col);
        vMin = std::min(vMin, p->row), vMax = std::max(vMax, p->row);
    }
    const int rows = view.rays.rows(), cols = view.rays.cols();
    const int step = std::max(1, cols / 160);
    const auto clampTo = [](double x, int n) { return int(std::clamp(x, -double(n), 2.0 * n)); };
    std::size_t total = 0, visible = 0;
    constexpr double kTolerance = 0.1;  // m: noise and the depth quantisation
    for (int v = clampTo(vMin, rows); v <= clampTo(vMax, rows); v += step) {
        for (int u = clampTo(uMin, cols); u <= clampTo(uMax, cols); u += step) {
            const double t = body.hit(view.origin(), view.ray(u, v));
            if (t < 0)
                continue;
            ++total;
            if (view.rays.inImage(v, u) && std::abs(view.rays.depth(v, u) - t) < kTolerance)
                ++visible;
        }
    }
    return total ? double(visible) / double(total) : 0.0;
}

/** Greedy one-to-one matching by distance (people are >= 1 m apart, the gate is smaller). */
std::vector<int> matchDetections(const std::vector<Eigen::Vector2d>& truth,
                                 const std::vector<perception::PersonMeasurement>& detections,
                                 double gate) {
    struct Pair {
        double distance;
        int truth, detection;
    };
    std::vector<Pair> pairs;
    for (std::size_t t = 0; t < truth.size(); ++t)
        for (std::size_t d = 0; d < detections.size(); ++d) {
            const double dist = (truth[t] - detections[d].position).norm();
            if (dist <= gate)
                pairs.push_back({dist, int(t), int(d)});
        }
    std::sort(pairs.begin(), pairs.end(),
              [](const Pair& a, const Pair& b) { return a.distance < b.distance; });
    std::vector<int> truthOfDetection(detections.size(), -1);
    std::vector<bool> truthUsed(truth.size(), false);
    for (const Pair& p : pairs) {
        if (truthUsed[std::size_t(p.truth)] || truthOfDetection[std::size_t(p.detection)] >= 0)
            continue;
        truthUsed[std::size_t(p.truth)] = true;
        truthOfDetection[std::size_t(p.detection)] = p.truth;
    }
    return truthOfDetection;
}

struct FrameScore {
    std::size_t eligible = 0, found = 0, detections = 0, falsePositives = 0, tracks = 0;
};

class Evaluator {
public:
    Evaluator(const ExperimentConfig& config, const DetectionEvalOptions& options,
              mapping::ExplorationMap& map, const std::string& sourceName)
        : options_(options),
          bodySize_(world::PeopleParams::fromConfig(config.config()).bodySize),
          people_(detectedPeople(config), 0),
          step_(stepParts(map, sourceName)) {}

    FrameScore scoreFrame(const Frame& frame) {
        step_.process(frame);
        const std::vector<perception::PersonMeasurement>& detections = people_.detections();
        const View view(*frame.depth, frame.robot);
        std::vector<Eigen::Vector2d> truth;
        std::vector<bool> eligible;
        FrameScore f;
        for (const world::PersonState& person : *frame.truePeople) {
            truth.push_back(person.position);
            const bool inRange = view.horizontalDistance(truth.back()) <= options_.range;
            const Body body{{person.position.x(), person.position.y(), 0.5 * bodySize_.z()},
                            0.5 * bodySize_,
                            person.heading};
            eligible.push_back(inRange &&
                               visibleFraction(view, body) >= options_.minVisibleFraction);
            score_.occludedOrTruncated += inRange && !eligible.back();
        }
        const std::vector<int> truthOf = matchDetections(truth, detections, options_.matchDistance);
        for (std::size_t d = 0; d < detections.size(); ++d) {
            const int who = truthOf[d];
            if (who >= 0 && eligible[std::size_t(who)]) {
                ++f.found;
                score_.errors.push_back((detections[d].position - truth[std::size_t(who)]).norm());
            }
            if (view.horizontalDistance(detections[d].position) > options_.range)
                continue;
            ++f.detections;
            f.falsePositives += who < 0;
        }
        f.eligible = std::size_t(std::count(eligible.begin(), eligible.end(), true));
        scoreTracks(view, frame.time, truth, f);
        add(f);
        return f;
    }

    const DetectionScore& score() const { return score_; }

private:
    void scoreTracks(const View& view, double t, const std::vector<Eigen::Vector2d>& truth,
                     FrameScore& f) {
        for (const perception::PersonForecast& track : people_.forecasts()) {
            const Eigen::Vector2d p = track.at(t).mean;
            if (view.horizontalDistance(p) > options_.range)
                continue;
            ++f.tracks;
            ++score_.confirmedTracks;
            for (const Eigen::Vector2d& q : truth)
                if ((p - q).norm() <= options_.matchDistance) {
                    ++score_.confirmedTrackMatches;
                    break;
                }
        }
    }

    void add(const FrameScore& f) {
        ++score_.frames;
        score_.eligible += f.eligible;
        score_.found += f.found;
        score_.detections += f.detections;
        score_.falsePositives += f.falsePositives;
        score_.truePositives += f.detections - f.falsePositives;
    }

    /** The [tracking] settings with the people found in the depth frames. */
    static PeopleInputParams detectedPeople(const ExperimentConfig& config) {
        PeopleInputParams p = PeopleInputParams::fromConfig(config.config());
        p.source = PeopleSource::Detected;
        return p;
    }

    /** The frame loop's step: detection against the map before the frame, then the map. */
    FrameStep::Parts stepParts(mapping::ExplorationMap& map, const std::string& sourceName) {
        FrameStep::Parts p;
        p.map = &map;
        p.stages = &stages_;
        p.people = &people_;
        p.bodySize = bodySize_;
        p.sourceName = sourceName;
        return p;
    }

    DetectionEvalOptions options_;
    Eigen::Vector3d bodySize_;
    PeopleInput people_;
    StageClock stages_;
    FrameStep step_;
    DetectionScore score_;
};

/** The map only needs a box for its dense mirror: 40 x 40 x 5 m around the first pose. */
Aabb mapBoxAround(const Eigen::Vector3d& p) {
    Aabb box;
    box.min = Eigen::Vector3d(p.x() - 20, p.y() - 20, -1);
    box.max = Eigen::Vector3d(p.x() + 20, p.y() + 20, 4);
    return box;
}

}  // namespace

DetectionScore evaluateDetection(const ExperimentConfig& config, const std::string& rawlogPath,
                                 const DetectionEvalOptions& options, std::ostream* frameCsv) {
    const ConfigReader r(config.config(), "rawlog", config.source());
    RawlogSource source(rawlogPath,
                        config.config().read_string("rawlog", "sensor_label", "", false),
                        r.requireString("pose_label"));
    Frame frame;
    if (!source.next(frame))
        throw InputError(rawlogPath + ": no depth frames");
    if (!frame.truePeople)
        throw InputError(rawlogPath +
                         ": no PERSON_<i> poses (record a dynamic run with output.rawlog = true)");
    mapping::ExplorationMap map(mapping::MapParams::fromConfig(config.config()),
                                mapBoxAround(frame.robot.position));
    Evaluator evaluator(config, options, map, source.name());
    if (frameCsv)
        *frameCsv << "t,eligible,found,detections,false_positives,confirmed_tracks\n";
    do {
        if (!frame.truePeople)
            throw InputError(rawlogPath + ": the depth frame at t = " + std::to_string(frame.time) +
                             " s has no PERSON_<i> poses");
        const FrameScore f = evaluator.scoreFrame(frame);
        if (frameCsv)
            *frameCsv << frame.time << ',' << f.eligible << ',' << f.found << ',' << f.detections
                      << ',' << f.falsePositives << ',' << f.tracks << '\n';
    } while (source.next(frame));
    return evaluator.score();
}

}  // namespace daep::mission
