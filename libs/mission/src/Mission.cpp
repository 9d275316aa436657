#include "daep/mission/Mission.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>

#include <octomap/OcTree.h>

#include "FlightLoop.h"
#include "MemoryLog.h"
#include "MissionCore.h"
#include "PeopleCsv.h"
#include "SimulatorSource.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"

namespace daep::mission {
namespace {

constexpr double kEps = 1e-9;

}  // namespace

struct Mission::Impl : FlightLoop::Mission {
    Impl(const ExperimentConfig& config, const std::string& outputDir, std::ostream* logStream)
        : configForReach(&config.config()),
          sim(config, &stages),
          core(config, coreUse(), stages, outputDir, logStream),
          memory(core.recorder.path("memory.csv"), core.outputs.memoryEvery) {
        nextScene = core.outputs.sceneEvery;
        if (core.peopleCsv && !sim.world().people.empty())
            peopleTruth = std::make_unique<PeopleTruthCsv>(core.recorder.path("people_truth.csv"));
    }

    MissionCore::Use coreUse() const {
        MissionCore::Use use;
        use.explorationBox = sim.world().explorationBox;
        use.explorationVolume = sim.world().explorationVolume();
        use.framesMayShowPeople = !sim.world().people.empty();
        use.sourceName = sim.name();
        return use;
    }

    const Settings& settings() const { return core.settings; }

    double now() const { return sim.time(); }
    bool exploring() const { return exploreStart >= 0; }
    double explorationTime() const { return exploring() ? now() - exploreStart : 0.0; }
    bool timeUp() const { return exploring() && explorationTime() >= settings().maxTime - kEps; }

    bool stopping() const override { return timeUp() || (stopFlag && *stopFlag); }

    double stepLimit(double end) const override {
        const double limit = end - now();
        return exploring() ? std::min(limit, settings().maxTime - explorationTime()) : limit;
    }

    void stepped(const SimulatorSource::Step& step, bool flying) override {
        if (flying && exploring())
            pathLength += step.moved;
        const auto& events = sim.monitor().events();
        while (collisionsBegun.size() < events.size())
            collisionsBegun.push_back(atCollision(events[collisionsBegun.size()].personIndex));
    }

    /** The people's true positions (with people.csv), and the scene when one is due. */
    void frameProcessed() override {
        noteTracked();
        if (peopleTruth)
            peopleTruth->write(now(), sim.people().states());
        if (core.outputs.scene && core.outputs.sceneEvery > 0 && now() + kEps >= nextScene) {
            core.scene.write(sceneContent());
            nextScene += core.outputs.sceneEvery;
        }
    }

    SceneContent sceneContent() const {
        SceneContent c = core.sceneBase();
        c.people = sim.people().states();
        c.drone = sim.drone().pose();
        return c;
    }

    void recordDue() override {
        if (!exploring())
            return;
        core.recordDueSamples(explorationTime(), pathLength, sim.monitor().personCollisions(), [&] {
            std::ostringstream o;
            o << std::fixed << std::setprecision(1) << "  path " << std::setw(6) << pathLength
              << " m  plans " << std::setw(4) << core.driver.iterations() << "  collisions "
              << sim.monitor().personCollisions();
            return o.str();
        });
        while (memory.due(explorationTime()))
            memory.addDue(core.map.knownVolumeInBox(), core.map.octree().size());
    }

    /** Where the tracks predict their people now. */
    std::vector<Eigen::Vector2d> trackedNow() const {
        std::vector<Eigen::Vector2d> means;
        for (const perception::PersonForecast& f : core.peopleInput.forecasts())
            means.push_back(f.at(now()).mean);
        return means;
    }

    /** Whether a track lies on a person at `at`: a prediction within a body's width. */
    bool trackLiesOn(const std::vector<Eigen::Vector2d>& tracked, const Eigen::Vector2d& at) const {
        for (const Eigen::Vector2d& mean : tracked)
            if ((mean - at).norm() < sim.people().params().bodySize.x())
                return true;
        return false;
    }

    /** When tracks lay on a person, as of the last frame. */
    struct TrackedSpan {
        bool now = false;
        double since = 0.0;          ///< when the unbroken stretch up to now began
        std::optional<double> last;  ///< the last frame a track lay on them
    };

    void noteTracked() {
        if (!core.driver.usesPeople())
            return;
        const std::vector<world::PersonState>& people = sim.people().states();
        const std::vector<Eigen::Vector2d> tracked = trackedNow();
        trackedSpans.resize(people.size());
        for (std::size_t i = 0; i < people.size(); ++i) {
            TrackedSpan& span = trackedSpans[i];
            const bool on = trackLiesOn(tracked, people[i].position);
            if (on && !span.now)
                span.since = now();
            if (on)
                span.last = now();
            span.now = on;
        }
    }

    /** What the planner knew of a person as a collision with them began. */
    eval::CollisionKnowledge atCollision(int person) const {
        eval::CollisionKnowledge knew;
        if (person < 0 || !core.driver.usesPeople())
            return knew;
        const auto i = static_cast<std::size_t>(person);
        const Eigen::Vector2d at = sim.people().states()[i].position;
        const TrackedSpan span = i < trackedSpans.size() ? trackedSpans[i] : TrackedSpan{};
        knew.tracked = trackLiesOn(trackedNow(), at) ? 1 : 0;
        if (knew.tracked)
            knew.trackedFor = span.now ? now() - span.since : 0.0;
        else if (span.last)
            knew.untrackedFor = now() - *span.last;
        knew.unseenWatch =
            planning::unseenWatchName(core.driver.planner().unseenWatchAt(at, now()));
        return knew;
    }

    void explore() {
        int failedPlans = 0;
        while (!stopping()) {
            const std::optional<planning::Plan> made = flight.planOnce(explorationTime());
            if (!made)
                continue;  // stale by the time it was done: plan again from here
            const planning::Plan& plan = *made;
            switch (plan.status) {
                case planning::Plan::Status::Finished:
                    finished = true;
                    endReason = eval::EndReason::plannerFinished(plan.reason);
                    return;
                case planning::Plan::Status::Wait:
                    flight.hoverUntil(now() + plan.waitSeconds);
                    break;
                case planning::Plan::Status::NoPath:
                    if (++failedPlans >= settings().maxFailedPlans) {
                        endReason = eval::EndReason::noPathLimit(failedPlans);
                        return;
                    }
                    break;
                case planning::Plan::Status::Path:
                    failedPlans = 0;
                    if (!flight.fly(plan))
                        ++abortedPaths;
                    core.recorder.flush();
                    break;
            }
        }
        endReason = eval::EndReason::of(timeUp() ? eval::EndReason::Kind::TimeLimit
                                                 : eval::EndReason::Kind::Interrupted);
    }

    eval::RunSummary summarize(double wallTime) {
        const sim::CollisionMonitor& monitor = sim.monitor();
        for (std::size_t i = 0; i < monitor.events().size(); ++i) {
            const sim::CollisionEvent& e = monitor.events()[i];
            core.recorder.addCollision(e.personIndex, e.start, e.end, collisionsBegun[i]);
        }
        eval::RunSummary s = core.summary(explorationTime(), pathLength, wallTime);
        s.reachablePercent =
            reachablePercent(sim.world(), settings(), *configForReach, core.map.resolution());
        s.collisions = monitor.personCollisions();
        s.staticCollisions = monitor.staticCollisions();
        s.abortedPaths = abortedPaths;
        s.hoverEvasions = flight.hoverEvasions();
        s.stalePlans = flight.stalePlans();
        s.finished = finished;
        s.endReason = endReason;
        s.explorationStart = exploreStart;
        s.labels = {{"world", sim.world().name},
                    {"mode", settings().mode},
                    {"planner", settings().plannerName},
                    {"start", std::to_string(settings().start)},
                    {"seed", std::to_string(settings().seed)}};
        return s;
    }

    void writeOutputs(const eval::RunSummary& summary) {
        memory.addFinal(explorationTime(), core.map.knownVolumeInBox(), core.map.octree().size());
        const SceneContent scene = sceneContent();
        if (peopleTruth)
            peopleTruth->flush();
        core.writeOutputs(summary, now(), &scene);
        memory.writePlot(core.recorder.path("memory.png"),
                         "Memory: " + settings().plannerName + ", " + sim.world().name);
    }

    const mrpt::config::CConfigFileBase* configForReach;
    StageClock stages;  ///< wall time by stage, of the simulator and the core
    SimulatorSource sim;
    MissionCore core;
    MemoryLog memory;
    FlightLoop flight{sim, core, *this};
    std::unique_ptr<PeopleTruthCsv> peopleTruth;  ///< with people.csv, in worlds with people
    std::vector<eval::CollisionKnowledge> collisionsBegun;  ///< per monitor event
    std::vector<TrackedSpan> trackedSpans;                  ///< per person, with people input
    double nextScene = 0.0;
    const std::atomic<bool>* stopFlag = nullptr;

    double exploreStart = -1.0;
    double pathLength = 0.0;
    int abortedPaths = 0;
    bool finished = false;
    eval::EndReason endReason;
};

Mission::Mission(const ExperimentConfig& config, const std::string& outputDir, std::ostream* log)
    : impl_(std::make_unique<Impl>(config, outputDir, log)) {
    impl_->stopFlag = &stopRequested_;
}

Mission::~Mission() = default;

eval::RunSummary Mission::run() {
    Impl& m = *impl_;
    return runKeepingOutputs(
        [&] {
            m.flight.takeOffAndLookAround(m.settings().climb);
            m.exploreStart = m.now();
            m.recordDue();
            if (!stopRequested_)
                m.explore();
            if (m.endReason.kind == eval::EndReason::Kind::None)
                m.endReason = eval::EndReason::of(eval::EndReason::Kind::Interrupted);
        },
        m.endReason, [&](double wall) { return m.summarize(wall); },
        [&](const eval::RunSummary& s) { m.writeOutputs(s); });
}

}  // namespace daep::mission
