#include "MissionCore.h"

#include <iomanip>
#include <ostream>
#include <stdexcept>

#include "daep/eval/Statistics.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/planning/PlannerRegistry.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"

namespace daep::mission {

MissionCore::MissionCore(const ExperimentConfig& config, const Use& how, StageClock& clock,
                         const std::string& outputDir, std::ostream* logStream)
    : stages(clock),
      settings(loadSettings(config)),
      use(how),
      log(logStream),
      recorder(outputDir, how.plans),
      outputs(loadOutputParams(config.config())),
      scene(outputs, outputDir, logStream),
      map(mapping::MapParams::fromConfig(config.config()), how.explorationBox),
      peopleInput(PeopleInputParams::fromConfig(config.config()),
                  settings.seed * 0xD1B54A32D192ED03ull + 7),
      bodySize(world::PeopleParams::fromConfig(config.config()).bodySize),
      driver(planning::createPlanner(settings.plannerName, config.config(),
                                     settings.seed * 0x9E3779B97F4A7C15ull + 1),
             driverSetup(config)),
      peopleCsv(outputs.peopleCsv && (driver.usesPeople() || how.trackPeopleAlways)
                    ? std::make_unique<PeopleCsv>(recorder.path("people.csv"))
                    : nullptr),
      rawlog(outputs.rawlog ? std::make_unique<RawlogRecorder>(recorder.path("run.rawlog"))
                            : nullptr),
      step(stepParts()),
      invocation(config.invocation()) {
    // People the planner does not keep out of the map enter it as occupied cells.
    map.setPeopleMapped(how.framesMayShowPeople &&
                        !(driver.usesPeople() && peopleInput.excludesFromMap()));
}

PlannerDriver::Setup MissionCore::driverSetup(const ExperimentConfig& config) {
    const sim::DroneParams drone = sim::DroneParams::fromConfig(config.config());
    PlannerDriver::Setup d;
    d.map = &map;
    d.explorationBox = use.explorationBox;
    d.motion.speed = drone.speed;
    d.motion.yawRate = drone.yawRate;
    d.droneSize = drone.boxSize;
    d.personSize = bodySize;
    d.people = &peopleInput;
    d.fixedTime = settings.planningTime == PlanningTime::Fixed;
    d.fixedSeconds = settings.planningFixed;
    d.deadlineSeconds = settings.planningDeadline;
    d.recorder = &recorder;
    d.stages = &stages;
    return d;
}

FrameStep::Parts MissionCore::stepParts() {
    FrameStep::Parts p;
    p.map = &map;
    p.recorder = &recorder;
    p.stages = &stages;
    if (driver.usesPeople() || use.trackPeopleAlways)
        p.people = &peopleInput;
    p.peopleOutOfMap = driver.usesPeople();
    p.bodySize = bodySize;
    p.peopleCsv = peopleCsv.get();
    p.rawlog = rawlog.get();
    p.sourceName = use.sourceName;
    return p;
}

void MissionCore::printProgress(const eval::MetricsSample& s, const std::string& figures) const {
    *log << "[t " << std::fixed << std::setprecision(0) << std::setw(5) << s.time << " s] coverage "
         << std::setprecision(1) << std::setw(5) << s.coveragePercent << " %" << figures
         << std::endl;
}

eval::RunSummary MissionCore::summary(double explorationTime, double pathLength,
                                      double wallTime) const {
    std::vector<double> ms;
    for (double s : recorder.chargedPlanTimes())
        ms.push_back(1e3 * s);
    eval::RunSummary s;
    s.coveragePercent = coveragePercent();
    s.explorationTime = explorationTime;
    s.pathLength = pathLength;
    s.planningTime = driver.chargedSeconds();
    s.planMsMedian = eval::median(ms);
    s.planMsP95 = eval::percentile(ms, 95);
    s.iterations = driver.iterations();
    s.wallTime = wallTime;
    s.knownVolume = map.knownVolumeInBox();
    s.boxVolume = use.explorationVolume;
    s.provenance = invocation;
    return s;
}

SceneContent MissionCore::sceneBase() const {
    SceneContent c;
    c.map = &map;
    c.trajectory = &step.trajectory();
    c.tree = &driver.lastTree();
    c.bodySize = bodySize;
    return c;
}

void MissionCore::writeOutputs(const eval::RunSummary& summary, double simTime,
                               const SceneContent* sceneContent) {
    recorder.flush();
    if (peopleCsv)
        peopleCsv->flush();
    recorder.writeSummary(summary);
    recorder.writeTiming(summary.wallTime, simTime, stages.report(summary.wallTime));
    recorder.writeCollisions();
    if (!map.writeBinary(recorder.path("map.bt")))
        throw std::runtime_error("cannot write " + recorder.path("map.bt"));
    if (rawlog)
        rawlog->close();
    if (outputs.scene && sceneContent)
        scene.write(*sceneContent);
}

}  // namespace daep::mission
