#include "RawlogReader.h"

#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <deque>
#include <filesystem>
#include <map>

#include "daep/common/Error.h"

namespace daep::mission {
namespace {

using ObservationPtr = mrpt::obs::CObservation::Ptr;

FlatPose flatPose(const mrpt::poses::CPose3D& p) {
    FlatPose f;
    f.position = Eigen::Vector3d(p.x(), p.y(), p.z());
    f.yaw = p.yaw();
    return f;
}

/** i for a label PERSON_<i>, else -1. */
int personIndex(const std::string& label) {
    const std::string prefix = "PERSON_";
    if (label.size() <= prefix.size() || label.compare(0, prefix.size(), prefix) != 0)
        return -1;
    const std::string digits = label.substr(prefix.size());
    if (digits.size() > 6 || digits.find_first_not_of("0123456789") != std::string::npos)
        return -1;
    return std::stoi(digits);
}

}  // namespace

struct RawlogReader::Impl {
    std::string path, sensorLabel, poseLabel;
    mrpt::io::CFileGZInputStream in;
    std::size_t objects = 0;
    std::deque<ObservationPtr> queue;  ///< read but not yet handled (sensory frame contents)
    std::shared_ptr<mrpt::obs::CObservation3DRangeScan> pending;
    double pendingStamp = 0.0;
    FlatPose latestPose;
    bool hasPose = false;
    std::map<int, FlatPose> people;

    [[noreturn]] void fail(const std::string& what) const { throw InputError(path + ": " + what); }

    /** The next serialized object, or nullptr at a clean end of file. */
    mrpt::serialization::CSerializable::Ptr readObject() {
        const auto before = in.getPosition();
        mrpt::serialization::CSerializable::Ptr obj;
        try {
            mrpt::serialization::archiveFrom(in) >> obj;
        } catch (const mrpt::serialization::CExceptionEOF&) {
            if (in.getPosition() != before)
                fail("truncated rawlog (object " + std::to_string(objects + 1) + ")");
            return nullptr;
        } catch (const std::exception& e) {
            fail("not a readable MRPT rawlog (object " + std::to_string(objects + 1) +
                 "): " + e.what());
        }
        ++objects;
        return obj;
    }

    /** The next observation in file order, or nullptr at the end. */
    ObservationPtr nextObservation() {
        while (queue.empty()) {
            const auto obj = readObject();
            if (!obj)
                return nullptr;
            if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
                queue.insert(queue.end(), sf->begin(), sf->end());
            else if (auto o = std::dynamic_pointer_cast<mrpt::obs::CObservation>(obj))
                queue.push_back(o);
            // anything else (CActionCollection: odometry) carries no depth or pose
        }
        ObservationPtr o = queue.front();
        queue.pop_front();
        return o;
    }

    std::shared_ptr<mrpt::obs::CObservation3DRangeScan> asDepthFrame(const ObservationPtr& o) {
        auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(o);
        if (!scan || (!sensorLabel.empty() && scan->sensorLabel != sensorLabel))
            return nullptr;
        try {
            scan->load();  // externally stored images (<rawlog>_Images/)
        } catch (const std::exception& e) {
            fail("cannot load the external data of a depth frame: " + std::string(e.what()));
        }
        return scan->hasRangeImage ? scan : nullptr;
    }

    bool takePose(const ObservationPtr& o) {
        auto pose = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(o);
        if (!pose)
            return false;
        if (pose->sensorLabel == poseLabel) {
            latestPose = flatPose(pose->pose.mean);
            hasPose = true;
            return true;
        }
        const int person = personIndex(pose->sensorLabel);
        if (person >= 0)
            people[person] = flatPose(pose->pose.mean);
        return person >= 0;
    }

    void emit(RawlogFrame& frame) {
        frame.stamp = pendingStamp;
        frame.depth = std::move(pending);
        frame.hasPose = hasPose;
        frame.robot = hasPose ? latestPose : FlatPose{};
        frame.people = people;
        pending.reset();
    }
};

RawlogReader::RawlogReader(const std::string& path, std::string sensorLabel, std::string poseLabel)
    : impl_(std::make_unique<Impl>()) {
    impl_->path = path;
    impl_->sensorLabel = std::move(sensorLabel);
    impl_->poseLabel = std::move(poseLabel);
    if (!std::filesystem::is_regular_file(path))
        impl_->fail("rawlog file not found");
    if (!impl_->in.open(path))
        impl_->fail("cannot open the rawlog");
    mrpt::img::CImage::setImagesPathBase(mrpt::obs::CRawlog::detectImagesDirectory(path));
}

RawlogReader::~RawlogReader() = default;

const std::string& RawlogReader::path() const {
    return impl_->path;
}

std::size_t RawlogReader::objectsRead() const {
    return impl_->objects;
}

/**
 * A depth frame is held back until an observation with a later timestamp (or another depth
 * frame, or the end of the file) shows that no more poses for its instant can follow.
 */
bool RawlogReader::next(RawlogFrame& frame) {
    Impl& m = *impl_;
    while (const ObservationPtr o = m.nextObservation()) {
        const double stamp = mrpt::Clock::toDouble(o->timestamp);
        auto depth = m.asDepthFrame(o);
        if (m.pending && (depth || stamp > m.pendingStamp)) {
            m.queue.push_front(o);
            m.emit(frame);
            return true;
        }
        if (depth) {
            m.pending = std::move(depth);
            m.pendingStamp = stamp;
        } else {
            m.takePose(o);
        }
    }
    if (!m.pending)
        return false;
    m.emit(frame);
    return true;
}

}  // namespace daep::mission
