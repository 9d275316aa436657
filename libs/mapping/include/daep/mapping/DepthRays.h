#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <vector>

#include "daep/mapping/DepthUnprojection.h"

namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace daep::mapping {

/**
 * The pinhole geometry of one depth image, in one place (the role of
 * CObservation3DRangeScan::get_unproj_lut()): MRPT's model for range images, where pixel
 * (row, col) looks along forward + up(row) * up + left(col) * left per metre of depth, with
 * left(col) = (cx - col) / fx and up(row) = (cy - row) / fy, tabulated once per frame for the
 * pixels of the image. The map insertion, its no-return clearing, the people detector, seesPast
 * and the detection scoring all turn pixels into rays (and points into pixels) through it.
 * The observation must outlive it.
 */
class DepthRays {
public:
    explicit DepthRays(const mrpt::obs::CObservation3DRangeScan& obs);

    int rows() const { return int(up_.size()); }
    int cols() const { return int(left_.size()); }
    /** The ray's left offset per metre of depth, for a column of the image. */
    float left(int col) const { return left_[std::size_t(col)]; }
    /** left(col) of every column, in order. */
    const float* lefts() const { return left_.data(); }
    /** The ray's up offset per metre of depth, for a row of the image. */
    float up(int row) const { return up_[std::size_t(row)]; }
    /** The same for any column or row, inside the image or not. */
    float leftAt(float col) const { return (cx_ - col) / fx_; }
    float upAt(float row) const { return (cy_ - row) / fy_; }

    /** Pixel (row, col)'s ray in the world, per metre of depth along `frame.forward`. */
    Eigen::Vector3f ray(const SensorFrame& frame, int row, int col) const {
        return frame.forward + up(row) * frame.up + left(col) * frame.left;
    }

    /**
     * Depth (m along the optical axis) of a return `range` (m) whose ray has these offsets:
     * the range itself for a depth image, else the range over the ray's length; <= 0 stays.
     */
    float depthOf(float range, float left, float up) const {
        return rangeIsDepth_ ? range : range / std::sqrt(1.0f + left * left + up * up);
    }
    /** depthOf(range, ...) is the range itself. */
    bool rangeIsDepth() const { return rangeIsDepth_; }
    /** Depth of pixel (row, col); 0 or less for no return. */
    float depth(int row, int col) const;

    /** Where a world point falls on the image. */
    struct Projection {
        double col = 0.0, row = 0.0;   ///< unrounded pixel coordinates (may lie off the image)
        float depth = 0.0f;            ///< m along the optical axis
        float left = 0.0f, up = 0.0f;  ///< the point's ray offsets per metre of depth
    };
    /** nullopt when the point lies less than `minDepth` in front of the camera. */
    std::optional<Projection> project(const SensorFrame& frame, const Eigen::Vector3f& point,
                                      float minDepth = 1e-3f) const;

    bool inImage(int row, int col) const {
        return row >= 0 && col >= 0 && row < rows() && col < cols();
    }

private:
    const mrpt::obs::CObservation3DRangeScan& obs_;
    float fx_, fy_, cx_, cy_;
    double fxd_, fyd_, cxd_, cyd_;
    bool rangeIsDepth_;
    std::vector<float> left_, up_;
};

}  // namespace daep::mapping
