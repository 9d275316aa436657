#include "daep/mission/RawlogSource.h"

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "RawlogReader.h"
#include "TumPoses.h"

namespace daep::mission {
namespace {

mrpt::poses::CPose3D toMrpt(const Eigen::Isometry3d& p) {
    mrpt::math::CMatrixDouble44 m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            m(i, j) = p.matrix()(i, j);
    return mrpt::poses::CPose3D(m);
}

Eigen::Isometry3d toEigen(const mrpt::poses::CPose3D& p) {
    mrpt::math::CMatrixDouble44 m;
    p.getHomogeneousMatrix(m);
    Eigen::Isometry3d out;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            out.matrix()(i, j) = m(i, j);
    return out;
}

/** MRPT's sensor axes (x forward, y left, z up) in optical axes (z forward, x right, y down). */
Eigen::Matrix3d sensorAxesInOptical() {
    Eigen::Matrix3d m;
    m.col(0) = Eigen::Vector3d(0, 0, 1);
    m.col(1) = Eigen::Vector3d(-1, 0, 0);
    m.col(2) = Eigen::Vector3d(0, -1, 0);
    return m;
}

FlatPose flatten(const Eigen::Isometry3d& p) {
    FlatPose f;
    f.position = p.translation();
    f.yaw = std::atan2(p.linear()(1, 0), p.linear()(0, 0));
    return f;
}

Eigen::Isometry3d unflatten(const FlatPose& f) {
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.linear() = Eigen::AngleAxisd(f.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    p.translation() = f.position;
    return p;
}

/**
 * The frame placed at a pose of the file: the robot at its flat part (position, heading), the
 * rest of the rotation in the frame's sensorPose. A level body pose keeps the sensorPose as
 * recorded, so a run's own trajectory maps its frames as the run did.
 */
FlatPose place(mrpt::obs::CObservation3DRangeScan& depth, const Eigen::Isometry3d& pose,
               bool optical) {
    const bool level = std::abs(pose.linear()(2, 0)) < 1e-9 && std::abs(pose.linear()(2, 1)) < 1e-9;
    if (!optical && level)
        return flatten(pose);
    Eigen::Isometry3d sensor = pose;
    if (optical)
        sensor.linear() = pose.linear() * sensorAxesInOptical();
    else
        sensor = pose * toEigen(depth.sensorPose);
    const FlatPose robot = flatten(optical ? sensor : pose);
    depth.sensorPose = toMrpt(unflatten(robot).inverse() * sensor);
    return robot;
}

}  // namespace

struct RawlogSource::Impl {
    Impl(const std::string& path, std::string sensorLabel, std::string poseLabel,
         const PosesFile* file)
        : reader(path, std::move(sensorLabel), file ? std::string() : std::move(poseLabel)) {
        if (file) {
            poses.emplace(file->path);
            posesFile = *file;
        }
    }

    /** The frame's pose from the poses file; false when the file has none for its time. */
    bool poseFromFile(double relativeTime) {
        const double t = posesFile.relativeTime ? relativeTime : raw.stamp;
        const std::optional<Eigen::Isometry3d> pose = poses->at(t);
        if (!pose)
            return false;
        raw.robot = place(*raw.depth, *pose, posesFile.optical);
        raw.hasPose = true;
        return true;
    }

    RawlogReader reader;
    std::optional<TumPoses> poses;
    PosesFile posesFile;
    RawlogFrame raw;
    std::int64_t firstTicks = 0;
    double firstStamp = 0.0;
    bool started = false;
    std::size_t outsidePoses = 0;
};

RawlogSource::RawlogSource(const std::string& path, std::string sensorLabel, std::string poseLabel,
                           const PosesFile* poses)
    : impl_(std::make_unique<Impl>(path, std::move(sensorLabel), std::move(poseLabel), poses)) {}

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

std::size_t RawlogSource::framesOutsidePoses() const {
    return impl_->outsidePoses;
}

bool RawlogSource::next(Frame& frame) {
    Impl& m = *impl_;
    double time = 0.0;
    do {
        if (!m.reader.next(m.raw))
            return false;
        if (!m.started) {
            m.firstStamp = m.raw.stamp;
            m.firstTicks = m.raw.ticks;
            m.started = true;
        }
        time = std::chrono::duration<double>(mrpt::Clock::duration(m.raw.ticks - m.firstTicks))
                   .count();
    } while (m.poses && !m.poseFromFile(time) && ++m.outsidePoses);
    frame.time = time;
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
