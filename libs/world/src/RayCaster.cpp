#include "daep/world/RayCaster.h"

#include <embree3/rtcore.h>
#include <xmmintrin.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "Shapes.h"

namespace daep::world {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

const char* errorName(RTCError code) {
    switch (code) {
        case RTC_ERROR_NONE:
            return "no error";
        case RTC_ERROR_INVALID_ARGUMENT:
            return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION:
            return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY:
            return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "unsupported CPU";
        case RTC_ERROR_CANCELLED:
            return "cancelled";
        default:
            return "unknown error";
    }
}

/** Embree calls back from C code, so errors are recorded here and thrown by check(). */
struct ErrorSink {
    std::string first;
};

void onEmbreeError(void* user, RTCError code, const char* what) {
    const std::string msg = std::string("Embree ") + errorName(code) + ": " + (what ? what : "");
    std::fprintf(stderr, "daep::world::RayCaster: %s\n", msg.c_str());
    auto* sink = static_cast<ErrorSink*>(user);
    if (sink->first.empty())
        sink->first = msg;
}

/** Embree's advice: flush denormals to zero while tracing; restores the caller's mode. */
class DenormalsFlushed {
public:
    DenormalsFlushed() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | 0x8040); }
    ~DenormalsFlushed() { _mm_setcsr(saved_); }
    DenormalsFlushed(const DenormalsFlushed&) = delete;
    DenormalsFlushed& operator=(const DenormalsFlushed&) = delete;

private:
    unsigned saved_;
};

/** Fills a triangle geometry's buffers (new buffers, sized for the soup). */
void setTriangles(RTCGeometry geom, const TriangleSoup& soup) {
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                          RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                          soup.vertices.size()));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), soup.triangles.size()));
    if (v == nullptr || idx == nullptr)
        return;  // the error callback has the reason
    for (std::size_t i = 0; i < soup.vertices.size(); ++i)
        for (int k = 0; k < 3; ++k)
            v[3 * i + k] = soup.vertices[i][k];
    for (std::size_t i = 0; i < soup.triangles.size(); ++i)
        for (int k = 0; k < 3; ++k)
            idx[3 * i + k] = static_cast<unsigned>(soup.triangles[i][k]);
}

/** The fields of a ray packet that stay the same for every ray of a frame (Embree writes only
 * tfar and the hit). */
template <typename Packet, int K>
void initPacket(Packet& p, const Eigen::Vector3f& o) {
    for (int k = 0; k < K; ++k) {
        p.ray.org_x[k] = o.x();
        p.ray.org_y[k] = o.y();
        p.ray.org_z[k] = o.z();
        p.ray.tnear[k] = 0.0f;
        p.ray.time[k] = 0.0f;
        p.ray.mask[k] = ~0u;
        p.ray.id[k] = static_cast<unsigned>(k);
        p.ray.flags[k] = 0;
    }
}

/** The fields of a packet initPacket set up that each cast sets anew. */
template <typename Packet, int K, typename Direction>
void fillPacket(Packet& p, int* valid, const Eigen::Vector3f* dirs, std::size_t count,
                float maxRange, const Direction& direction) {
    for (int k = 0; k < K; ++k) {
        const bool on = static_cast<std::size_t>(k) < count;
        valid[k] = on ? -1 : 0;
        const Eigen::Vector3f d = direction(on ? dirs[k] : dirs[0]);
        p.ray.dir_x[k] = d.x();
        p.ray.dir_y[k] = d.y();
        p.ray.dir_z[k] = d.z();
        p.ray.tfar[k] = maxRange;
        p.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        p.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
    }
}

/** A voxel map's box in float, as rays are traced. */
struct FloatBox {
    float lo[3], hi[3];
};

/**
 * Distance along the ray to the box's surface within [tnear, tfar), or -1: the entry, or the
 * exit when the origin lies inside (as a ray meets a box made of triangles).
 */
float boxHit(const FloatBox& b, const float o[3], const float d[3], float tnear, float tfar) {
    float entry = -kInf, exit = kInf;
    for (int k = 0; k < 3; ++k) {
        if (d[k] == 0.0f) {
            if (o[k] < b.lo[k] || o[k] > b.hi[k])
                return -1.0f;
            continue;
        }
        const float inv = 1.0f / d[k];
        const float t0 = (b.lo[k] - o[k]) * inv, t1 = (b.hi[k] - o[k]) * inv;
        entry = std::max(entry, std::min(t0, t1));
        exit = std::min(exit, std::max(t0, t1));
    }
    if (entry > exit)
        return -1.0f;
    const float t = entry >= tnear ? entry : exit;
    return t >= tnear && t < tfar ? t : -1.0f;
}

/** Embree user geometry callback: the voxel boxes against a packet of N rays. */
void intersectVoxelBoxes(const RTCIntersectFunctionNArguments* args) {
    const auto& box = static_cast<const FloatBox*>(args->geometryUserPtr)[args->primID];
    const unsigned n = args->N;
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, n);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, n);
    for (unsigned i = 0; i < n; ++i) {
        if (args->valid[i] == 0)
            continue;
        const float o[3] = {RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i),
                            RTCRayN_org_z(ray, n, i)};
        const float d[3] = {RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i),
                            RTCRayN_dir_z(ray, n, i)};
        const float t = boxHit(box, o, d, RTCRayN_tnear(ray, n, i), RTCRayN_tfar(ray, n, i));
        if (t < 0.0f)
            continue;
        RTCRayN_tfar(ray, n, i) = t;
        RTCHitN_Ng_x(hit, n, i) = RTCHitN_Ng_y(hit, n, i) = RTCHitN_Ng_z(hit, n, i) = 0.0f;
        RTCHitN_u(hit, n, i) = RTCHitN_v(hit, n, i) = 0.0f;
        RTCHitN_primID(hit, n, i) = args->primID;
        RTCHitN_geomID(hit, n, i) = args->geomID;
        RTCHitN_instID(hit, n, i, 0) = args->context->instID[0];
    }
}

void occludedByVoxelBoxes(const RTCOccludedFunctionNArguments* args) {
    const auto& box = static_cast<const FloatBox*>(args->geometryUserPtr)[args->primID];
    const unsigned n = args->N;
    for (unsigned i = 0; i < n; ++i) {
        if (args->valid[i] == 0)
            continue;
        const float o[3] = {RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i),
                            RTCRayN_org_z(args->ray, n, i)};
        const float d[3] = {RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i),
                            RTCRayN_dir_z(args->ray, n, i)};
        if (boxHit(box, o, d, RTCRayN_tnear(args->ray, n, i), RTCRayN_tfar(args->ray, n, i)) >=
            0.0f)
            RTCRayN_tfar(args->ray, n, i) = -kInf;
    }
}

void voxelBoxBounds(const RTCBoundsFunctionArguments* args) {
    const auto& box = static_cast<const FloatBox*>(args->geometryUserPtr)[args->primID];
    RTCBounds* b = args->bounds_o;
    b->lower_x = box.lo[0], b->lower_y = box.lo[1], b->lower_z = box.lo[2];
    b->upper_x = box.hi[0], b->upper_y = box.hi[1], b->upper_z = box.hi[2];
}

}  // namespace

struct RayCaster::Impl {
    ErrorSink errors;
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    RTCGeometry people = nullptr;
    std::size_t peopleCount = 0;
    unsigned peopleGeomId = RTC_INVALID_GEOMETRY_ID;
    std::size_t trianglesPerPerson = 0;
    bool packets16 = false;
    std::vector<FloatBox> voxelBoxes;  ///< the voxel maps' boxes, read by the user geometry

    ~Impl() {
        if (people != nullptr)
            rtcReleaseGeometry(people);
        if (scene != nullptr)
            rtcReleaseScene(scene);
        if (device != nullptr)
            rtcReleaseDevice(device);
    }

    void check(const char* during) {
        const RTCError code = rtcGetDeviceError(device);
        if (code == RTC_ERROR_NONE && errors.first.empty())
            return;
        const std::string what = errors.first.empty() ? errorName(code) : errors.first;
        errors.first.clear();
        throw std::runtime_error(std::string("RayCaster: ") + during + " failed: " + what);
    }

    void addStatic(const WorldSpec& world) {
        const TriangleSoup soup = triangulateStatic(world);
        if (soup.triangles.empty())
            return;
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        setTriangles(geom, soup);
        rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene, geom);
        rtcReleaseGeometry(geom);
    }

    /** The voxel maps' boxes as one user geometry: a triangle box would take 12 primitives. */
    void addVoxelMaps(const WorldSpec& world) {
        for (const auto& map : world.voxelMaps)
            for (const auto& b : map.boxes)
                voxelBoxes.push_back({{float(b.min.x()), float(b.min.y()), float(b.min.z())},
                                      {float(b.max.x()), float(b.max.y()), float(b.max.z())}});
        if (voxelBoxes.empty())
            return;
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, unsigned(voxelBoxes.size()));
        rtcSetGeometryUserData(geom, voxelBoxes.data());
        rtcSetGeometryBoundsFunction(geom, voxelBoxBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, intersectVoxelBoxes);
        rtcSetGeometryOccludedFunction(geom, occludedByVoxelBoxes);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene, geom);
        rtcReleaseGeometry(geom);
    }

    template <typename Packet, int K, typename Intersect, typename Direction>
    void castPackets(Intersect intersect, const Eigen::Vector3f& origin,
                     const std::vector<Eigen::Vector3f>& dirs, float maxRange,
                     const Direction& direction, std::vector<float>& out) const {
        alignas(64) Packet packet;
        alignas(64) int valid[K];
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        initPacket<Packet, K>(packet, origin);
        for (std::size_t base = 0; base < dirs.size(); base += K) {
            const std::size_t count = std::min<std::size_t>(K, dirs.size() - base);
            fillPacket<Packet, K>(packet, valid, dirs.data() + base, count, maxRange, direction);
            intersect(valid, scene, &context, &packet);
            for (std::size_t k = 0; k < count; ++k)
                out[base + k] =
                    packet.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID ? kInf : packet.ray.tfar[k];
        }
    }

    template <typename Direction>
    void castAll(const Eigen::Vector3f& origin, const std::vector<Eigen::Vector3f>& dirs,
                 float maxRange, const Direction& direction, std::vector<float>& out) const {
        out.resize(dirs.size());
        if (dirs.empty())
            return;
        DenormalsFlushed ftz;
        if (packets16)
            castPackets<RTCRayHit16, 16>(rtcIntersect16, origin, dirs, maxRange, direction, out);
        else
            castPackets<RTCRayHit8, 8>(rtcIntersect8, origin, dirs, maxRange, direction, out);
    }
};

RayCaster::RayCaster(const WorldSpec& world) : impl_(std::make_unique<Impl>()) {
    // One build/trace thread: runs are single-core and deterministic.
    impl_->device = rtcNewDevice("threads=1");
    if (impl_->device == nullptr)
        throw std::runtime_error(std::string("RayCaster: cannot create the Embree device: ") +
                                 errorName(rtcGetDeviceError(nullptr)));
    rtcSetDeviceErrorFunction(impl_->device, onEmbreeError, &impl_->errors);
    impl_->packets16 =
        rtcGetDeviceProperty(impl_->device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;

    impl_->scene = rtcNewScene(impl_->device);
    // Two-level BVH: moving the people rebuilds only their small geometry.
    rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_DYNAMIC);
    impl_->addStatic(world);
    impl_->addVoxelMaps(world);

    rtcCommitScene(impl_->scene);
    impl_->check("building the static scene");
}

RayCaster::~RayCaster() = default;

void RayCaster::setPeople(const std::vector<PersonState>& people, const Eigen::Vector3d& bodySize) {
    Impl& d = *impl_;
    if (people.empty()) {
        if (d.people != nullptr)
            rtcDisableGeometry(d.people);
    } else {
        TriangleSoup soup;
        for (const auto& p : people)
            soup.addBox(personBoxPose(p.position, p.heading, bodySize), bodySize);
        if (d.people == nullptr) {
            d.people = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_TRIANGLE);
            rtcSetGeometryBuildQuality(d.people, RTC_BUILD_QUALITY_LOW);
            d.peopleGeomId = rtcAttachGeometry(d.scene, d.people);
        }
        if (people.size() != d.peopleCount) {
            setTriangles(d.people, soup);
            d.peopleCount = people.size();
            d.trianglesPerPerson = soup.triangles.size() / people.size();
        } else {
            auto* v =
                static_cast<float*>(rtcGetGeometryBufferData(d.people, RTC_BUFFER_TYPE_VERTEX, 0));
            for (std::size_t i = 0; i < soup.vertices.size(); ++i)
                for (int k = 0; k < 3; ++k)
                    v[3 * i + k] = soup.vertices[i][k];
            rtcUpdateGeometryBuffer(d.people, RTC_BUFFER_TYPE_VERTEX, 0);
        }
        rtcEnableGeometry(d.people);
        rtcCommitGeometry(d.people);
    }
    rtcCommitScene(d.scene);
    d.check("moving the people");
}

namespace {

RTCRayHit castOne(RTCScene scene, const Eigen::Vector3f& origin, const Eigen::Vector3f& unitDir,
                  float maxRange) {
    RTCRayHit rh;
    rh.ray.org_x = origin.x();
    rh.ray.org_y = origin.y();
    rh.ray.org_z = origin.z();
    rh.ray.dir_x = unitDir.x();
    rh.ray.dir_y = unitDir.y();
    rh.ray.dir_z = unitDir.z();
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = maxRange;
    rh.ray.time = 0.0f;
    rh.ray.mask = ~0u;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(scene, &context, &rh);
    return rh;
}

}  // namespace

float RayCaster::castRay(const Eigen::Vector3f& origin, const Eigen::Vector3f& unitDir,
                         float maxRange) const {
    const RTCRayHit rh = castOne(impl_->scene, origin, unitDir, maxRange);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? kInf : rh.ray.tfar;
}

int RayCaster::firstPersonHit(const Eigen::Vector3f& origin, const Eigen::Vector3f& unitDir,
                              float maxRange) const {
    const RTCRayHit rh = castOne(impl_->scene, origin, unitDir, maxRange);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || rh.hit.geomID != impl_->peopleGeomId ||
        impl_->trianglesPerPerson == 0)
        return -1;
    return static_cast<int>(rh.hit.primID / impl_->trianglesPerPerson);
}

void RayCaster::castRays(const Eigen::Vector3f& origin,
                         const std::vector<Eigen::Vector3f>& unitDirs, float maxRange,
                         std::vector<float>& out) const {
    impl_->castAll(
        origin, unitDirs, maxRange, [](const Eigen::Vector3f& d) { return d; }, out);
}

void RayCaster::castRays(const Eigen::Vector3f& origin,
                         const std::vector<Eigen::Vector3f>& unitDirs, YawTurn turn, float maxRange,
                         std::vector<float>& out) const {
    const float c = turn.cos, s = turn.sin;
    impl_->castAll(
        origin, unitDirs, maxRange,
        [c, s](const Eigen::Vector3f& r) {
            return Eigen::Vector3f(c * r.x() - s * r.y(), s * r.x() + c * r.y(), r.z());
        },
        out);
}

}  // namespace daep::world
