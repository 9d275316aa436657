#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/common/Types.h"

namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace daep::mapping {

class DepthRays;

/** Sensor axes and position in the world (X forward, Y left, Z up), float for pixel loops. */
struct SensorFrame {
    Eigen::Vector3f forward, left, up, origin;
};

/** Where the observation's sensor is for a robot at `robot` (robot pose + obs.sensorPose). */
SensorFrame sensorFrameInWorld(const mrpt::obs::CObservation3DRangeScan& obs,
                               const FlatPose& robot);

/**
 * Whether the frame sees past a world point: the point projects into the image and its pixel
 * returns more than `margin` beyond the point's depth, or returns nothing while the point
 * lies within the sensor's maxRange. False behind the camera, outside the image, or where a
 * return lies in front of the point (it may be hidden there).
 */
bool seesPast(const mrpt::obs::CObservation3DRangeScan& obs, const SensorFrame& frame,
              const Eigen::Vector3f& point, float margin);
/** The same with the frame's rays already tabulated (many points of one frame). */
bool seesPast(const DepthRays& rays, const mrpt::obs::CObservation3DRangeScan& obs,
              const SensorFrame& frame, const Eigen::Vector3f& point, float margin);

/**
 * World-frame points of every pixel with a return (depth > 0), in row-major pixel order: the
 * same points and order as CObservation3DRangeScan::unprojectInto with the sensor pose and the
 * robot pose applied (X forward, Y left, Z up), without copying the observation.
 */
std::vector<Eigen::Vector3f> unprojectDepthImage(const mrpt::obs::CObservation3DRangeScan& obs,
                                                 const FlatPose& robot);

}  // namespace daep::mapping
