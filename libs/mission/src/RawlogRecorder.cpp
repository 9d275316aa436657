#include "RawlogRecorder.h"

#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace daep::mission {
namespace {

/** Near is bright, far is dark, no return is black. */
void fillIntensityFromDepth(mrpt::obs::CObservation3DRangeScan& obs) {
    const int rows = static_cast<int>(obs.rangeImage.rows());
    const int cols = static_cast<int>(obs.rangeImage.cols());
    obs.intensityImage = mrpt::img::CImage(cols, rows, mrpt::img::CH_GRAY);
    const float maxRange = std::max(obs.maxRange, 1e-3f);
    for (int r = 0; r < rows; ++r) {
        auto* line = obs.intensityImage.ptrLine<uint8_t>(r);
        for (int c = 0; c < cols; ++c) {
            const float d = obs.rangeImage(r, c) * obs.rangeUnits;
            const float v = d > 0 ? 255.f * (1.f - 0.8f * std::min(d / maxRange, 1.f)) : 0.f;
            line[c] = static_cast<uint8_t>(v);
        }
    }
    obs.hasIntensityImage = true;
}

mrpt::obs::CObservationRobotPose::Ptr poseObservation(const std::string& label,
                                                      mrpt::Clock::time_point stamp,
                                                      const mrpt::poses::CPose3D& pose) {
    auto obs = mrpt::obs::CObservationRobotPose::Create();
    obs->sensorLabel = label;
    obs->timestamp = stamp;
    obs->pose.mean = pose;
    obs->pose.cov.setZero();  // ground truth
    return obs;
}

}  // namespace

struct RawlogRecorder::Impl {
    std::string path;
    mrpt::io::CFileGZOutputStream out;
};

RawlogRecorder::RawlogRecorder(const std::string& path) : impl_(std::make_unique<Impl>()) {
    impl_->path = path;
    std::string error;
    if (!impl_->out.open(path, 1, error))
        throw std::runtime_error("cannot write " + path + ": " + error);
}

RawlogRecorder::~RawlogRecorder() {
    close();
}

void RawlogRecorder::close() {
    if (impl_->out.is_open())
        impl_->out.close();
}

void RawlogRecorder::addFrame(const mrpt::obs::CObservation3DRangeScan& depth, double simTime,
                              const FlatPose& drone, const std::vector<world::PersonState>& people,
                              const Eigen::Vector3d& bodySize) {
    if (!impl_->out.is_open())
        return;
    // Epoch and offset apart: their sum as a double would round the time to 0.1 us steps.
    const auto stamp =
        mrpt::Clock::fromDouble(kRawlogEpoch) +
        std::chrono::round<mrpt::Clock::duration>(std::chrono::duration<double>(simTime));
    auto arch = mrpt::serialization::archiveFrom(impl_->out);

    auto scan = mrpt::obs::CObservation3DRangeScan::Create(depth);
    scan->timestamp = stamp;
    fillIntensityFromDepth(*scan);
    arch << *scan;

    const Eigen::Vector3d& p = drone.position;
    arch << *poseObservation("DRONE_POSE", stamp,
                             mrpt::poses::CPose3D(p.x(), p.y(), p.z(), drone.yaw, 0, 0));
    for (std::size_t i = 0; i < people.size(); ++i) {
        const auto& s = people[i];
        const mrpt::poses::CPose3D body(s.position.x(), s.position.y(), 0.5 * bodySize.z(),
                                        s.heading, 0, 0);
        arch << *poseObservation("PERSON_" + std::to_string(i), stamp, body);
    }
    written_ += 2 + people.size();
}

}  // namespace daep::mission
