#include "FrameStep.h"

#include <mrpt/obs/CObservation3DRangeScan.h>

#include "PeopleCsv.h"
#include "RawlogRecorder.h"
#include "StageClock.h"
#include "daep/eval/RunRecorder.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/PeopleInput.h"

namespace daep::mission {

void FrameStep::process(const Frame& frame, const CameraSight* sight) {
    std::vector<mapping::PersonFootprint> footprints;
    if (parts_.people) {
        const auto timed = parts_.stages->time(Stage::People);
        parts_.people->update(frame, *parts_.map, parts_.bodySize, sight, parts_.sourceName);
        if (parts_.peopleOutOfMap)
            footprints = parts_.people->mapFootprints(frame.time, parts_.bodySize);
    }
    {
        const auto timed = parts_.stages->time(Stage::Map);
        parts_.map->insertObservation(*frame.depth, frame.robot, footprints);
    }
    record(frame);
}

void FrameStep::record(const Frame& frame) {
    const auto timed = parts_.stages->time(Stage::Recording);
    if (parts_.recorder)
        parts_.recorder->addPose(frame.time, frame.robot);
    if (parts_.rawlog)
        parts_.rawlog->addFrame(
            *frame.depth, frame.time, frame.robot,
            frame.truePeople ? *frame.truePeople : std::vector<world::PersonState>{},
            parts_.bodySize);
    if (parts_.peopleCsv && parts_.people)
        parts_.peopleCsv->write(frame.time, parts_.people->forecasts());
    if (trajectory_.empty() || (trajectory_.back() - frame.robot.position).norm() > 0.05)
        trajectory_.push_back(frame.robot.position);
}

}  // namespace daep::mission
