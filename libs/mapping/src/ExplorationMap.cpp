#include "daep/mapping/ExplorationMap.h"

#include <fstream>

#include <cmath>
#include <limits>
#include <sstream>

#include "MapImpl.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"

namespace daep::mapping {
namespace {

constexpr double kGridMargin = 1.0;  // metres of dense grid around the exploration box
constexpr std::int64_t kMaxGridCells = std::int64_t(1) << 30;
constexpr std::size_t kMaxTreeStaleCells = std::size_t(1) << 18;

void validate(const MapParams& p, const Aabb& box) {
    std::ostringstream err;
    if (!(p.resolution > 0.0)) {
        err << "map resolution must be > 0 (got " << p.resolution << ")";
    } else if (!(p.maxRange > 0.0)) {
        err << "map maxRange must be > 0 (got " << p.maxRange << ")";
    } else if (!(p.probHit > 0.5 && p.probHit < 1.0) || !(p.probMiss > 0.0 && p.probMiss < 0.5)) {
        err << "map probHit must be in (0.5, 1) and probMiss in (0, 0.5) (got " << p.probHit << ", "
            << p.probMiss << ")";
    } else if (!(p.clampMin > 0.0 && p.clampMin < p.clampMax && p.clampMax < 1.0)) {
        err << "map clamping thresholds must satisfy 0 < clampMin < clampMax < 1 (got "
            << p.clampMin << ", " << p.clampMax << ")";
    } else if (!box.min.allFinite() || !box.max.allFinite() ||
               !(box.max.array() > box.min.array()).all()) {
        err << "exploration box must have max > min on every axis";
    }
    if (!err.str().empty()) {
        throw InputError(err.str());
    }
}

}  // namespace

ExplorationMap::Impl::Impl(const MapParams& params, const Aabb& box) : tree(params.resolution) {
    tree.setProbHit(params.probHit);
    tree.setProbMiss(params.probMiss);
    tree.setClampingThresMin(params.clampMin);
    tree.setClampingThresMax(params.clampMax);
    pointIndex.scale = 1.0 / tree.getResolution();  // axisKeyOf's factor, as OctoMap's own

    const Eigen::Vector3d lo = box.min.array() - kGridMargin;
    const Eigen::Vector3d hi = box.max.array() + kGridMargin;
    octomap::OcTreeKey kLo, kHi;
    if (!keyOf(lo, kLo) || !keyOf(hi, kHi)) {
        throw InputError("exploration box lies outside the octree's addressable range");
    }
    std::int64_t total = 1;
    const double half = 0.5 * tree.getResolution() * (1.0 + 1e-6);  // touchesBox's tolerance
    for (int a = 0; a < 3; ++a) {
        gridMin[a] = kLo[a];
        dims[a] = int(kHi[a]) - int(kLo[a]) + 1;
        total *= dims[a];
        inBox[a].resize(std::size_t(dims[a]));
        touchesBox[a].resize(std::size_t(dims[a]));
        for (int i = 0; i < dims[a]; ++i) {
            const double c = tree.keyToCoord(octomap::key_type(kLo[a] + i));
            inBox[a][std::size_t(i)] = c >= box.min[a] && c < box.max[a];
            touchesBox[a][std::size_t(i)] = c + half >= box.min[a] && c - half <= box.max[a];
        }
    }
    const int keyOfZero = tree.coordToKey(0.0);
    std::array<int, 3> low{};
    for (std::size_t a = 0; a < 3; ++a)
        low[a] = int(gridMin[a]) - keyOfZero;
    pointIndex = DenseGridIndex(pointIndex.scale, low, dims);
    if (total > kMaxGridCells) {
        std::ostringstream err;
        err << "exploration box needs " << total << " cells at resolution " << params.resolution
            << " m; too large for the dense grid";
        throw InputError(err.str());
    }
    cells.assign(std::size_t(total), std::uint8_t(CellState::Unknown));
    flags.assign(std::size_t(total), 0);
    treeStale.assign((std::size_t(total) + 63) / 64, 0);
    const std::size_t rows = std::size_t(dims[1]) * std::size_t(dims[2]);
    passWords = (dims[0] + 63) / 64;
    passBits.assign(rows * std::size_t(passWords), 0);
    passStale.assign(rows, 1);
    std::size_t blockCount = 1;
    for (std::size_t a = 0; a < 3; ++a) {
        blockDims[a] = ((dims[a] - 1) >> kBlockShift) + 1;
        blockCount *= std::size_t(blockDims[a]);
    }
    blocks.assign(blockCount, kBlockStale);
    logOddsBlocks.resize(blockCount);
}

CellState ExplorationMap::Impl::treeState(const octomap::OcTreeKey& key) const {
    const octomap::OcTreeNode* node = tree.search(key);
    if (node == nullptr) {
        return CellState::Unknown;
    }
    return tree.isNodeOccupied(node) ? CellState::Occupied : CellState::Free;
}

bool ExplorationMap::Impl::keyInBox(const octomap::OcTreeKey& key) const {
    for (int a = 0; a < 3; ++a) {
        const int i = int(key[a]) - int(gridMin[a]);
        if (i < 0 || i >= dims[a] || !inBox[a][std::size_t(i)]) {
            return false;
        }
    }
    return true;
}

bool ExplorationMap::Impl::mark(const octomap::OcTreeKey& key, std::uint8_t m) {
    const std::int64_t i = gridIndex(key);
    return i >= 0 ? markCell(i, m) : markOutside(key, m);
}

bool ExplorationMap::Impl::markOutside(const octomap::OcTreeKey& key, std::uint8_t m) {
    octomap::KeySet& outside = m == kFreeNow       ? freeOutside
                               : m == kOccupiedNow ? occupiedOutside
                                                   : endsOutside;
    return outside.insert(key).second;
}

bool ExplorationMap::Impl::walkStaysOnGrid(const octomap::OcTreeKey& from,
                                           const octomap::OcTreeKey& to) const {
    for (std::size_t a = 0; a < 3; ++a) {
        const int lo = std::min(int(from[a]), int(to[a])) - 1 - int(gridMin[a]);
        const int hi = std::max(int(from[a]), int(to[a])) + 1 - int(gridMin[a]);
        if (lo < 0 || hi >= dims[a])
            return false;
    }
    return true;
}

/**
 * Marks free the cells OctoMap's computeRayKeys lists for origin-end (the traversal of Amanatides
 * and Woo with OctoMap's own arithmetic, so the very same cells: the first, then each one
 * entered before the end's cell or the end's distance), as they are walked rather than
 * collected, with the dense index stepped along.
 */
void ExplorationMap::Impl::markRay(const octomap::point3d& origin, const octomap::point3d& end) {
    octomap::OcTreeKey key, last;
    if (!keyOf(origin, key) || !keyOf(end, last) || key == last)
        return;
    octomap::point3d dir = end - origin;
    const float length = float(dir.norm());
    dir /= length;
    const double res = tree.getResolution();
    constexpr double kNever = std::numeric_limits<double>::max();
    std::array<int, 3> step{};
    std::array<double, 3> tNext{kNever, kNever, kNever}, tDelta{kNever, kNever, kNever};
    for (std::size_t a = 0; a < 3; ++a) {
        step[a] = dir(unsigned(a)) > 0.0f ? 1 : (dir(unsigned(a)) < 0.0f ? -1 : 0);
        if (step[a] == 0)
            continue;
        double border = tree.keyToCoord(key[a]);
        border += float(step[a] * res * 0.5);
        tNext[a] = (border - origin(unsigned(a))) / dir(unsigned(a));
        tDelta[a] = res / std::fabs(dir(unsigned(a)));
    }
    // The walk with its state in registers: one branch per axis instead of indexed arrays.
    double tx = tNext[0], ty = tNext[1], tz = tNext[2];
    const auto walk = [&](const auto& markHere, const auto& stepAxis, const auto& atLast) {
        for (;;) {
            markHere();
            if (tx < ty) {
                if (tx < tz)
                    stepAxis(0, tx);
                else
                    stepAxis(2, tz);
            } else if (ty < tz) {
                stepAxis(1, ty);
            } else {
                stepAxis(2, tz);
            }
            if (atLast() || std::min(std::min(tx, ty), tz) > length)
                return;
        }
    };
    const std::array<std::int64_t, 3> stride{1, dims[0], std::int64_t(dims[0]) * dims[1]};
    std::int64_t index = gridIndex(key);  // stepped along while the walk stays on the grid
    if (walkStaysOnGrid(key, last)) {
        // No key, no bounds: the dense index alone.
        const std::array<std::int64_t, 3> indexStep{step[0] * stride[0], step[1] * stride[1],
                                                    step[2] * stride[2]};
        const std::int64_t lastIndex = gridIndex(last);
        walk([&] { markCell(index, kFreeNow); },
             [&](std::size_t a, double& t) {
                 t += tDelta[a];
                 index += indexStep[a];
             },
             [&] { return index == lastIndex; });
        return;
    }
    walk([&] { index >= 0 ? markCell(index, kFreeNow) : markOutside(key, kFreeNow); },
         [&](std::size_t a, double& t) {
             key[a] = octomap::key_type(key[a] + step[a]);
             t += tDelta[a];
             const int c = int(key[a]) - int(gridMin[a]);
             index =
                 index >= 0 && c >= 0 && c < dims[a] ? index + step[a] * stride[a] : gridIndex(key);
         },
         [&] { return key == last; });
}

bool ExplorationMap::Impl::applyUpdate(const octomap::OcTreeKey& key, bool hit) {
    const std::int64_t i = gridIndex(key);
    if (i < 0) {
        // Not lazy: updateInnerOccupancy() after each frame walks the whole tree (about 30 ms
        // at 2e6 leaves); eager updates cost O(frame) and keep the tree pruned.
        tree.updateNode(key, hit, false);
        return false;
    }
    std::uint8_t& f = flags[std::size_t(i)];
    // OctoMap leaves a clamped cell as it is; the flag says so.
    if (f & (hit ? kClampedOccupied : kClampedFree))
        return false;
    // OctoMap's updateNodeLogOdds, in the same float arithmetic.
    float& value = logOddsAt(int(key[0]) - int(gridMin[0]), int(key[1]) - int(gridMin[1]),
                             int(key[2]) - int(gridMin[2]));
    value += hit ? tree.getProbHitLog() : tree.getProbMissLog();
    if (value < tree.getClampingThresMinLog())
        value = tree.getClampingThresMinLog();
    else if (value > tree.getClampingThresMaxLog())
        value = tree.getClampingThresMaxLog();
    std::uint64_t& staleWord = treeStale[std::size_t(i) >> 6];
    const std::uint64_t staleBit = std::uint64_t(1) << (i & 63);
    if (!(staleWord & staleBit)) {
        staleWord |= staleBit;
        treeStaleCells.push_back(i);
    }
    std::uint8_t& cell = cells[std::size_t(i)];
    const std::uint8_t before = cell, hitBefore = f & kEverHit;
    const bool newlyKnown = cell == std::uint8_t(CellState::Unknown) && keyInBox(key);
    if (hit && (f & kClampedFree))
        f |= kMovedIn;
    cell =
        std::uint8_t(value >= tree.getOccupancyThresLog() ? CellState::Occupied : CellState::Free);
    f &= std::uint8_t(~(kClampedFree | kClampedOccupied));
    if (value <= tree.getClampingThresMinLog())
        f |= kClampedFree;
    else if (value >= tree.getClampingThresMaxLog())
        f |= kClampedOccupied;
    f |= std::uint8_t(hit ? kEverHit : 0);
    if (cell != before || (f & kEverHit) != hitBefore)
        passCellChanged(i);
    if (cell != before)
        frontierCellChanged(i);
    return newlyKnown;
}

/**
 * Each changed cell set to its value with the tree kept pruned, as its updates one by one
 * would have left it: a node is pruned when its eight children are leaves of one value, and
 * every change re-checks the nodes above it, so the tree depends on its leaves' values alone.
 */
void ExplorationMap::Impl::flushTree() const {
    for (const std::int64_t i : treeStaleCells) {
        const std::array<int, 3> c = cellOfIndex(i);
        tree.setNodeValue(keyOfCell(c), updatedLogOdds(c[0], c[1], c[2]), false);
        treeStale[std::size_t(i) >> 6] &= ~(std::uint64_t(1) << (i & 63));
    }
    treeStaleCells.clear();
}

/**
 * OctoMap's discrete update (each end point reduced to its cell's centre once; a ray cleared up
 * to it, or up to maxRange, and its cell marked occupied if within range; occupied wins over
 * free), with the frame's cells deduplicated by marks on the dense grid instead of hash sets.
 * Every cell is updated once per frame, so the order of updates does not change the tree.
 */
std::size_t ExplorationMap::Impl::integrate(const octomap::point3d& origin, double maxRange) {
    for (const octomap::OcTreeKey& key : ends) {
        const octomap::point3d end = tree.keyToCoord(key);
        if ((end - origin).norm() <= maxRange) {
            markRay(origin, end);
            mark(key, kOccupiedNow);
        } else {
            markRay(origin, origin + (end - origin).normalized() * maxRange);
        }
    }
    for (const octomap::OcTreeKey& key : personKeys)
        markRay(origin, tree.keyToCoord(key));
    personKeys.clear();
    ends.clear();

    std::size_t newlyKnown = 0;
    for (const std::int64_t i : marked) {
        std::uint8_t& f = flags[std::size_t(i)];
        if (f & (kFreeNow | kOccupiedNow))
            newlyKnown += applyUpdate(keyOfIndex(i), (f & kOccupiedNow) != 0);
        f &= std::uint8_t(~kFrameMarks);
    }
    marked.clear();
    for (const octomap::OcTreeKey& key : freeOutside)
        if (occupiedOutside.count(key) == 0)
            applyUpdate(key, false);
    for (const octomap::OcTreeKey& key : occupiedOutside)
        applyUpdate(key, true);
    freeOutside.clear();
    occupiedOutside.clear();
    endsOutside.clear();
    // The list of cells the tree has yet to take stays within a few MB, however rarely it is read.
    if (treeStaleCells.size() > kMaxTreeStaleCells)
        flushTree();
    return newlyKnown;
}

ExplorationMap::ExplorationMap(const MapParams& params, const Aabb& explorationBox)
    : params_(params), box_(explorationBox) {
    validate(params, explorationBox);
    impl_ = std::make_unique<Impl>(params, explorationBox);
    gridIndex_ = impl_->pointIndex;
    gridCells_ = impl_->cells.data();  // the grid is never resized
}

ExplorationMap::~ExplorationMap() = default;

void ExplorationMap::setPeopleMapped(bool mapped) {
    impl_->setGuardGrazed(!mapped);
}

void ExplorationMap::insertPointCloud(const Eigen::Vector3d& origin,
                                      const std::vector<Eigen::Vector3f>& points) {
    for (const auto& p : points)
        if (p.allFinite())
            impl_->addEndPoint(octomap::point3d(p.x(), p.y(), p.z()));
    const octomap::point3d o(float(origin.x()), float(origin.y()), float(origin.z()));
    knownInBox_ += impl_->integrate(o, params_.maxRange);
    ++revision_;
}

bool ExplorationMap::movedIn(const Eigen::Vector3d& p) const {
    const std::int64_t i = gridIndex_(p);
    return i >= 0 && (impl_->flags[std::size_t(i)] & Impl::kMovedIn);
}

CellState ExplorationMap::stateOffGrid(const Eigen::Vector3d& p) const {
    octomap::OcTreeKey key;
    if (!impl_->keyOf(p, key)) {
        return CellState::Unknown;
    }
    return impl_->stateAt(key);
}

double ExplorationMap::knownVolumeInBox() const {
    return double(knownInBox_) * std::pow(params_.resolution, 3);
}

double ExplorationMap::coverage() const {
    // A box not aligned to the grid can hold slightly more cell centres than its volume allows.
    return std::min(1.0, knownVolumeInBox() / box_.volume());
}

const octomap::OcTree& ExplorationMap::octree() const {
    impl_->flushTree();
    return impl_->tree;
}

Eigen::Vector3d ExplorationMap::cellCenter(const Eigen::Vector3d& p) const {
    octomap::OcTreeKey key;
    if (!impl_->keyOf(p, key)) {
        return p;
    }
    const auto& t = impl_->tree;
    return {t.keyToCoord(key[0]), t.keyToCoord(key[1]), t.keyToCoord(key[2])};
}

bool ExplorationMap::writeBinary(const std::string& path) const {
    // The .bt header written by hand: OcTree::writeBinaryConst prints debug text to stderr.
    std::ofstream out(path, std::ios::binary);
    if (!out)
        return false;
    const auto& t = octree();
    out << "# Octomap OcTree binary file\n"
        << "id " << t.getTreeType() << "\n"
        << "size " << t.size() << "\n"
        << "res " << t.getResolution() << "\n"
        << "data\n";
    try {
        t.writeBinaryData(out);
    } catch (const std::exception&) {
        return false;
    }
    return bool(out.flush());
}

MapParams MapParams::fromConfig(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "map");
    MapParams p;
    p.resolution = requirePositive(r, "resolution");
    p.maxRange = requirePositive(r, "max_range");
    p.probHit = requireBetween(r, "prob_hit", 0.5, 1.0);
    p.probMiss = requireBetween(r, "prob_miss", 0.0, 0.5);
    p.clampMin = r.requireDouble("clamp_min");
    p.clampMax = r.requireDouble("clamp_max");
    p.noReturnIsFree = r.requireBool("no_return_free");
    p.bodyHalfExtents = 0.5 * requirePositiveXyz(ConfigReader(cfg, "drone"), "box");
    return p;
}

}  // namespace daep::mapping
