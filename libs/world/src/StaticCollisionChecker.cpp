#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "Sat.h"
#include "Shapes.h"
#include "daep/world/RayCaster.h"

namespace daep::world {
namespace {

using Box3 = Eigen::AlignedBox3d;

enum class Kind : std::uint8_t { Box, Prism, Triangle, AlignedBox };

struct Primitive {
    Box3 bounds;
    Kind kind;
    std::uint32_t index;
};

/** A box or a cylinder's circumscribed prism, ready for the SAT. */
struct Polytope {
    std::vector<Eigen::Vector3d> vertices, normals, edges;

    ConvexView view() const {
        return {vertices.data(), static_cast<int>(vertices.size()),
                normals.data(),  static_cast<int>(normals.size()),
                edges.data(),    static_cast<int>(edges.size())};
    }
    Box3 bounds() const {
        Box3 b;
        for (const auto& v : vertices)
            b.extend(v);
        return b;
    }
};

Polytope boxPolytope(const BoxShape& b) {
    Polytope p;
    for (const auto& c : boxCorners(b.pose, b.size))
        p.vertices.push_back(c);
    for (int i = 0; i < 3; ++i)
        p.normals.push_back(b.pose.linear().col(i));
    p.edges = p.normals;
    return p;
}

/** Circumscribed so that the prism contains the cylinder: conservative by < 0.5 % of r. */
Polytope prismPolytope(const CylinderShape& c) {
    constexpr int n = kCylinderSegments;
    Polytope p;
    p.vertices = cylinderPrismVertices(c, 1.0 / std::cos(M_PI / n));
    const Eigen::Vector3d axis = c.pose.linear().col(2);
    p.normals.push_back(axis);
    p.edges.push_back(axis);
    for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d edge = (p.vertices[(i + 1) % n] - p.vertices[i]).normalized();
        p.edges.push_back(edge);
        p.normals.push_back(edge.cross(axis));
    }
    return p;
}

/** Flat bounding volume hierarchy over primitive bounds (median splits, small leaves). */
class Bvh {
public:
    void build(std::vector<Primitive> prims) {
        prims_ = std::move(prims);
        nodes_.clear();
        if (!prims_.empty())
            buildNode(0, prims_.size());
    }

    /** Calls hit(primitive) for primitives whose bounds meet `query`; stops when it returns true.
     */
    template <typename Hit>
    bool any(const Box3& query, Hit&& hit) const {
        if (nodes_.empty())
            return false;
        std::array<std::uint32_t, 128> stack;
        std::size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!node.bounds.intersects(query))
                continue;
            if (node.count > 0) {
                for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
                    if (prims_[i].bounds.intersects(query) && hit(prims_[i]))
                        return true;
            } else {
                stack[top++] = node.first;  // left child
                stack[top++] = node.right;
            }
        }
        return false;
    }

private:
    struct Node {
        Box3 bounds;
        std::uint32_t first = 0;  ///< first primitive (leaf) or left child (inner)
        std::uint32_t count = 0;  ///< 0 for inner nodes
        std::uint32_t right = 0;
    };
    static constexpr std::size_t kLeafSize = 4;

    std::uint32_t buildNode(std::size_t begin, std::size_t end) {
        const auto id = static_cast<std::uint32_t>(nodes_.size());
        nodes_.emplace_back();
        Box3 bounds;
        for (std::size_t i = begin; i < end; ++i)
            bounds.extend(prims_[i].bounds);
        nodes_[id].bounds = bounds;
        if (end - begin <= kLeafSize) {
            nodes_[id].first = static_cast<std::uint32_t>(begin);
            nodes_[id].count = static_cast<std::uint32_t>(end - begin);
            return id;
        }
        Eigen::Index axis;
        bounds.sizes().maxCoeff(&axis);
        const std::size_t mid = (begin + end) / 2;
        std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                         [axis](const Primitive& a, const Primitive& b) {
                             return a.bounds.center()[axis] < b.bounds.center()[axis];
                         });
        const std::uint32_t left = buildNode(begin, mid);
        const std::uint32_t right = buildNode(mid, end);
        nodes_[id].first = left;
        nodes_[id].right = right;
        return id;
    }

    std::vector<Primitive> prims_;
    std::vector<Node> nodes_;
};

bool overlapsTriangle(const Obb& box, const std::array<Eigen::Vector3d, 3>& t) {
    std::array<Eigen::Vector3d, 3> edges;
    for (int i = 0; i < 3; ++i)
        edges[i] = (t[(i + 1) % 3] - t[i]).normalized();
    Eigen::Vector3d normal = (t[1] - t[0]).cross(t[2] - t[0]);
    const double area2 = normal.norm();
    const int normalCount = area2 > 1e-15 ? 1 : 0;  // degenerate: edges still separate
    if (normalCount)
        normal /= area2;
    for (auto& e : edges)
        if (!e.allFinite())
            e.setZero();
    return overlapsConvex(box, {t.data(), 3, &normal, normalCount, edges.data(), 3});
}

const std::array<Eigen::Vector3d, 3> kUnitAxes = {
    Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};

/** A voxel map's box: axis-aligned, so its corners are all the SAT needs besides the axes. */
bool overlapsAligned(const Obb& box, const Box3& aligned) {
    std::array<Eigen::Vector3d, 8> corners;
    for (int i = 0; i < 8; ++i)
        corners[std::size_t(i)] = aligned.corner(Box3::CornerType(i));
    return overlapsConvex(box, {corners.data(), 8, kUnitAxes.data(), 3, kUnitAxes.data(), 3});
}

}  // namespace

struct StaticCollisionChecker::Impl {
    std::vector<Polytope> polytopes;
    std::vector<std::array<Eigen::Vector3d, 3>> triangles;
    std::vector<Box3> alignedBoxes;
    Bvh bvh;

    explicit Impl(const WorldSpec& world) {
        for (const auto& b : world.boxes)
            polytopes.push_back(boxPolytope(b));
        const auto boxCount = static_cast<std::uint32_t>(polytopes.size());
        for (const auto& c : world.cylinders)
            polytopes.push_back(prismPolytope(c));
        for (const auto& m : world.meshes) {
            for (const auto& t : m.triangles)
                triangles.push_back({m.vertices[t[0]].cast<double>(),
                                     m.vertices[t[1]].cast<double>(),
                                     m.vertices[t[2]].cast<double>()});
        }
        std::vector<Primitive> prims;
        for (std::uint32_t i = 0; i < polytopes.size(); ++i)
            prims.push_back({polytopes[i].bounds(), i < boxCount ? Kind::Box : Kind::Prism, i});
        for (std::uint32_t i = 0; i < triangles.size(); ++i) {
            Box3 b;
            for (const auto& v : triangles[i])
                b.extend(v);
            prims.push_back({b, Kind::Triangle, i});
        }
        for (const auto& map : world.voxelMaps)
            for (const auto& b : map.boxes) {
                prims.push_back(
                    {Box3(b.min, b.max), Kind::AlignedBox, std::uint32_t(alignedBoxes.size())});
                alignedBoxes.emplace_back(b.min, b.max);
            }
        bvh.build(std::move(prims));
    }

    bool test(const Primitive& p, const Obb& box) const {
        if (p.kind == Kind::Triangle)
            return overlapsTriangle(box, triangles[p.index]);
        if (p.kind == Kind::AlignedBox)
            return overlapsAligned(box, alignedBoxes[p.index]);
        return overlapsConvex(box, polytopes[p.index].view());
    }
};

StaticCollisionChecker::StaticCollisionChecker(const WorldSpec& world)
    : impl_(std::make_unique<Impl>(world)) {}

StaticCollisionChecker::~StaticCollisionChecker() = default;

bool StaticCollisionChecker::overlaps(const Eigen::Vector3d& center, const Eigen::Vector3d& size,
                                      double yaw) const {
    Obb box;
    box.center = center;
    box.axes = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    box.half = 0.5 * size;
    const Eigen::Vector3d reach = box.aabbHalf();
    const Box3 query(center - reach, center + reach);
    return impl_->bvh.any(query, [&](const Primitive& p) { return impl_->test(p, box); });
}

}  // namespace daep::world
