#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace daep::mission {

/**
 * A trajectory in the TUM RGB-D format ("timestamp tx ty tz qx qy qz qw" per line, '#'
 * comments), as RGB-D datasets ship their ground truth, read whole and looked up by time.
 */
class TumPoses {
public:
    /** Reads the file; InputError naming the file and line on bad input or no poses. */
    explicit TumPoses(const std::string& path);

    /**
     * The pose at time t: linear between the two samples around t, the rotation by slerp;
     * nullopt more than 1 ms before the first sample or after the last.
     */
    std::optional<Eigen::Isometry3d> at(double t) const;

    const std::string& path() const { return path_; }
    double firstTime() const { return samples_.front().time; }
    double lastTime() const { return samples_.back().time; }

private:
    struct Sample {
        double time;
        Eigen::Vector3d position;
        Eigen::Quaterniond rotation;
    };
    std::string path_;
    std::vector<Sample> samples_;
};

}  // namespace daep::mission
