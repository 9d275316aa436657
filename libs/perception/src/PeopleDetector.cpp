#include "daep/perception/PeopleDetector.h"

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <unordered_map>

#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/mapping/DepthRays.h"
#include "daep/mapping/DepthUnprojection.h"
#include "daep/mapping/ExplorationMap.h"

namespace daep::perception {
namespace {

using mapping::CellState;
using mapping::SensorFrame;
using mapping::sensorFrameInWorld;

void validate(const DetectorParams& p) {
    if (!(p.maxRange > 0) || !(p.ceilingHeight > p.floorHeight) || p.morphKernel < 1 ||
        p.pixelStride < 1 || !(p.sigmaAlong > 0) || !(p.sigmaAcross > 0) ||
        !(p.sideSigmaAcross > 0) || p.imprintKeep < 0 || !(p.depthJump > 0) ||
        p.minEvidenceFraction < 0 || p.minEvidenceFraction > 1)
        throw std::invalid_argument("PeopleDetector: invalid parameters");
}

/** Per-pixel class against the map. */
enum PixelClass : std::uint8_t {
    kIgnored = 0,      ///< no return, out of range or out of the height band
    kStatic = 1,       ///< on a static surface the map holds occupied
    kUnexplained = 2,  ///< in unknown space: may be a person, may be unseen static geometry
    kRemembered = 3,   ///< in a cell a person was found in lately
    kFresh = 4,        ///< contradicts the map now: known free, or seen through an occupied cell
};

/** Sums of one group of pixels (a connected component, or several merged). */
struct Group {
    std::vector<int> pixels;  ///< indices into the pixel grid
    double area = 0.0, evidenceArea = 0.0, freshArea = 0.0;
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();  ///< area-weighted point sum
    double zMin = 1e9, zMax = -1e9;

    Eigen::Vector3d centroid() const { return weighted / area; }
    void absorb(Group& other) {
        pixels.insert(pixels.end(), other.pixels.begin(), other.pixels.end());
        area += other.area;
        evidenceArea += other.evidenceArea;
        freshArea += other.freshArea;
        weighted += other.weighted;
        zMin = std::min(zMin, other.zMin);
        zMax = std::max(zMax, other.zMax);
        other = Group{};
    }
};

}  // namespace

class PeopleDetector::Impl {
public:
    explicit Impl(const DetectorParams& p) : params(p) {}

    std::vector<PersonMeasurement> detect(const mrpt::obs::CObservation3DRangeScan& obs,
                                          const FlatPose& robot,
                                          const mapping::ExplorationMap& map) {
        if (!obs.hasRangeImage)
            throw std::invalid_argument("PeopleDetector: observation has no range image");
        now = mrpt::Clock::toDouble(obs.timestamp);
        cellSize = map.resolution();
        forgetOldImprint();
        frame = sensorFrameInWorld(obs, robot);
        classifyPixels(obs, map);
        cutAtDepthJumps();
        removeSpeckles();
        std::vector<Group> groups = mergeNearbyGroups(connectedGroups());
        detections.clear();
        detectionPixels.clear();
        for (const Group& g : groups)
            if (!g.pixels.empty())
                acceptIfPerson(g);
        rememberPeopleCells(map);
        std::vector<PersonMeasurement> out;
        out.reserve(detections.size());
        for (const PersonDetection& d : detections)
            out.push_back(d.measurement);
        return out;
    }

    DetectorParams params;
    std::vector<PersonDetection> detections;

private:
    // --- the cells of people found lately -------------------------------------------------

    std::uint64_t cellKey(const Eigen::Vector3f& p) const {
        const auto axis = [this](float c) {
            return std::uint64_t(std::int64_t(std::floor(c / cellSize)) + (1 << 20)) & 0x1FFFFF;
        };
        return axis(p.x()) | axis(p.y()) << 21 | axis(p.z()) << 42;
    }

    bool nearImprint(const Eigen::Vector3f& p) const {
        return !imprint.empty() && (p.array() >= imprintMin.array()).all() &&
               (p.array() <= imprintMax.array()).all();
    }

    bool imprinted(const Eigen::Vector3f& p) const {
        if (!nearImprint(p))
            return false;
        const auto it = imprint.find(cellKey(p));
        return it != imprint.end() && now - it->second.time <= params.imprintKeep;
    }

    void forgetOldImprint() {
        imprintMin.setConstant(1e9f);
        imprintMax.setConstant(-1e9f);
        for (auto it = imprint.begin(); it != imprint.end();) {
            if (now - it->second.time > params.imprintKeep || now < it->second.time) {
                it = imprint.erase(it);
                continue;
            }
            imprintMin = imprintMin.cwiseMin(it->second.point);
            imprintMax = imprintMax.cwiseMax(it->second.point);
            ++it;
        }
        const float margin = float(cellSize);
        imprintMin.array() -= margin;
        imprintMax.array() += margin;
    }

    void remember(const Eigen::Vector3f& p) { imprint[cellKey(p)] = {now, p}; }

    /**
     * The cells of each person's points, and the unknown cells of its body box (its interior,
     * which it walks into when it walks away from the camera).
     */
    void rememberPeopleCells(const mapping::ExplorationMap& map) {
        const float step = float(cellSize);
        const float half = float(params.bodyHalfWidth);
        for (std::size_t k = 0; k < detections.size(); ++k) {
            if (detectionPixels[k].empty())
                continue;
            for (const int i : detectionPixels[k])
                remember(points[std::size_t(i)]);
            const Eigen::Vector2f c = detections[k].measurement.position.cast<float>();
            for (float x = c.x() - half; x <= c.x() + half; x += step)
                for (float y = c.y() - half; y <= c.y() + half; y += step)
                    for (float z = float(params.floorHeight); z <= float(params.bodyHeight);
                         z += step) {
                        const Eigen::Vector3f p(x, y, z);
                        if (map.state(p.cast<double>()) == CellState::Unknown)
                            remember(p);
                    }
        }
    }

    // --- per pixel --------------------------------------------------------------------------

    /** A free point just in front of a static occupied cell is that surface, seen noisily. */
    bool staticSurfaceBehind(const Eigen::Vector3f& p, const mapping::ExplorationMap& map) const {
        const Eigen::Vector3f ray = (p - frame.origin).normalized();
        const Eigen::Vector3f q = p + float(params.surfaceMargin) * ray;
        return map.state(q.cast<double>()) == CellState::Occupied && !imprinted(q);
    }

    /**
     * A point in unknown space whose ray has just crossed a cell the map holds occupied: what
     * was there has moved on (a person walking away from the camera), as static things do not.
     */
    bool seenThroughOccupied(const Eigen::Vector3f& p, const mapping::ExplorationMap& map) const {
        if (!(params.seeThroughDepth > 0))
            return false;
        const Eigen::Vector3f ray = (p - frame.origin).normalized();
        for (float back = float(cellSize); back <= float(params.seeThroughDepth) + 1e-4f;
             back += float(cellSize))
            if (map.state((p - back * ray).cast<double>()) == CellState::Occupied)
                return true;
        return false;
    }

    PixelClass classify(const Eigen::Vector3f& p, const mapping::ExplorationMap& map) const {
        if (p.z() < params.floorHeight || p.z() > params.ceilingHeight)
            return kIgnored;
        switch (map.state(p.cast<double>())) {
            case CellState::Free:
                return staticSurfaceBehind(p, map) ? kStatic : kFresh;
            case CellState::Occupied:
                return imprinted(p) ? kRemembered : kStatic;
            case CellState::Unknown:
                break;
        }
        if (seenThroughOccupied(p, map))
            return kFresh;
        return imprinted(p) ? kRemembered : kUnexplained;
    }

    void classifyPixels(const mrpt::obs::CObservation3DRangeScan& obs,
                        const mapping::ExplorationMap& map) {
        const auto& image = obs.rangeImage;
        const int stride = params.pixelStride;
        rows = (int(image.rows()) + stride - 1) / stride;
        cols = (int(image.cols()) + stride - 1) / stride;
        const auto& cam = obs.cameraParams;
        fx = float(cam.fx());
        const float fy = float(cam.fy());
        pixelArea = float(stride * stride) / (fx * fy);  // times depth^2: m^2 per pixel
        depth.create(rows, cols);
        classes.create(rows, cols);
        points.resize(std::size_t(rows * cols));
        const float maxRange = float(params.maxRange);
        const mapping::DepthRays rays(obs);
        for (int r = 0; r < rows; ++r) {
            const int v = r * stride;
            const float kz = rays.up(v);
            const Eigen::Vector3f rowDir = frame.forward + kz * frame.up;
            float* depthRow = depth.ptr<float>(r);
            std::uint8_t* classRow = classes.ptr<std::uint8_t>(r);
            for (int c = 0; c < cols; ++c) {
                const int u = c * stride;
                const float ky = rays.left(u);
                const float d = rays.depthOf(float(image(v, u)) * obs.rangeUnits, ky, kz);
                if (!(d > 0.0f && d <= maxRange)) {
                    depthRow[c] = 0.0f;
                    classRow[c] = kIgnored;
                    continue;
                }
                const Eigen::Vector3f p = frame.origin + d * (rowDir + ky * frame.left);
                points[std::size_t(r * cols + c)] = p;
                depthRow[c] = d;
                classRow[c] = classify(p, map);
            }
        }
    }

    /**
     * Pixels where the depth steps by more than a surface could at the steepest grazing angle
     * (or by depthJump, whichever is more) belong to no object: they split objects apart.
     */
    void cutAtDepthJumps() {
        const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
        cv::morphologyEx(depth, depthStep, cv::MORPH_GRADIENT, kernel);
        // A 3 x 3 gradient spans two pixels of depth * stride / fx each, times tan(grazing).
        const double perMetre = 2.0 * params.pixelStride * std::tan(params.maxGrazingAngle) / fx;
        cv::max(depth * perMetre, params.depthJump, stepLimit);
        cv::compare(classes, kStatic, mask, cv::CMP_GT);
        mask.setTo(0, depthStep > stepLimit);
    }

    void removeSpeckles() {
        if (params.morphKernel <= 1)
            return;
        const int k = params.morphKernel;
        const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k));
        cv::morphologyEx(mask, mask, cv::MORPH_OPEN, kernel);
    }

    // --- groups -----------------------------------------------------------------------------

    std::vector<Group> connectedGroups() {
        const int n = cv::connectedComponents(mask, labels, 8, CV_32S);
        std::vector<Group> groups(std::size_t(std::max(0, n - 1)));
        for (int r = 0; r < rows; ++r) {
            const int* labelRow = labels.ptr<int>(r);
            const float* depthRow = depth.ptr<float>(r);
            const std::uint8_t* classRow = classes.ptr<std::uint8_t>(r);
            for (int c = 0; c < cols; ++c) {
                if (labelRow[c] == 0)
                    continue;
                Group& g = groups[std::size_t(labelRow[c] - 1)];
                const int i = r * cols + c;
                const Eigen::Vector3f& p = points[std::size_t(i)];
                const double a = double(pixelArea) * depthRow[c] * depthRow[c];
                g.pixels.push_back(i);
                g.area += a;
                g.evidenceArea += classRow[c] >= kRemembered ? a : 0.0;
                g.freshArea += classRow[c] == kFresh ? a : 0.0;
                g.weighted += a * p.cast<double>();
                g.zMin = std::min(g.zMin, double(p.z()));
                g.zMax = std::max(g.zMax, double(p.z()));
            }
        }
        return groups;
    }

    /**
     * One person cut in pieces (two faces seen at a corner, an occluder, a depth step) becomes
     * one group again, when the pieces are close and together still fit a person.
     */
    std::vector<Group> mergeNearbyGroups(std::vector<Group> groups) const {
        const double limit2 = params.mergeDistance * params.mergeDistance;
        for (std::size_t a = 0; a < groups.size(); ++a) {
            for (std::size_t b = a + 1; b < groups.size() && !groups[a].pixels.empty(); ++b) {
                if (groups[b].pixels.empty())
                    continue;
                const Eigen::Vector2d d =
                    groups[a].centroid().head<2>() - groups[b].centroid().head<2>();
                if (d.squaredNorm() >= limit2)
                    continue;
                Group merged = groups[a];
                Group other = groups[b];
                merged.absorb(other);
                if (!extentsFitPerson(merged))
                    continue;
                groups[a] = std::move(merged);
                groups[b] = Group{};
                b = a;  // its centroid moved: look at all others again
            }
        }
        return groups;
    }

    /** Horizontal viewing direction from the sensor to the group's centroid. */
    Eigen::Vector2d viewDirection(const Group& g) const {
        const Eigen::Vector2d along =
            g.centroid().head<2>() - frame.origin.head<2>().cast<double>();
        return along.norm() < 1e-6 ? Eigen::Vector2d(1, 0) : along.normalized();
    }

    bool extentsFitPerson(const Group& g) const {
        const Eigen::Vector2d e = horizontalExtents(g, viewDirection(g));
        return e.x() <= params.maxWidth && e.y() <= params.maxDepthSpread;
    }

    /** Extents of a group across and along the horizontal viewing direction. */
    Eigen::Vector2d horizontalExtents(const Group& g, const Eigen::Vector2d& along) const {
        const Eigen::Vector2d across(-along.y(), along.x());
        double aMin = 1e9, aMax = -1e9, cMin = 1e9, cMax = -1e9;
        const Eigen::Vector2d o = frame.origin.head<2>().cast<double>();
        for (const int i : g.pixels) {
            const Eigen::Vector2d q = points[std::size_t(i)].head<2>().cast<double>() - o;
            const double a = q.dot(along), c = q.dot(across);
            aMin = std::min(aMin, a);
            aMax = std::max(aMax, a);
            cMin = std::min(cMin, c);
            cMax = std::max(cMax, c);
        }
        return {cMax - cMin, aMax - aMin};
    }

    bool sizeFitsPerson(const Group& g) const {
        const DetectorParams& p = params;
        return g.area >= p.minArea && g.zMax <= p.maxPersonTop &&
               g.zMax - g.zMin >= p.minVerticalExtent && extentsFitPerson(g);
    }

    /** Which of the image's side edges cut the group: the body goes on beyond them, unseen. */
    struct SideCut {
        bool left = false, right = false;
        bool any() const { return left || right; }
    };
    SideCut sideCut(const Group& g) const {
        SideCut cut;
        for (const int i : g.pixels) {
            cut.left = cut.left || i % cols == 0;
            cut.right = cut.right || i % cols == cols - 1;
        }
        return cut;
    }

    /**
     * The body centre: behind the visible surface along the view and, when one side edge of
     * the image cuts the body, beyond the visible part towards that edge, by half the width not
     * seen. The visible part's centroid alone puts a person leaving the view inside it, and a
     * track then takes up a sideways velocity from the last detections.
     */
    Eigen::Vector2d bodyCentre(const Group& g, const Eigen::Vector2d& along,
                               const SideCut& cut) const {
        const Eigen::Vector2d centre = g.centroid().head<2>() + params.centreOffset * along;
        if (cut.left == cut.right)
            return centre;
        const Eigen::Vector2d left(-along.y(), along.x());
        const double seen = horizontalExtents(g, along).x();
        const double unseen = std::max(0.0, params.bodyHalfWidth - 0.5 * seen);
        return centre + (cut.left ? unseen : -unseen) * left;
    }

    void acceptIfPerson(const Group& g) {
        const double evidence = g.evidenceArea / g.area;
        if (evidence < params.minEvidenceFraction || !sizeFitsPerson(g))
            return;
        const Eigen::Vector3d centroid = g.centroid();
        const Eigen::Vector2d along = viewDirection(g);
        PersonDetection d;
        d.measurement.id = -1;
        const SideCut cut = sideCut(g);
        d.measurement.position = bodyCentre(g, along, cut);
        Eigen::Matrix2d axes;
        axes.col(0) = along;
        axes.col(1) = Eigen::Vector2d(-along.y(), along.x());
        d.cutBySide = cut.any();
        const double across = d.cutBySide ? params.sideSigmaAcross : params.sigmaAcross;
        const Eigen::Vector2d var(params.sigmaAlong * params.sigmaAlong, across * across);
        d.measurement.covariance = axes * var.asDiagonal() * axes.transpose();
        d.surfaceCentroid = centroid;
        d.area = g.area;
        d.evidenceFraction = evidence;
        d.pixels = int(g.pixels.size());
        detections.push_back(d);
        // Remembering only what the map contradicts now bounds how long anything the map
        // explains (a false detection, a person standing still) is kept alive: imprintKeep.
        detectionPixels.emplace_back();
        if (g.freshArea >= params.minFreshFraction * g.area)
            detectionPixels.back() = g.pixels;
    }

    struct ImprintCell {
        double time = 0.0;
        Eigen::Vector3f point = Eigen::Vector3f::Zero();
    };

    SensorFrame frame{};
    double now = 0.0;
    double cellSize = 0.2;
    int rows = 0, cols = 0;
    float pixelArea = 0.0f;
    float fx = 1.0f;
    cv::Mat1f depth, depthStep, stepLimit;
    cv::Mat1b classes, mask;
    cv::Mat1i labels;
    std::vector<Eigen::Vector3f> points;  ///< world point of each grid pixel with a return
    std::vector<std::vector<int>> detectionPixels;
    std::unordered_map<std::uint64_t, ImprintCell> imprint;
    Eigen::Vector3f imprintMin = Eigen::Vector3f::Zero(), imprintMax = Eigen::Vector3f::Zero();
};

PeopleDetector::PeopleDetector(const DetectorParams& params)
    : params_(params), impl_(std::make_unique<Impl>(params)) {
    validate(params);
}

PeopleDetector::~PeopleDetector() = default;
PeopleDetector::PeopleDetector(PeopleDetector&&) noexcept = default;
PeopleDetector& PeopleDetector::operator=(PeopleDetector&&) noexcept = default;

std::vector<PersonMeasurement> PeopleDetector::detect(const mrpt::obs::CObservation3DRangeScan& obs,
                                                      const FlatPose& robot,
                                                      const mapping::ExplorationMap& map) {
    return impl_->detect(obs, robot, map);
}

const std::vector<PersonDetection>& PeopleDetector::lastDetections() const {
    return impl_->detections;
}

DetectorParams DetectorParams::fromConfig(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "detector");
    DetectorParams p;
    p.maxRange = requirePositive(r, "max_range");
    p.floorHeight = r.requireDouble("floor_height");
    p.ceilingHeight = r.requireDouble("ceiling_height");
    if (!(p.ceilingHeight > p.floorHeight))
        failRange(r, "ceiling_height", p.ceilingHeight, "must be above floor_height");
    p.maxPersonTop = requirePositive(r, "max_person_top");
    p.minVerticalExtent = requireNonNegative(r, "min_vertical_extent");
    p.maxWidth = requirePositive(r, "max_width");
    p.maxDepthSpread = requirePositive(r, "max_depth_spread");
    p.minArea = requireNonNegative(r, "min_area");
    p.minEvidenceFraction = requireNonNegative(r, "min_evidence_fraction");
    if (p.minEvidenceFraction > 1)
        failRange(r, "min_evidence_fraction", p.minEvidenceFraction, "must be in [0, 1]");
    p.depthJump = requirePositive(r, "depth_jump");
    p.maxGrazingAngle = requireBetween(r, "max_grazing_deg", 0.0, 90.0) * M_PI / 180.0;
    p.morphKernel = requireIntAtLeast(r, "morph_kernel_px", 1);
    p.surfaceMargin = requireNonNegative(r, "surface_margin");
    p.centreOffset = requireNonNegative(r, "centre_offset");
    p.mergeDistance = requireNonNegative(r, "merge_distance");
    p.sigmaAlong = requirePositive(r, "sigma_along");
    p.sigmaAcross = requirePositive(r, "sigma_across");
    p.sideSigmaAcross = requirePositive(r, "side_sigma_across");
    p.imprintKeep = requireNonNegative(r, "imprint_keep_s");
    p.minFreshFraction = requireNonNegative(r, "min_fresh_fraction");
    p.seeThroughDepth = requireNonNegative(r, "see_through_depth");
    p.bodyHalfWidth = requirePositive(r, "body_half_width");
    p.bodyHeight = requirePositive(r, "body_height");
    p.pixelStride = requireIntAtLeast(r, "pixel_stride", 1);
    return p;
}

}  // namespace daep::perception
