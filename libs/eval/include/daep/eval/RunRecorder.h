#pragma once

#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "daep/common/BuildInfo.h"
#include "daep/common/Types.h"

namespace daep::eval {

/** One sample of the metrics over time (timeseries.csv). */
struct MetricsSample {
    double time = 0.0;  ///< exploration time, s
    double coveragePercent = 0.0;
    double pathLength = 0.0;
    double planningTime = 0.0;
    int collisions = 0;
};

/** What the planner knew of the person in a collision as it began (collisions.csv). */
struct CollisionKnowledge {
    int tracked = -1;  ///< 1 / 0: a track lay on the person; -1: the planner ignores people
    /** With a track on them: how long tracks had lain on them without a break, s. */
    std::optional<double> trackedFor;
    /** Without: how long since a track last lay on them, s (none: never in this run). */
    std::optional<double> untrackedFor;
    /** What the planner's watch over people it has not seen held there ("-": no watch). */
    std::string unseenWatch = "-";
};

/** Why a run ended; summary.json's end_reason is its text(). */
struct EndReason {
    enum class Kind {
        None,             ///< not ended (yet)
        PlannerFinished,  ///< the planner judged the exploration complete (detail: its reason)
        NoPathLimit,      ///< max_failed_plans plans in a row had no path (detail: how many)
        TimeLimit,
        EndOfFrames,  ///< an open-loop source ran out of frames
        EndOfRawlog,
        Interrupted,  ///< Ctrl-C or a stop request
        Error,        ///< an exception ended the loop (detail: its one-line text)
    };
    Kind kind = Kind::None;
    std::string detail;

    static EndReason plannerFinished(std::string why) {
        return {Kind::PlannerFinished, std::move(why)};
    }
    static EndReason noPathLimit(int plans) { return {Kind::NoPathLimit, std::to_string(plans)}; }
    static EndReason error(std::string text) { return {Kind::Error, std::move(text)}; }
    static EndReason of(Kind kind) { return {kind, {}}; }

    std::string text() const;
};

/** The final figures of a run (summary.json). */
struct RunSummary {
    double coveragePercent = 0.0;
    /** The most coverage the world and start allow (daep::world::computeReachableVolume);
     * unset for rawlog replays, and then not written. */
    std::optional<double> reachablePercent;
    double explorationTime = 0.0;
    double pathLength = 0.0;
    double planningTime = 0.0;  ///< total, as charged to the simulated clock
    double planMsMedian = 0.0;  ///< per call, as charged to the simulated clock
    double planMsP95 = 0.0;
    int collisions = 0;
    int staticCollisions = 0;
    int iterations = 0;
    int abortedPaths = 0;   ///< paths the planner stopped in flight (re-plans)
    int hoverEvasions = 0;  ///< escapes flown while hovering (planning or waiting)
    int stalePlans = 0;     ///< plans dropped: unsafe against the frames taken while made
    bool finished = false;
    double wallTime = 0.0;
    double knownVolume = 0.0;
    double boxVolume = 0.0;
    double explorationStart = 0.0;  ///< simulated time since spawn when exploration began
    EndReason endReason;
    /** Run identification (world, mode, planner, start, seed): written as strings. */
    std::map<std::string, std::string> labels;
    /** Host, date and command line of the run; with buildInfo() it makes the "provenance" block. */
    RunProvenance provenance;
};

/** One planner call on recorded data (source = rawlog): where from, and what it would fly. */
struct ReplayPlanRecord {
    double time = 0.0;  ///< rawlog time since the first depth frame, s
    FlatPose pose;      ///< the robot pose the planner planned from
    std::string status;
    double gain = 0.0;
    int waypoints = 0;
    FlatPose firstWaypoint;  ///< meaningful when waypoints > 0
    int safe = -1;           ///< keepFlying() on the plan from `pose`: 1, 0, or -1 (no path)
    double wallSec = 0.0;    ///< the planner's real time
};

/** Columns of plans.csv: a simulated flight's, or a rawlog replay's. */
enum class PlansFormat { Flight, Replay };

/**
 * Streams a run's records to DIR as they happen (so an interrupted run keeps what it had):
 * timeseries.csv, trajectory.csv (and trajectory_tum.txt, the same poses in the TUM format) and
 * plans.csv; writes summary.json and timing.json at the end.
 * Numbers are printed with fixed precision so equal runs give byte-identical files.
 */
class RunRecorder {
public:
    /** Creates DIR (and parents); throws std::runtime_error naming the path on failure. */
    explicit RunRecorder(const std::string& directory, PlansFormat plans = PlansFormat::Flight);
    ~RunRecorder();

    const std::string& directory() const { return directory_; }
    std::string path(const std::string& file) const;

    void addSample(const MetricsSample& sample);
    /** A drone pose at simulated time since spawn (take-off included). */
    void addPose(double simTime, const FlatPose& pose);
    /** One planner call: when, how long it was charged, its real duration, its outcome. */
    void addPlan(double time, double chargedSec, double wallSec, const std::string& status,
                 double gain, int waypoints, const std::string& reason = "");
    /** One planner call of a replay (PlansFormat::Replay); its real time counts as charged. */
    void addReplayPlan(const ReplayPlanRecord& plan);
    /** One collision episode, and what the planner knew of that person as it began. */
    void addCollision(int personIndex, double start, double end,
                      const CollisionKnowledge& knew = {});

    const std::vector<MetricsSample>& samples() const { return samples_; }
    const std::vector<double>& chargedPlanTimes() const { return chargedPlanTimes_; }
    const std::vector<double>& wallPlanTimes() const { return wallPlanTimes_; }

    void writeSummary(const RunSummary& summary) const;
    /**
     * Real planner durations and, when given, the wall time per stage of the run (not
     * deterministic, so kept apart from summary.json).
     */
    void writeTiming(double wallTimeSec, double simTimeSec,
                     const std::vector<std::pair<std::string, double>>& stages = {}) const;
    void writeCollisions() const;

    /** Flushes the streams (called by the mission after each plan). */
    void flush();

private:
    struct Collision {
        int person;
        double start, end;
        CollisionKnowledge knew;
    };
    std::string directory_;
    std::FILE* timeseries_ = nullptr;
    std::FILE* trajectory_ = nullptr;
    std::FILE* trajectoryTum_ = nullptr;  ///< trajectory_tum.txt: the same poses, TUM format
    std::FILE* plans_ = nullptr;
    std::vector<MetricsSample> samples_;
    std::vector<double> chargedPlanTimes_;
    std::vector<double> wallPlanTimes_;
    std::vector<Collision> collisions_;
};

/**
 * summary.json's "provenance" object (indented for its place there): the build (version, git
 * commit and dirty flag, build type, compiler, sanitizers, library versions) and the run (host,
 * UTC date, command line).
 */
std::string provenanceJson(const RunProvenance& run, const BuildInfo& build = buildInfo());

/** Writes a JSON string literal with escapes. */
std::string jsonString(const std::string& s);

}  // namespace daep::eval
