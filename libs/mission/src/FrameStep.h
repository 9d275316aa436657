#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "daep/mission/FrameSource.h"

namespace daep::eval {
class RunRecorder;
}
namespace daep::mapping {
class ExplorationMap;
}

namespace daep::mission {

class PeopleCsv;
class PeopleInput;
class RawlogRecorder;
class StageClock;
struct CameraSight;

/**
 * What every depth frame goes through, whatever its source, in the order that matters: the
 * people input (detection, or measurement, against the map before the frame: the detector
 * looks for what the map contradicts), then the map (without the people tracked in the frame,
 * when they are kept out of it), then the records (pose, rawlog, people.csv, the trajectory for
 * the scene). The parts are owned by the mission that runs the step.
 */
class FrameStep {
public:
    struct Parts {
        mapping::ExplorationMap* map = nullptr;
        StageClock* stages = nullptr;
        eval::RunRecorder* recorder = nullptr;  ///< trajectory.csv; null: not written
        PeopleInput* people = nullptr;          ///< null: nobody is tracked
        /** The tracked people's depth returns are kept out of the map (PeopleInput decides). */
        bool peopleOutOfMap = false;
        Eigen::Vector3d bodySize = Eigen::Vector3d(1.0, 1.0, 1.8);
        PeopleCsv* peopleCsv = nullptr;    ///< the tracks after every frame; null: not written
        RawlogRecorder* rawlog = nullptr;  ///< the frame and the true people; null: not written
        std::string sourceName;            ///< for errors about what the source cannot give
    };

    explicit FrameStep(const Parts& parts) : parts_(parts) {}

    /** The frame through people, map and records; `sight` lets sensed people be measured. */
    void process(const Frame& frame, const CameraSight* sight = nullptr);

    /** The poses flown so far, one every 5 cm, for the scene. */
    const std::vector<Eigen::Vector3d>& trajectory() const { return trajectory_; }

private:
    void record(const Frame& frame);

    Parts parts_;
    std::vector<Eigen::Vector3d> trajectory_;
};

}  // namespace daep::mission
