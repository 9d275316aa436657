#include "daep/mission/RawlogSource.h"

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>

#include "RawlogReader.h"

namespace daep::mission {

struct RawlogSource::Impl {
    Impl(const std::string& path, std::string sensorLabel, std::string poseLabel)
        : reader(path, std::move(sensorLabel), std::move(poseLabel)) {}

    RawlogReader reader;
    RawlogFrame raw;
    double firstStamp = 0.0;
    std::int64_t firstTicks = 0;
    bool started = false;
};

RawlogSource::RawlogSource(const std::string& path, std::string sensorLabel, std::string poseLabel)
    : impl_(std::make_unique<Impl>(path, std::move(sensorLabel), std::move(poseLabel))) {}

RawlogSource::~RawlogSource() = default;

std::string RawlogSource::name() const {
    return impl_->reader.path();
}

double RawlogSource::firstStamp() const {
    return impl_->firstStamp;
}

bool RawlogSource::lastFrameHadPose() const {
    return impl_->raw.hasPose;
}

bool RawlogSource::next(Frame& frame) {
    Impl& m = *impl_;
    if (!m.reader.next(m.raw))
        return false;
    if (!m.started) {
        m.firstStamp = m.raw.stamp;
        m.firstTicks = m.raw.ticks;
        m.started = true;
    }
    frame.time =
        std::chrono::duration<double>(mrpt::Clock::duration(m.raw.ticks - m.firstTicks)).count();
    frame.depth = m.raw.depth;
    frame.robot = m.raw.robot;
    frame.truePeople.reset();
    if (!m.raw.people.empty()) {
        std::vector<world::PersonState> people;
        // PERSON_<i> in order of i: their ids as the simulator numbered them.
        for (const auto& person : m.raw.people) {
            world::PersonState p;
            p.position = person.second.position.head<2>();
            p.heading = person.second.yaw;
            people.push_back(p);
        }
        frame.truePeople = std::move(people);
    }
    return true;
}

}  // namespace daep::mission
