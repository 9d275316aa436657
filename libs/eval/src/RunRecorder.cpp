#include "daep/eval/RunRecorder.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "daep/eval/Statistics.h"

namespace daep::eval {

std::string EndReason::text() const {
    switch (kind) {
        case Kind::None:
            return "";
        case Kind::PlannerFinished:
            return "planner finished: " + detail;
        case Kind::NoPathLimit:
            return "planner returned no path " + detail + " times in a row";
        case Kind::TimeLimit:
            return "time limit";
        case Kind::EndOfFrames:
            return "end of frames";
        case Kind::EndOfRawlog:
            return "end of rawlog";
        case Kind::Interrupted:
            return "interrupted";
        case Kind::Error:
            return "error: " + detail;
    }
    return "";
}

namespace {

std::FILE* openForWriting(const std::string& path, const char* header) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f)
        throw std::runtime_error("cannot write " + path);
    std::fputs(header, f);
    return f;
}

void closeFile(std::FILE*& f) {
    if (f)
        std::fclose(f);
    f = nullptr;
}

}  // namespace

std::string provenanceJson(const RunProvenance& run, const BuildInfo& build) {
    const auto field = [](const char* key, const std::string& json) {
        return std::string("    \"") + key + "\": " + json + ",\n";
    };
    std::string libraries;
    for (const auto& [name, version] : build.libraries)
        libraries +=
            (libraries.empty() ? "" : ", ") + jsonString(name) + ": " + jsonString(version);
    std::string out = "{\n";
    out += field("version", jsonString(build.version));
    out += field("git_commit", jsonString(build.gitCommit));
    out += field("git_dirty", build.gitDirty ? "true" : "false");
    out += field("build_type", jsonString(build.buildType));
    out += field("compiler", jsonString(build.compiler));
    out += field("sanitizers", jsonString(build.sanitizers));
    out += field("libraries", "{" + libraries + "}");
    out += field("host", jsonString(run.host));
    out += field("date_utc", jsonString(run.dateUtc));
    out += "    \"command_line\": " + jsonString(run.commandLine) + "\n  }";
    return out;
}

std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (const char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

RunRecorder::RunRecorder(const std::string& directory, PlansFormat plans) : directory_(directory) {
    std::error_code ec;
    std::filesystem::create_directories(directory_, ec);
    if (ec)
        throw std::runtime_error("cannot create output directory " + directory_ + ": " +
                                 ec.message());
    timeseries_ = openForWriting(path("timeseries.csv"),
                                 "t,coverage_percent,path_length_m,planning_time_s,collisions\n");
    trajectory_ = openForWriting(path("trajectory.csv"), "sim_time,x,y,z,yaw\n");
    trajectoryTum_ =
        openForWriting(path("trajectory_tum.txt"), "# timestamp tx ty tz qx qy qz qw\n");
    plans_ = openForWriting(path("plans.csv"),
                            plans == PlansFormat::Flight
                                ? "t,charged_s,status,gain,waypoints,reason\n"
                                : "t,x,y,z,yaw,status,gain,waypoints,wp_x,wp_y,wp_z,wp_yaw,safe,"
                                  "plan_ms\n");
}

RunRecorder::~RunRecorder() {
    closeFile(timeseries_);
    closeFile(trajectory_);
    closeFile(trajectoryTum_);
    closeFile(plans_);
}

std::string RunRecorder::path(const std::string& file) const {
    return (std::filesystem::path(directory_) / file).string();
}

void RunRecorder::addSample(const MetricsSample& s) {
    samples_.push_back(s);
    std::fprintf(timeseries_, "%.3f,%.4f,%.4f,%.4f,%d\n", s.time, s.coveragePercent, s.pathLength,
                 s.planningTime, s.collisions);
}

void RunRecorder::addPose(double time, const FlatPose& p) {
    std::fprintf(trajectory_, "%.3f,%.4f,%.4f,%.4f,%.4f\n", time, p.position.x(), p.position.y(),
                 p.position.z(), p.yaw);
    // TUM RGB-D format (evo, the TUM benchmark scripts): the yaw as a unit quaternion about z.
    std::fprintf(trajectoryTum_, "%.3f %.4f %.4f %.4f 0 0 %.6f %.6f\n", time, p.position.x(),
                 p.position.y(), p.position.z(), std::sin(p.yaw / 2), std::cos(p.yaw / 2));
}

void RunRecorder::addPlan(double time, double chargedSec, double wallSec, const std::string& status,
                          double gain, int waypoints, const std::string& reason) {
    chargedPlanTimes_.push_back(chargedSec);
    wallPlanTimes_.push_back(wallSec);
    std::string quoted;
    for (const char c : reason)
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    std::fprintf(plans_, "%.3f,%.6f,%s,%.4f,%d,\"%s\"\n", time, chargedSec, status.c_str(), gain,
                 waypoints, quoted.c_str());
}

void RunRecorder::addReplayPlan(const ReplayPlanRecord& r) {
    chargedPlanTimes_.push_back(r.wallSec);
    wallPlanTimes_.push_back(r.wallSec);
    const Eigen::Vector3d& p = r.pose.position;
    const Eigen::Vector3d& w = r.firstWaypoint.position;
    std::fprintf(plans_, "%.3f,%.4f,%.4f,%.4f,%.4f,%s,%.4f,%d,", r.time, p.x(), p.y(), p.z(),
                 r.pose.yaw, r.status.c_str(), r.gain, r.waypoints);
    if (r.waypoints > 0)
        std::fprintf(plans_, "%.4f,%.4f,%.4f,%.4f,", w.x(), w.y(), w.z(), r.firstWaypoint.yaw);
    else
        std::fputs(",,,,", plans_);
    if (r.safe >= 0)
        std::fprintf(plans_, "%d", r.safe);
    std::fprintf(plans_, ",%.3f\n", 1e3 * r.wallSec);
}

void RunRecorder::addCollision(int personIndex, double start, double end,
                               const CollisionKnowledge& knew) {
    collisions_.push_back({personIndex, start, end, knew});
}

void RunRecorder::flush() {
    std::fflush(timeseries_);
    std::fflush(trajectory_);
    std::fflush(trajectoryTum_);
    std::fflush(plans_);
}

void RunRecorder::writeSummary(const RunSummary& s) const {
    const std::string file = path("summary.json");
    std::FILE* f = std::fopen(file.c_str(), "w");
    if (!f)
        throw std::runtime_error("cannot write " + file);
    std::fprintf(f, "{\n");
    for (const auto& [key, value] : s.labels)
        std::fprintf(f, "  %s: %s,\n", jsonString(key).c_str(), jsonString(value).c_str());
    std::fprintf(f, "  \"coverage_percent\": %.4f,\n", s.coveragePercent);
    if (s.reachablePercent)
        std::fprintf(f, "  \"reachable_percent\": %.4f,\n", *s.reachablePercent);
    std::fprintf(f, "  \"exploration_time_s\": %.3f,\n", s.explorationTime);
    std::fprintf(f, "  \"path_length_m\": %.4f,\n", s.pathLength);
    std::fprintf(f, "  \"planning_time_s\": %.4f,\n", s.planningTime);
    std::fprintf(f, "  \"plan_ms_median\": %.4f,\n", s.planMsMedian);
    std::fprintf(f, "  \"plan_ms_p95\": %.4f,\n", s.planMsP95);
    std::fprintf(f, "  \"collisions\": %d,\n", s.collisions);
    std::fprintf(f, "  \"static_collisions\": %d,\n", s.staticCollisions);
    std::fprintf(f, "  \"iterations\": %d,\n", s.iterations);
    std::fprintf(f, "  \"aborted_paths\": %d,\n", s.abortedPaths);
    std::fprintf(f, "  \"hover_evasions\": %d,\n", s.hoverEvasions);
    std::fprintf(f, "  \"stale_plans\": %d,\n", s.stalePlans);
    std::fprintf(f, "  \"finished\": %s,\n", s.finished ? "true" : "false");
    std::fprintf(f, "  \"end_reason\": %s,\n", jsonString(s.endReason.text()).c_str());
    std::fprintf(f, "  \"known_volume_m3\": %.4f,\n", s.knownVolume);
    std::fprintf(f, "  \"box_volume_m3\": %.4f,\n", s.boxVolume);
    std::fprintf(f, "  \"exploration_start_s\": %.3f,\n", s.explorationStart);
    std::fprintf(f, "  \"wall_time_s\": %.3f,\n", s.wallTime);
    std::fprintf(f, "  \"provenance\": %s\n}\n", provenanceJson(s.provenance).c_str());
    std::fclose(f);
}

void RunRecorder::writeTiming(double wallTimeSec, double simTimeSec,
                              const std::vector<std::pair<std::string, double>>& stages) const {
    const std::string file = path("timing.json");
    std::FILE* f = std::fopen(file.c_str(), "w");
    if (!f)
        throw std::runtime_error("cannot write " + file);
    std::vector<double> ms;
    ms.reserve(wallPlanTimes_.size());
    for (double s : wallPlanTimes_)
        ms.push_back(1e3 * s);
    std::fprintf(f, "{\n");
    std::fprintf(f, "  \"plan_calls\": %zu,\n", ms.size());
    std::fprintf(f, "  \"plan_wall_ms_median\": %.4f,\n", median(ms));
    std::fprintf(f, "  \"plan_wall_ms_p95\": %.4f,\n", percentile(ms, 95));
    std::fprintf(f, "  \"plan_wall_ms_max\": %.4f,\n", percentile(ms, 100));
    std::fprintf(f, "  \"wall_time_s\": %.3f,\n", wallTimeSec);
    std::fprintf(f, "  \"simulated_time_s\": %.3f,\n", simTimeSec);
    std::fprintf(f, "  \"speedup_vs_real_time\": %.2f%s\n",
                 wallTimeSec > 0 ? simTimeSec / wallTimeSec : 0.0, stages.empty() ? "" : ",");
    if (!stages.empty()) {
        std::fprintf(f, "  \"wall_time_by_stage_s\": {");
        for (std::size_t i = 0; i < stages.size(); ++i)
            std::fprintf(f, "%s\"%s\": %.3f", i == 0 ? "" : ", ", stages[i].first.c_str(),
                         stages[i].second);
        std::fprintf(f, "}\n");
    }
    std::fprintf(f, "}\n");
    std::fclose(f);
}

void RunRecorder::writeCollisions() const {
    std::FILE* f =
        openForWriting(path("collisions.csv"),
                       "person,start_s,end_s,tracked,unseen_watch,tracked_for_s,untracked_for_s\n");
    const auto seconds = [f](const std::optional<double>& s) {
        if (s)
            std::fprintf(f, ",%.1f", *s);
        else
            std::fputs(",-", f);
    };
    for (const auto& c : collisions_) {
        std::fprintf(f, "%d,%.3f,%.3f,%d,%s", c.person, c.start, c.end, c.knew.tracked,
                     c.knew.unseenWatch.c_str());
        seconds(c.knew.trackedFor);
        seconds(c.knew.untrackedFor);
        std::fputc('\n', f);
    }
    std::fclose(f);
}

}  // namespace daep::eval
