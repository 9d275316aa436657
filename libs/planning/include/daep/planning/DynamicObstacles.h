#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

#include "daep/common/Types.h"
#include "daep/perception/PersonTrack.h"
#include "daep/planning/GainEvaluator.h"

namespace daep::planning {

/** How people's predicted bodies are kept away from the drone. */
struct SafetyParams {
    Eigen::Vector3d droneSize{0.4, 0.4, 0.1};
    Eigen::Vector3d personSize{1.0, 1.0, 1.8};  ///< a box standing on z = 0
    double clearance = 0.2;                     ///< free gap kept between drone and body, m
    double sigmaInflation = 2.0;  ///< bodies grow by this many predicted standard deviations...
    double maxInflation = 1.0;    ///< ...but never by more than this, m
    double horizon = 10.0;        ///< predictions beyond this (s from their state) are not used
    double timeStep = 0.2;        ///< sampling step of swept checks, s (made conservative)
    /**
     * Highest drone centre the flight space allows, m. Where it is below the top of the
     * grown bodies the drone cannot climb over people, so the gap below their top is the
     * horizontal one alone.
     */
    double ceiling = std::numeric_limits<double>::infinity();
    /** Free gap kept over a body's top, m; unset: `clearance`. */
    std::optional<double> overheadClearance;

    /** Drone centres below this can touch a body: its top plus half the drone. */
    double bodyTop() const { return personSize.z() + 0.5 * droneSize.z(); }
};

/** A drone move as the simulator flies it: turn on the spot at `from`, then fly to `to`. */
struct TimedSegment {
    Eigen::Vector3d from = Eigen::Vector3d::Zero();
    Eigen::Vector3d to = Eigen::Vector3d::Zero();
    double start = 0.0;     ///< absolute time the segment starts (turn begins)
    double turnTime = 0.0;  ///< s spent turning at `from`
    double flyTime = 0.0;   ///< s spent flying from `from` to `to`
    double end() const { return start + turnTime + flyTime; }
    Eigen::Vector3d positionAt(double t) const;
    /** The rest of the move from time t on (clamped to the move). */
    TimedSegment after(double t) const;
};

/** The segment a drone with `motion`-like limits flies from pose a to pose b from `start`. */
TimedSegment timedSegment(const FlatPose& a, const FlatPose& b, double start, double speed,
                          double yawRate);

/**
 * People as the planner sees them: closed-form forecasts with growing covariance. Answers
 * whether a timed drone move keeps clear of every predicted body (checked along the whole
 * move, not at its end only) and where the bodies will stand at a given time.
 *
 * A body is the disc circumscribing the person's footprint, grown by the drone's half
 * diagonal, the clearance and k predicted standard deviations (largest axis, capped); it spans
 * z in [0, person height + drone half height + clearance]. Samples every timeStep add the
 * largest distance drone and body can close in half a step, so the sampled check is
 * conservative for the continuous motion.
 */
class DynamicObstacles {
public:
    DynamicObstacles() = default;
    DynamicObstacles(const SafetyParams& params, std::vector<perception::PersonForecast> people);

    bool empty() const { return people_.empty(); }
    std::size_t size() const { return people_.size(); }
    const SafetyParams& params() const { return params_; }
    const std::vector<perception::PersonForecast>& people() const { return people_; }

    /**
     * Smallest gap (m, negative inside) between the drone and any grown body along the move.
     * Inside a body's footprint and below its top, the gap is the shorter way out, sideways
     * or up; up only where the ceiling lets the drone rise above the body.
     */
    double clearance(const TimedSegment& move, double clearanceScale = 1.0) const;

    /** clearance(move) > 0. */
    bool isSafe(const TimedSegment& move, double clearanceScale = 1.0) const;

    /** Hovering at p over [t0, t1]. */
    bool isSafeToHover(const Eigen::Vector3d& p, double t0, double t1) const;

    /** Predicted bodies (mean positions, no inflation) at time t, within the horizon. */
    std::vector<BodyOccluder> bodiesAt(double t) const;

    /** Drone centres at or above this height keep the clearance over every body. */
    double clearedHeight(double clearanceScale = 1.0) const {
        return bodyTop_ + clearanceScale * params_.overheadClearance.value_or(params_.clearance);
    }
    /** Centre distance kept from a body known exactly: body + drone + clearance. */
    double bodyKeepOut(double clearanceScale = 1.0) const {
        return bodyRadius_ + clearanceScale * params_.clearance;
    }
    /** Required centre distance for person i at time t (body + drone + clearance + k sigma). */
    double keepOutRadius(const perception::PersonForecast& person, double t,
                         double clearanceScale) const;

private:
    double keepOutRadius(const perception::PositionPrediction& at, double clearanceScale) const;
    /** When a move and a person's forecast overlap in time, and how fast they can close in. */
    struct Encounter {
        double t0 = 0.0, t1 = 0.0;  ///< the overlap, absolute s
        double closing = 0.0;       ///< drone speed + walker speed, m/s
    };
    std::optional<Encounter> encounter(const perception::PersonForecast& person,
                                       const TimedSegment& move) const;
    double gapTo(const perception::PersonForecast& person, const TimedSegment& move,
                 double clearanceScale) const;
    double gapDuring(const perception::PersonForecast& person, const TimedSegment& move,
                     const Encounter& e, double clearanceScale) const;
    /** gapTo(person, move) <= 0, faster for walkers far from the move. */
    bool blocks(const perception::PersonForecast& person, const TimedSegment& move,
                double clearanceScale) const;

    SafetyParams params_;
    std::vector<perception::PersonForecast> people_;
    double bodyRadius_ = 0.0;              ///< person footprint half diagonal + drone half diagonal
    double bodyTop_ = 0.0;                 ///< drone centres below this can touch a body
    mutable std::size_t lastBlocker_ = 0;  ///< isSafe's first walker to ask (one thread)
};

}  // namespace daep::planning
