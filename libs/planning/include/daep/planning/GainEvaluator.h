#pragma once

#include <Eigen/Core>
#include <cmath>
#include <utility>
#include <vector>

#include "daep/common/Types.h"

namespace mrpt::config {
class CConfigFileBase;
}
namespace daep::mapping {
class ExplorationMap;
}

namespace daep::planning {

/** Ray-cubature parameters, section [gain]. Angles in radians. */
struct GainParams {
    double hfov = 103.2 * M_PI / 180.0;
    double vfov = 77.4 * M_PI / 180.0;
    double range = 5.0;
    double dr = 0.2;
    double dphi = 10.0 * M_PI / 180.0;    ///< elevation step
    double dtheta = 10.0 * M_PI / 180.0;  ///< azimuth step

    /** Reads and validates [gain]; throws InputError naming the bad key. */
    static GainParams fromConfig(const mrpt::config::CConfigFileBase& config);
};

/**
 * The sample grid of the ray cubature: for each column (an azimuth sector of the full circle)
 * a fan of rings (elevation cells filling the vertical FoV), and shells along each ray.
 */
struct RayCubature {
    RayCubature() = default;
    /** Columns of equal width 2 pi / n, their central azimuths given. */
    RayCubature(const GainParams& params, const std::vector<double>& columnCentres);

    int rings = 0;
    double phiMin = 0.0;  ///< elevation cells span [phiMin, phiMax], measured from +z
    double phiMax = 0.0;
    std::vector<Eigen::Vector3d> directions;  ///< [column * rings + ring], unit length
    std::vector<double> ringWeights;          ///< solid angle of each ring's cell in a column
    std::vector<double> radii;                ///< shell mid-radii
    std::vector<double> shellWeights;         ///< r^2 dr + dr^3 / 12 per shell
};

/** Something that blocks rays besides the map: a person's body as a vertical cylinder. */
struct BodyOccluder {
    Eigen::Vector2d center = Eigen::Vector2d::Zero();
    double radius = 0.5;
    double height = 1.8;  ///< spans z in [0, height]
};

/** Distance along the unit ray from o to where it enters the body (0 inside, +inf never). */
double rayEntry(const BodyOccluder& body, const Eigen::Vector3d& o, const Eigen::Vector3d& dir);

/** A heading and the unknown volume (m^3) seen with the camera at that heading. */
struct YawGain {
    double yaw = 0.0;
    double gain = 0.0;
};

/**
 * Information gain as unknown volume in the camera's field of view, estimated by ray cubature
 * (as in AEP): rays on an azimuth x elevation grid, marched in radial steps until they hit an
 * occupied cell or leave the exploration box; every unknown sample adds the exact volume of its
 * spherical shell element.
 *
 * Discretisation: the steps are rounded so that the cells tile their ranges exactly: N azimuth
 * columns of width 2pi/N covering [i w, (i+1) w] (ray at the column centre), M elevation rings
 * tiling [pi/2 - vfov/2, pi/2 + vfov/2] (phi from +z), K shells tiling [0, range] with samples at
 * the shell mid-radii. A fully unknown, unobstructed view therefore sums to exactly the volume
 * range^3/3 * hfov * (cos phi_min - cos phi_max).
 *
 * The gain at a yaw weights each column by the fraction of its azimuth interval inside
 * [yaw - hfov/2, yaw + hfov/2], so the gain is continuous in yaw. bestYaw() computes all
 * columns once and sweeps candidate yaws in 1 degree steps.
 */
class GainEvaluator {
public:
    explicit GainEvaluator(const GainParams& params);

    /**
     * Unknown volume per azimuth column (column i spans [i, i+1] * columnWidth()). With
     * occluders, rays stop where they enter a body: the dynamic gain of DAEP.
     */
    std::vector<double> columns(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                                const std::vector<BodyOccluder>* occluders = nullptr) const;

    /**
     * DAEP's yaw angle booster (the paper's name; it boosts by distance to the box's border):
     * unknown samples within `distance` of an x or y face of the exploration box count `alpha`
     * times (alpha = 1: off, the default).
     */
    void setYawAngleBooster(double alpha, double distance);

    /** Gain seen at heading `yaw`; evaluates only the columns inside the field of view. */
    double gainAtYaw(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                     double yaw) const;

    /** The heading with the largest gain (first maximum of the 1 degree sweep). */
    YawGain bestYaw(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                    const std::vector<BodyOccluder>* occluders = nullptr) const;

    /** Columns at p without and with rays stopped by `occluders`. */
    struct ColumnViews {
        std::vector<double> open, occluded;
    };
    /**
     * Both column sets from one march: the rays stopped by a body see a prefix of what the
     * open rays see, so the occluded sums are the open ones' partial sums (bit for bit those of
     * columns(map, p, &occluders)).
     */
    ColumnViews columnsOpenAndOccluded(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                                       const std::vector<BodyOccluder>& occluders) const;

    /** Field-of-view window over precomputed columns. */
    double windowGain(const std::vector<double>& columns, double yaw) const;
    YawGain bestYaw(const std::vector<double>& columns) const;

    const GainParams& params() const { return params_; }
    int columnCount() const { return columns_; }
    double columnWidth() const { return columnWidth_; }
    /** Angular extent actually covered by the elevation rings, [phi_min, phi_max] from +z. */
    double phiMin() const { return cubature_.phiMin; }
    double phiMax() const { return cubature_.phiMax; }

private:
    /**
     * No ray from p can sample an unknown cell (ExplorationMap::mayMeetUnknown), so every
     * column is exactly 0; false when unsure, or when a sample step reaches a whole cell on
     * some axis (then a ray could pass a cell by).
     */
    bool seesNoUnknown(const mapping::ExplorationMap& map, const Eigen::Vector3d& p) const;
    double columnGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p, int column,
                      const std::vector<BodyOccluder>* occluders = nullptr) const;
    /** A column's gain {open, occluded}: rays marched to the box, the occluded sum stopped at
     * the first body. */
    std::pair<double, double> columnGains(const mapping::ExplorationMap& map,
                                          const Eigen::Vector3d& p, int column,
                                          const std::vector<BodyOccluder>* occluders) const;
    /** columnGains in code built for SSE4.1, where the machine has it: the same sums. */
    __attribute__((target("sse4.1"))) std::pair<double, double> columnGainsSse41(
        const mapping::ExplorationMap& map, const Eigen::Vector3d& p, int column,
        const std::vector<BodyOccluder>* occluders) const;
    template <bool kFloored>
    std::pair<double, double> columnGainsOn(const mapping::ExplorationMap& map,
                                            const Eigen::Vector3d& p, int column,
                                            const std::vector<BodyOccluder>* occluders) const;
    double yawAngleBoost(const Aabb& box, const Eigen::Vector3d& s) const;
    template <class ColumnFn>
    double window(double yaw, const ColumnFn& columnGainOf) const;
    /** Calls term(column, weight) for each column overlapping the field of view at yaw. */
    template <class TermFn>
    void windowTerms(double yaw, const TermFn& term) const;

    /** One column's share of a yaw's window: gain += weight * columns[column]. */
    struct WindowTerm {
        int column;
        double weight;
    };
    /** The windows of bestYaw's 1 degree sweep, computed once: sweepTerms_[sweepStart_[d]...]. */
    std::vector<WindowTerm> sweepTerms_;
    std::vector<std::size_t> sweepStart_;

    GainParams params_;
    int columns_ = 0;
    double columnWidth_ = 0.0;
    RayCubature cubature_;
    double longestAxisStep_ = 0.0;  ///< longest move of a ray's sample on one axis, from p on
    double boostAlpha_ = 1.0;
    double boostDistance_ = 0.0;
};

}  // namespace daep::planning
