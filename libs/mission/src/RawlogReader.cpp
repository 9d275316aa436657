#include "RawlogReader.h"

#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <filesystem>
#include <limits>
#include <map>
#include <new>
#include <set>
#include <utility>

#include "RawlogObjects.h"
#include "daep/common/Error.h"

namespace daep::mission {
namespace {

constexpr int kMaxImageSide = 16384;
constexpr std::size_t kLargestImageBytes =
    std::size_t(kMaxImageSide) * kMaxImageSide * sizeof(float);

std::atomic<std::size_t> largestReadBlock{kLargestImageBytes};
/** Set while this thread deserializes one rawlog object. */
thread_local bool readingObject = false;

/** Marks the deserialization of one object, for mrpt::aligned_malloc below. */
class ReadingObject {
public:
    ReadingObject() { readingObject = true; }
    ~ReadingObject() { readingObject = false; }
    ReadingObject(const ReadingObject&) = delete;
    ReadingObject& operator=(const ReadingObject&) = delete;
};

}  // namespace
}  // namespace daep::mission

// MRPT 2.5's aligned_allocator_cpp11 hands on what mrpt::aligned_malloc returns unchecked, and
// std::vector writes through the null that a corrupt rawlog's image size (3.7e18 bytes) gets:
// a segmentation fault instead of an error naming the file; a size of a few gigabytes is
// allocated and filled for minutes. This definition is found before libmrpt-core's (the
// executable's symbols come first; the MRPT libraries call it through their PLT) and does what
// it does, rounding the size up to the alignment for aligned_alloc, except that no memory, or
// a block beyond RawlogReader::setLargestReadBlock while a rawlog object is read, is
// std::bad_alloc, which the reader reports as a corrupt object.
namespace mrpt {
void* aligned_malloc(std::size_t size, std::size_t alignment) {
    if (alignment == 0 || size > std::numeric_limits<std::size_t>::max() - alignment)
        throw std::bad_alloc();
    if (daep::mission::readingObject && size > daep::mission::largestReadBlock.load())
        throw std::bad_alloc();
    const std::size_t rounded = (size + alignment - 1) / alignment * alignment;
    void* p = std::aligned_alloc(alignment, rounded);
    if (p == nullptr && rounded != 0)
        throw std::bad_alloc();
    return p;
}
}  // namespace mrpt

namespace daep::mission {
namespace {

using ObservationPtr = mrpt::obs::CObservation::Ptr;

FlatPose flatPose(const mrpt::poses::CPose3D& p) {
    FlatPose f;
    f.position = Eigen::Vector3d(p.x(), p.y(), p.z());
    f.yaw = p.yaw();
    return f;
}

/** The label of the robot poses integrated from robot movement actions. */
const std::string kActionsLabel = "ACTIONS";

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

/** Longest gap between consecutive depth frames, s: a larger jump is a corrupt timestamp. */
constexpr double kMaxFrameGap = 3600.0;
/** Farthest a rawlog pose may lie from the origin, m (the map's octree reaches +-6.5 km). */
constexpr double kMaxCoordinate = 5000.0;

/**
 * One printable line from an MRPT exception: the innermost "Message:" of its nested report
 * (without the backtraces), else the first line; bytes a corrupt file put in it (a garbled
 * class name) become '?'.
 */
std::string oneLineReason(const std::exception& e) {
    std::string what = e.what();
    if (const auto at = what.rfind("Message:"); at != std::string::npos)
        what = what.substr(at + 8);
    what = what.substr(0, what.find('\n'));
    if (const auto hint = what.find(" (Perhaps it's a gz"); hint != std::string::npos)
        what.resize(hint);
    std::string out = printable(what);
    const auto b = out.find_first_not_of(' ');
    out = b == std::string::npos ? std::string() : out.substr(b);
    if (out.size() > 200)
        out = out.substr(0, 200) + "...";
    return out.empty() ? "unknown error" : out;
}

/** An MRPT exception as the user is told it: one line, and with --debug its whole text after it. */
std::string reportedReason(const std::exception& e) {
    const std::string line = oneLineReason(e);
    return debugErrors() ? line + "\n" + e.what() : line;
}

bool isEndOfData(const std::string& reason) {
    return reason.find("EOF") != std::string::npos;
}

/**
 * The byte behind a bool that MRPT read from the file as it stands there: 0 or 1 unless the
 * file is corrupt (reading any other as a bool is undefined behaviour; found by fuzz_rawlog).
 */
unsigned storedByte(const bool& flag) {
    unsigned char byte = 0;
    std::memcpy(&byte, &flag, 1);
    return byte;
}

bool finitePose(const mrpt::poses::CPose3D& p) {
    for (const double v : {p.x(), p.y(), p.z(), p.yaw(), p.pitch(), p.roll()})
        if (!std::isfinite(v) || std::abs(v) > kMaxCoordinate)
            return false;
    return true;
}

}  // namespace

struct RawlogReader::Impl {
    std::string path, sensorLabel, poseLabel;
    mrpt::io::CFileGZInputStream in;
    RawlogObjects objectStream{in};
    std::size_t objects = 0;
    std::deque<ObservationPtr> queue;  ///< read but not yet handled (sensory frame contents)
    std::shared_ptr<mrpt::obs::CObservation3DRangeScan> pending;
    double pendingStamp = 0.0;
    std::int64_t pendingTicks = 0;
    FlatPose latestPose;
    bool hasPose = false;
    std::map<int, FlatPose> people;
    std::set<std::string> otherPoseLabels;  ///< robot poses seen under labels not asked for
    mrpt::poses::CPose3D actionPose;        ///< the robot movements so far, integrated
    std::size_t framesEmitted = 0;
    double lastFrameStamp = 0.0;

    [[noreturn]] void fail(const std::string& what) const { throw InputError(path + ": " + what); }

    /** "object N (after K depth frames)": where in the file a problem is. */
    std::string where(std::size_t object) const {
        return "object " + std::to_string(object) + " (after " + std::to_string(framesEmitted) +
               " depth frames)";
    }

    /** Queues the observations of the next object; false at a clean end of the file. */
    bool readObject() {
        std::vector<ObservationPtr> observations;
        std::vector<std::shared_ptr<mrpt::obs::CAction>> actions;
        try {
            const ReadingObject reading;
            if (!objectStream.readNext(observations, &actions))
                return false;
        } catch (const TruncatedObject&) {
            failTruncated();
        } catch (const MalformedObject& e) {
            fail(unreadable() + where(objects + 1) + " " + e.what());
        } catch (const mrpt::serialization::CExceptionEOF&) {
            failTruncated();
        } catch (const std::bad_alloc&) {
            fail("corrupt rawlog: " + where(objects + 1) + " declares more data than memory holds");
        } catch (const std::exception& e) {
            if (isEndOfData(oneLineReason(e)) || in.checkEOF())
                failTruncated();
            fail(unreadable() + where(objects + 1) + " is unreadable: " + reportedReason(e));
        }
        ++objects;
        queue.insert(queue.end(), observations.begin(), observations.end());
        for (const auto& action : actions)
            if (integrateMovement(*action))
                break;  // one movement per collection (a 2D and a 3D one describe the same)
        return true;
    }

    /**
     * A robot movement action (actions / sensory-frames format) moves the odometry pose by its
     * increment; the pose joins the queue as a robot pose labelled ACTIONS, in file order.
     */
    bool integrateMovement(const mrpt::obs::CAction& action) {
        mrpt::poses::CPose3D change;
        if (const auto* m2 = dynamic_cast<const mrpt::obs::CActionRobotMovement2D*>(&action))
            change = mrpt::poses::CPose3D(m2->poseChange ? m2->poseChange->getMeanVal()
                                                         : m2->rawOdometryIncrementReading);
        else if (const auto* m3 = dynamic_cast<const mrpt::obs::CActionRobotMovement3D*>(&action))
            change = m3->poseChange.mean;
        else
            return false;
        if (!finitePose(change))
            fail("corrupt rawlog: a robot movement in " + where(objects) +
                 " is not finite or lies beyond " +
                 std::to_string(static_cast<int>(kMaxCoordinate)) + " m");
        actionPose = actionPose + change;
        auto pose = mrpt::obs::CObservationRobotPose::Create();
        pose->sensorLabel = kActionsLabel;
        pose->timestamp = action.timestamp;
        pose->pose.mean = actionPose;
        queue.push_back(pose);
        return true;
    }

    [[noreturn]] void failTruncated() const {
        fail("truncated rawlog: the file ends inside " + where(objects + 1));
    }

    std::string unreadable() const {
        return objects == 0 ? "not an MRPT rawlog: " : "corrupt rawlog: ";
    }

    /** The next observation in file order, or nullptr at the end. */
    ObservationPtr nextObservation() {
        while (queue.empty())
            if (!readObject())
                return nullptr;
        ObservationPtr o = queue.front();
        queue.pop_front();
        return o;
    }

    std::shared_ptr<mrpt::obs::CObservation3DRangeScan> asDepthFrame(const ObservationPtr& o) {
        auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(o);
        if (!scan || (!sensorLabel.empty() && scan->sensorLabel != sensorLabel))
            return nullptr;
        checkFlags(*scan);
        try {
            scan->load();  // externally stored images (<rawlog>_Images/)
        } catch (const std::exception& e) {
            fail("cannot load the external data of a depth frame: " + reportedReason(e));
        }
        if (!scan->hasRangeImage)
            return nullptr;
        checkDepthFrame(*scan);
        return scan;
    }

    /** The flags the mapping and the detector read must be bools. */
    void checkFlags(const mrpt::obs::CObservation3DRangeScan& scan) const {
        const std::pair<const char*, const bool*> flags[] = {
            {"hasRangeImage", &scan.hasRangeImage}, {"range_is_depth", &scan.range_is_depth}};
        for (const auto& [name, flag] : flags)
            if (storedByte(*flag) > 1)
                fail("corrupt rawlog: the depth frame in " + where(objects) + " has " + name +
                     " = " + std::to_string(storedByte(*flag)) + ", not a bool");
    }

    /** What the mapping and the detector index or divide by must make sense. */
    void checkDepthFrame(const mrpt::obs::CObservation3DRangeScan& scan) const {
        const std::string frame = "depth frame " + std::to_string(framesEmitted + 1) + " (object " +
                                  std::to_string(objects) + ")";
        const auto rows = scan.rangeImage.rows(), cols = scan.rangeImage.cols();
        if (rows < 1 || cols < 1 || rows > kMaxImageSide || cols > kMaxImageSide)
            fail("corrupt " + frame + ": range image of " + std::to_string(cols) + " x " +
                 std::to_string(rows) + " pixels");
        const auto& cam = scan.cameraParams;
        if (!(cam.fx() > 0 && std::isfinite(cam.fx()) && cam.fy() > 0 && std::isfinite(cam.fy()) &&
              std::isfinite(cam.cx()) && std::isfinite(cam.cy())))
            fail("corrupt " + frame + ": camera intrinsics are not finite positive numbers");
        if (!(scan.rangeUnits > 0 && std::isfinite(scan.rangeUnits)))
            fail("corrupt " + frame + ": range units are not a finite positive number");
        if (!finitePose(scan.sensorPose))
            fail("corrupt " + frame + ": the sensor pose is not finite or lies beyond " +
                 std::to_string(static_cast<int>(kMaxCoordinate)) + " m");
        const double stamp = mrpt::Clock::toDouble(scan.timestamp);
        if (!std::isfinite(stamp))
            fail("corrupt " + frame + ": the timestamp is not a number");
        if (framesEmitted > 0 && stamp < lastFrameStamp)
            fail("corrupt " + frame + ": its timestamp is " +
                 std::to_string(lastFrameStamp - stamp) + " s before the previous frame's");
        if (framesEmitted > 0 && stamp > lastFrameStamp + kMaxFrameGap)
            fail("corrupt " + frame + ": its timestamp jumps " +
                 std::to_string(stamp - lastFrameStamp) + " s past the previous frame's");
    }

    /** A pose observation: the robot's (poseLabel), a person's (PERSON_<i>), or another. */
    bool takePose(const ObservationPtr& o) {
        if (auto odometry = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o))
            return takeRobotPose(odometry->sensorLabel, mrpt::poses::CPose3D(odometry->odometry));
        auto pose = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(o);
        if (!pose)
            return false;
        const int person = personIndex(pose->sensorLabel);
        if (person < 0)
            return takeRobotPose(pose->sensorLabel, pose->pose.mean);
        checkFinite(pose->sensorLabel, pose->pose.mean);
        people[person] = flatPose(pose->pose.mean);
        return true;
    }

    bool takeRobotPose(const std::string& label, const mrpt::poses::CPose3D& pose) {
        if (label != poseLabel) {
            otherPoseLabels.insert(label);
            return false;
        }
        checkFinite(label, pose);
        latestPose = flatPose(pose);
        hasPose = true;
        return true;
    }

    void checkFinite(const std::string& label, const mrpt::poses::CPose3D& pose) const {
        if (!finitePose(pose))
            fail("corrupt rawlog: pose '" + label + "' in " + where(objects) +
                 " is not finite or lies beyond " +
                 std::to_string(static_cast<int>(kMaxCoordinate)) + " m");
    }

    /** A frame without a pose under poseLabel while the file has robot poses under others. */
    void checkPoseLabel() const {
        if (poseLabel.empty() || hasPose || otherPoseLabels.empty())
            return;  // an empty label: the poses come from elsewhere
        std::string labels;
        for (const std::string& l : otherPoseLabels)
            labels += (labels.empty() ? "'" : ", '") + l + "'";
        fail("no robot pose labelled '" + poseLabel + "' ([rawlog] pose_label) at or before " +
             where(objects) + "; the robot poses in the file are labelled " + labels);
    }

    void emit(RawlogFrame& frame) {
        checkPoseLabel();
        frame.stamp = pendingStamp;
        frame.ticks = pendingTicks;
        frame.depth = std::move(pending);
        frame.hasPose = hasPose;
        frame.robot = hasPose ? latestPose : FlatPose{};
        frame.people = people;
        pending.reset();
        lastFrameStamp = frame.stamp;
        ++framesEmitted;
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

void RawlogReader::setLargestReadBlock(std::size_t bytes) {
    largestReadBlock.store(bytes);
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
        // A movement after a frame is the next frame's: the pending one goes out first.
        const bool movement = !depth && o->sensorLabel == kActionsLabel;
        if (m.pending && (depth || stamp > m.pendingStamp || movement)) {
            m.queue.push_front(o);
            m.emit(frame);
            return true;
        }
        if (depth) {
            m.pending = std::move(depth);
            m.pendingStamp = stamp;
            m.pendingTicks = o->timestamp.time_since_epoch().count();
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
