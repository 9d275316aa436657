#include "TumPoses.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "daep/common/Error.h"

namespace daep::mission {

TumPoses::TumPoses(const std::string& path) : path_(path) {
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot open the poses file");
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
            continue;
        std::istringstream cells(line);
        Sample s;
        double qx, qy, qz, qw;
        const std::string where = path + ":" + std::to_string(lineNo) + ": ";
        if (!(cells >> s.time >> s.position.x() >> s.position.y() >> s.position.z() >> qx >> qy >>
              qz >> qw) ||
            !(cells >> std::ws).eof())
            throw InputError(where + "expected 'timestamp tx ty tz qx qy qz qw'");
        s.rotation = Eigen::Quaterniond(qw, qx, qy, qz);
        const double norm = s.rotation.norm();
        if (!std::isfinite(s.time) || !s.position.allFinite() || !(std::abs(norm - 1.0) < 1e-3))
            throw InputError(where + "not finite, or the quaternion is not of unit length");
        s.rotation.normalize();
        if (!samples_.empty() && s.time <= samples_.back().time)
            throw InputError(where + "the timestamp does not increase");
        samples_.push_back(s);
    }
    if (samples_.empty())
        throw InputError(path + ": no poses");
}

std::optional<Eigen::Isometry3d> TumPoses::at(double time) const {
    // Files print their times rounded (a run's trajectory_tum.txt to 1 ms): a frame that
    // close past either end takes the end's pose.
    constexpr double kRounding = 1e-3;
    if (time < samples_.front().time - kRounding || time > samples_.back().time + kRounding)
        return std::nullopt;
    const double t = std::clamp(time, samples_.front().time, samples_.back().time);
    const auto after = std::upper_bound(samples_.begin(), samples_.end(), t,
                                        [](double v, const Sample& s) { return v < s.time; });
    const Sample& b = after == samples_.end() ? samples_.back() : *after;
    const Sample& a = after == samples_.begin() ? b : *(after - 1);
    const double f = b.time > a.time ? (t - a.time) / (b.time - a.time) : 0.0;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = a.rotation.slerp(f, b.rotation).toRotationMatrix();
    pose.translation() = a.position + f * (b.position - a.position);
    return pose;
}

}  // namespace daep::mission
