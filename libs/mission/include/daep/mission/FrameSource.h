#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "daep/common/Types.h"
#include "daep/world/People.h"

namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace daep::mission {

/** One depth frame, from whatever source: what the per-frame step (people, map, records) takes. */
struct Frame {
    /** s: simulated time since spawn, or rawlog time since the first depth frame. */
    double time = 0.0;
    std::shared_ptr<const mrpt::obs::CObservation3DRangeScan> depth;
    FlatPose robot;  ///< the drone's pose when the frame was taken
    /**
     * The true people at `time` (index = person id; position and heading, no velocity), where
     * the source knows them: the simulator, or a rawlog recorded from it (PERSON_<i> poses).
     * people_source = ground_truth and the detection scoring use them.
     */
    std::optional<std::vector<world::PersonState>> truePeople;
};

/**
 * Where depth frames come from, in the shape of MRPT's app data sources
 * (mrpt/apps/BaseAppDataSource.h): one app loop over any of them. Implementations: the
 * simulator (closed loop: it also flies the drone; SimulatorSource), a rawlog (open loop,
 * streamed; RawlogSource) and a recorded trajectory flown again through a world
 * (TrajectorySource). A live RGB-D camera is one more implementation (README, "A live
 * camera").
 */
class FrameSource {
public:
    virtual ~FrameSource() = default;
    /**
     * The next frame; false once the source has no more. Throws InputError on bad data. The
     * depth image is the source's: a source may render the next frame into the same object.
     */
    virtual bool next(Frame& frame) = 0;
    /** The file or world the frames come from, for messages. */
    virtual std::string name() const = 0;
};

}  // namespace daep::mission
