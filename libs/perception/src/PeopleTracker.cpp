#include "daep/perception/PeopleTracker.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/mapping/DepthRays.h"
#include "daep/mapping/DepthUnprojection.h"
#include "daep/perception/Assignment.h"

namespace daep::perception {
namespace {

/**
 * Frame times replayed from a rawlog are the simulator's rounded to MRPT's 0.1 us clock ticks,
 * so a span of whole frames can come out a hair either side of a threshold: spans are compared
 * with this slack, and a threshold met at a frame is met on either clock.
 */
constexpr double kClockSlack = 1e-6;

/** The span has lasted `limit` (at a frame exactly `limit` later, too). */
bool spanReaches(double span, double limit) {
    return span >= limit - kClockSlack;
}

/** The span has lasted longer than `limit` (not yet at a frame exactly `limit` later). */
bool spanExceeds(double span, double limit) {
    return span > limit + kClockSlack;
}

/** Cost of a pair outside the gate: larger than any sum of gated costs, so never preferred. */
constexpr double kOutsideGate = 1e9;

struct Innovation {
    double mahalanobis2 = 0.0;
    double logDet = 0.0;
};

Innovation innovation(const PersonTrack& track, double time, const PersonMeasurement& m) {
    const PositionPrediction p = track.predict(std::max(time, track.lastUpdate()));
    const Eigen::Matrix2d s = p.covariance + m.covariance;
    const Eigen::Vector2d r = m.position - p.mean;
    return {r.dot(s.ldlt().solve(r)), std::log(s.determinant())};
}

}  // namespace

PeopleTracker::PeopleTracker(const TrackerParams& params) : params_(params) {
    if (params.dropAfter <= 0)
        throw std::invalid_argument("PeopleTracker: dropAfter must be positive");
    if (!(params.gateChi2 > 0) || params.confirmHits < 1 || !(params.tentativeDropAfter > 0))
        throw std::invalid_argument(
            "PeopleTracker: gateChi2, confirmHits and tentativeDropAfter must be positive");
    if (!(params.staticAfter >= 0) || !(params.staticRadius > 0) || !(params.staticMemory >= 0))
        throw std::invalid_argument(
            "PeopleTracker: staticAfter and staticMemory must be >= 0, staticRadius positive");
}

PeopleTracker::Track* PeopleTracker::findById(int id) {
    for (Track& t : tracks_)
        if (t.id == id)
            return &t;
    return nullptr;
}

void PeopleTracker::updateOrStart(double time, int id, const PersonMeasurement& m) {
    if (Track* t = findById(id)) {
        t->filter.update(time, m.position, m.covariance);
        t->lastSeen = time;
        t->missesInView = 0;
        ++t->hits;
        return;
    }
    tracks_.push_back({id, PersonTrack(params_.predictor, time, m.position), time, 1, false});
}

/** A new track starts with the measurement's own position uncertainty. */
void PeopleTracker::startAnonymous(double time, const PersonMeasurement& m) {
    PredictorParams p = params_.predictor;
    p.measurementSigma = std::sqrt(std::max(0.5 * m.covariance.trace(), 1e-12));
    Track t{nextAnonymousId_++, PersonTrack(p, time, m.position), time, 1, true};
    t.stillAt = m.position;
    t.stillSince = time;
    tracks_.push_back(std::move(t));
}

void PeopleTracker::noteStill(Track& t, double time, const Eigen::Vector2d& m) {
    if ((m - t.stillAt).norm() > params_.staticRadius) {
        t.stillAt = m;
        t.stillSince = time;
    }
}

void PeopleTracker::forgetOldClutter(double time) {
    clutter_.erase(std::remove_if(clutter_.begin(), clutter_.end(),
                                  [&](const ClutterSpot& s) {
                                      return spanExceeds(time - s.time, params_.staticMemory);
                                  }),
                   clutter_.end());
}

void PeopleTracker::dropStaticClutter(double time) {
    if (!(params_.staticAfter > 0))
        return;
    tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                                 [&](const Track& t) {
                                     // Measured at one spot all along, and predicted to
                                     // stay there (a walker out of view is predicted on).
                                     if (!t.anonymous ||
                                         !spanReaches(time - t.stillSince, params_.staticAfter) ||
                                         (t.filter.predict(time).mean - t.stillAt).norm() >
                                             params_.staticRadius)
                                         return false;
                                     clutter_.push_back({t.stillAt, time});
                                     ++staticDropped_;
                                     return true;
                                 }),
                  tracks_.end());
}

bool PeopleTracker::inClutter(const Eigen::Vector2d& p) const {
    for (const ClutterSpot& s : clutter_)
        if ((p - s.position).norm() <= params_.staticRadius)
            return true;
    return false;
}

void PeopleTracker::associateAnonymous(double time,
                                       const std::vector<PersonMeasurement>& anonymous) {
    std::vector<Track*> candidates;
    for (Track& t : tracks_)
        if (t.anonymous)
            candidates.push_back(&t);
    Eigen::MatrixXd cost(candidates.size(), anonymous.size());
    std::vector<bool> nearConfirmed(anonymous.size(), false);
    for (std::size_t r = 0; r < candidates.size(); ++r) {
        for (std::size_t c = 0; c < anonymous.size(); ++c) {
            const Innovation in = innovation(candidates[r]->filter, time, anonymous[c]);
            const bool gated = in.mahalanobis2 <= params_.gateChi2;
            cost(r, c) = gated ? in.mahalanobis2 + in.logDet : kOutsideGate;
            if (gated && confirmed(*candidates[r]))
                nearConfirmed[c] = true;
        }
    }
    const std::vector<int> columnOfRow = solveAssignment(cost);
    std::vector<bool> used(anonymous.size(), false);
    for (std::size_t r = 0; r < candidates.size(); ++r) {
        const int c = columnOfRow[r];
        if (c < 0 || cost(r, c) >= kOutsideGate)
            continue;
        Track& t = *candidates[r];
        const PersonMeasurement& m = anonymous[std::size_t(c)];
        t.filter.update(time, m.position, m.covariance);
        t.lastSeen = time;
        t.missesInView = 0;
        ++t.hits;
        noteStill(t, time, m.position);
        used[std::size_t(c)] = true;
    }
    for (std::size_t c = 0; c < anonymous.size(); ++c)
        if (!used[c] && !nearConfirmed[c])
            startAnonymous(time, anonymous[c]);
}

void PeopleTracker::update(double time, const std::vector<PersonMeasurement>& measurements,
                           const EmptyTest& seenEmpty) {
    forgetOldClutter(time);
    std::vector<PersonMeasurement> anonymous;
    for (const PersonMeasurement& m : measurements) {
        if (m.id >= 0)
            updateOrStart(time, m.id, m);
        else if (!inClutter(m.position))
            anonymous.push_back(m);
    }
    if (!anonymous.empty())
        associateAnonymous(time, anonymous);
    dropStaticClutter(time);
    if (seenEmpty)
        countMisses(time, seenEmpty);
    dropStale(time);
}

void PeopleTracker::countMisses(double time, const EmptyTest& seenEmpty) {
    for (Track& t : tracks_)
        if (confirmed(t) && t.lastSeen < time)
            t.missesInView = seenEmpty(t.filter.predict(time).mean) ? t.missesInView + 1 : 0;
    tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                                 [&](const Track& t) {
                                     return t.missesInView >= params_.dropAfterMissesInView;
                                 }),
                  tracks_.end());
}

void PeopleTracker::dropStale(double time) {
    tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                                 [&](const Track& t) {
                                     const double limit = confirmed(t) ? params_.dropAfter
                                                                       : params_.tentativeDropAfter;
                                     return spanExceeds(time - t.lastSeen, limit);
                                 }),
                  tracks_.end());
}

std::vector<PersonForecast> PeopleTracker::forecasts() const {
    std::vector<PersonForecast> out;
    out.reserve(tracks_.size());
    for (const Track& t : tracks_)
        if (confirmed(t))
            out.push_back(t.filter.forecast(t.id));
    return out;
}

std::vector<PersonForecast> PeopleTracker::tentativeForecasts() const {
    std::vector<PersonForecast> out;
    for (const Track& t : tracks_)
        if (!confirmed(t))
            out.push_back(t.filter.forecast(t.id));
    return out;
}

std::vector<TrackInfo> PeopleTracker::tracks() const {
    std::vector<TrackInfo> out;
    out.reserve(tracks_.size());
    for (const Track& t : tracks_)
        out.push_back({t.filter.forecast(t.id), t.hits, confirmed(t), t.lastSeen});
    return out;
}

std::size_t PeopleTracker::confirmedCount() const {
    return std::size_t(std::count_if(tracks_.begin(), tracks_.end(),
                                     [this](const Track& t) { return confirmed(t); }));
}

PeopleTracker::EmptyTest seenEmptyIn(const mrpt::obs::CObservation3DRangeScan* observation,
                                     const FlatPose& robot, const Eigen::Vector3d& bodySize) {
    if (observation == nullptr)
        return {};
    const mapping::SensorFrame sensor = mapping::sensorFrameInWorld(*observation, robot);
    const mrpt::obs::CObservation3DRangeScan& frame = *observation;
    const auto rays = std::make_shared<const mapping::DepthRays>(frame);
    return [&frame, rays, sensor, bodySize](const Eigen::Vector2d& xy) {
        const Eigen::Vector3f middle(float(xy.x()), float(xy.y()), float(0.5 * bodySize.z()));
        Eigen::Vector3f across = sensor.up.cross(middle - sensor.origin);
        across = across.norm() > 1e-6f ? across.normalized() : sensor.left;
        const float half = float(0.3 * bodySize.x());
        for (const float side : {-half, 0.0f, half})
            if (!mapping::seesPast(*rays, frame, sensor, middle + side * across, float(0.1)))
                return false;
        return true;
    };
}

TrackerParams TrackerParams::fromConfig(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "tracker");
    TrackerParams p;
    p.predictor.accelNoise = requireNonNegative(r, "accel_noise");
    p.predictor.measurementSigma = requirePositive(r, "measurement_sigma");
    p.predictor.initialSpeedSigma = requirePositive(r, "initial_speed_sigma");
    p.dropAfter = requirePositive(r, "drop_after_s");
    p.dropAfterMissesInView = requireIntAtLeast(r, "drop_after_misses_in_view", 1);
    p.gateChi2 = requirePositive(r, "gate_chi2");
    p.confirmHits = requireIntAtLeast(r, "confirm_hits", 1);
    p.tentativeDropAfter = requirePositive(r, "tentative_drop_after_s");
    p.staticAfter = requireNonNegative(r, "static_after_s");
    p.staticRadius = requirePositive(r, "static_radius");
    p.staticMemory = requireNonNegative(r, "static_memory_s");
    return p;
}

}  // namespace daep::perception
