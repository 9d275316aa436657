#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "daep/common/Types.h"
#include "daep/perception/PersonMeasurement.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace mrpt::obs {
class CObservation3DRangeScan;
}
namespace daep::mapping {
class ExplorationMap;
}

namespace daep::perception {

/** Parameters of PeopleDetector; the [detector] section of defaults.ini documents each. */
struct DetectorParams {
    double maxRange = 5.0;             ///< pixels farther than this (depth, m) are ignored
    double floorHeight = 0.15;         ///< points below this z (m) are floor
    double ceilingHeight = 2.4;        ///< points above this z (m) are not looked at
    double maxPersonTop = 2.05;        ///< a cluster reaching higher is not a person (m)
    double minVerticalExtent = 0.5;    ///< a person's visible part spans at least this (m)
    double maxWidth = 1.6;             ///< horizontal extent across the view, at most (m)
    double maxDepthSpread = 1.6;       ///< horizontal extent along the view, at most (m)
    double minArea = 0.08;             ///< visible surface of a cluster, at least (m^2)
    double minEvidenceFraction = 0.1;  ///< share of a cluster's surface the map contradicts
    double depthJump = 0.25;  ///< depth step (m) between neighbours that splits objects, at least
    /** Steeper than this (rad from face-on) a surface's depth steps like a jump between objects. */
    double maxGrazingAngle = 75.0 * M_PI / 180.0;
    int morphKernel = 3;             ///< side (px) of the opening that removes speckles
    double surfaceMargin = 0.15;     ///< a free point this close (m) before a static cell is noise
    double centreOffset = 0.42;      ///< body centre behind the visible surface's centroid (m)
    double mergeDistance = 0.8;      ///< clusters whose centres are closer (m) are one person
    double sigmaAlong = 0.15;        ///< position std along the viewing direction (m)
    double sigmaAcross = 0.10;       ///< position std across it (m)
    double sideSigmaAcross = 0.20;   ///< across it for a person the image's side edge cuts (m)
    double minFreshFraction = 0.05;  ///< share contradicting the map now that refreshes the memory
    double imprintKeep = 2.0;        ///< cells a person occupied count as dynamic this long (s)
    double seeThroughDepth = 0.2;    ///< an occupied cell this close before an unknown point (m)
    double bodyHalfWidth = 0.5;      ///< of the body box whose unknown cells are remembered (m)
    double bodyHeight = 1.8;         ///< (m)
    int pixelStride = 1;             ///< look at every n-th pixel of every n-th row

    /** Reads and validates [detector]; throws InputError naming the key. */
    static DetectorParams fromConfig(const mrpt::config::CConfigFileBase& cfg);
};

/** One accepted cluster, for evaluation and display. */
struct PersonDetection {
    PersonMeasurement measurement;
    Eigen::Vector3d surfaceCentroid = Eigen::Vector3d::Zero();  ///< of the visible points
    double area = 0.0;                                          ///< visible surface, m^2
    double evidenceFraction = 0.0;  ///< share of the surface that contradicts the static map
    int pixels = 0;
    bool cutBySide = false;  ///< the image's left or right edge cuts the person
};

/**
 * Finds people in a depth frame by comparing it with the exploration map (call it before the
 * frame is inserted): a pixel is dynamic evidence when its point lies in space the map knows
 * to be free, or in a cell that a person occupied lately (the map keeps people's traces as
 * occupied until it sees through them again). Pixels between floor and ceiling that are not
 * explained by static occupied cells are cut at depth discontinuities, cleaned by a
 * morphological opening and grouped by connected components; a group is a person when its 3D
 * size fits one and enough of its surface is evidence. Positions are body centres on the
 * ground plane (the visible surface's centroid pushed back along the view), with a covariance
 * elongated along the viewing direction.
 *
 * Stateful: it remembers the cells of the people it found for DetectorParams::imprintKeep
 * seconds, so a person standing still (whose cells the map now holds occupied) is still found.
 * Per frame: detect(obs, robotPose, map) -> PeopleTracker::update(time, measurements).
 */
class PeopleDetector {
public:
    explicit PeopleDetector(const DetectorParams& params);
    ~PeopleDetector();
    PeopleDetector(PeopleDetector&&) noexcept;
    PeopleDetector& operator=(PeopleDetector&&) noexcept;

    /**
     * Anonymous measurements (id = -1) of the people in `obs` (range image, intrinsics and
     * sensorPose relative to the robot) seen from `robot`. The observation's timestamp
     * (non-decreasing across calls) ages the remembered person cells.
     */
    std::vector<PersonMeasurement> detect(const mrpt::obs::CObservation3DRangeScan& obs,
                                          const FlatPose& robot,
                                          const mapping::ExplorationMap& map);

    /** The clusters accepted by the last detect(), with their measurements. */
    const std::vector<PersonDetection>& lastDetections() const;

    const DetectorParams& params() const { return params_; }

private:
    class Impl;
    DetectorParams params_;
    std::unique_ptr<Impl> impl_;
};

}  // namespace daep::perception
