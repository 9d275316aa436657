#include "daep/mapping/DepthRays.h"

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cmath>

namespace daep::mapping {

DepthRays::DepthRays(const mrpt::obs::CObservation3DRangeScan& obs)
    : obs_(obs),
      fx_(float(obs.cameraParams.fx())),
      fy_(float(obs.cameraParams.fy())),
      cx_(float(obs.cameraParams.cx())),
      cy_(float(obs.cameraParams.cy())),
      fxd_(obs.cameraParams.fx()),
      fyd_(obs.cameraParams.fy()),
      cxd_(obs.cameraParams.cx()),
      cyd_(obs.cameraParams.cy()),
      rangeIsDepth_(obs.range_is_depth),
      left_(std::size_t(obs.rangeImage.cols())),
      up_(std::size_t(obs.rangeImage.rows())) {
    for (int col = 0; col < cols(); ++col)
        left_[std::size_t(col)] = leftAt(float(col));
    for (int row = 0; row < rows(); ++row)
        up_[std::size_t(row)] = upAt(float(row));
}

float DepthRays::depth(int row, int col) const {
    return depthOf(float(obs_.rangeImage(row, col)) * obs_.rangeUnits, left(col), up(row));
}

std::optional<DepthRays::Projection> DepthRays::project(const SensorFrame& frame,
                                                        const Eigen::Vector3f& point,
                                                        float minDepth) const {
    const Eigen::Vector3f d = point - frame.origin;
    Projection p;
    p.depth = d.dot(frame.forward);
    if (p.depth <= minDepth)
        return std::nullopt;
    p.left = d.dot(frame.left) / p.depth;
    p.up = d.dot(frame.up) / p.depth;
    p.col = cxd_ - p.left * fxd_;
    p.row = cyd_ - p.up * fyd_;
    return p;
}

}  // namespace daep::mapping
