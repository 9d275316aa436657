#pragma once

#include <Eigen/Core>

namespace daep::perception {

/**
 * One measured person position on the ground plane. `id` >= 0 when the source knows who it is
 * (the simulator's ground truth, or its "sensed" camera model); -1 for an anonymous detection
 * (PeopleDetector), which the tracker associates with its tracks itself.
 */
struct PersonMeasurement {
    int id = -1;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity() * 1e-4;  ///< of the position, m^2
};

}  // namespace daep::perception
