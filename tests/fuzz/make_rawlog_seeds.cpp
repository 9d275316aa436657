// Writes the seed corpus of fuzz_rawlog: tiny rawlogs (4 x 3 depth frames) in the
// observations format (plain and gzip'ed) and in the actions / sensory-frames format.
// usage: fuzz_make_rawlog_seeds OUT_DIR
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdio>
#include <string>

namespace {

using mrpt::obs::CObservation3DRangeScan;
using mrpt::obs::CObservationRobotPose;

mrpt::Clock::time_point at(double seconds) {
    return mrpt::Clock::fromDouble(946684800.0 + seconds);
}

CObservation3DRangeScan::Ptr depthFrame(double t, float range) {
    auto scan = CObservation3DRangeScan::Create();
    scan->sensorLabel = "DEPTH_CAM";
    scan->timestamp = at(t);
    scan->cameraParams.ncols = 4;
    scan->cameraParams.nrows = 3;
    scan->cameraParams.fx(2.0);
    scan->cameraParams.fy(2.0);
    scan->cameraParams.cx(2.0);
    scan->cameraParams.cy(1.5);
    scan->hasRangeImage = true;
    scan->rangeImage_setSize(3, 4);
    scan->rangeImage.setConstant(static_cast<uint16_t>(range / scan->rangeUnits));
    scan->rangeImage(1, 2) = 0;  // one pixel without a return
    return scan;
}

CObservationRobotPose::Ptr pose(const std::string& label, double t, double x, double y) {
    auto p = CObservationRobotPose::Create();
    p->sensorLabel = label;
    p->timestamp = at(t);
    p->pose.mean = mrpt::poses::CPose3D(x, y, 1.0, 0.3, 0.0, 0.0);
    return p;
}

template <typename Stream>
void writeObservations(Stream& out) {
    auto arch = mrpt::serialization::archiveFrom(out);
    arch << *depthFrame(0.0, 2.5) << *pose("DRONE_POSE", 0.0, 0.5, -0.25)
         << *pose("PERSON_0", 0.0, 2.0, 1.0);
    arch << *depthFrame(0.2, 3.0) << *pose("DRONE_POSE", 0.2, 0.6, -0.25)
         << *pose("PERSON_0", 0.2, 2.1, 1.0);
}

void writeSensoryFrames(mrpt::io::CFileOutputStream& out) {
    auto arch = mrpt::serialization::archiveFrom(out);
    for (int i = 0; i < 2; ++i) {
        mrpt::obs::CActionCollection actions;
        mrpt::obs::CSensoryFrame frame;
        frame.insert(pose("DRONE_POSE", 0.2 * i, 0.1 * i, 0.0));
        frame.insert(depthFrame(0.2 * i, 2.0));
        arch << actions << frame;
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: fuzz_make_rawlog_seeds OUT_DIR\n");
        return 1;
    }
    const std::string dir = argv[1];
    {
        mrpt::io::CFileOutputStream plain(dir + "/observations.rawlog");
        writeObservations(plain);
    }
    {
        mrpt::io::CFileGZOutputStream gz(dir + "/observations_gz.rawlog");
        writeObservations(gz);
    }
    mrpt::io::CFileOutputStream frames(dir + "/sensory_frames.rawlog");
    writeSensoryFrames(frames);
    return 0;
}
