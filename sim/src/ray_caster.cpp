#include "anascan/sim/ray_caster.hpp"

#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "closest_point_triangle.hpp"

namespace anascan::sim {

struct RayCaster::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<Eigen::Vector3d> triangle_normals;
    std::vector<double> triangle_offsets_m;  ///< n . v0 of each triangle's plane.
    std::vector<Eigen::Vector3d> vertices;   ///< Double copies, for exact nearest points.
    std::vector<Eigen::Vector3i> triangles;

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

Expected<void> check_mesh(const Mesh& mesh) {
    if (mesh.triangles.empty()) return fail(ErrorCode::kEmpty, "ray caster: mesh has no triangles");
    const int n = static_cast<int>(mesh.vertices.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        if (tri.minCoeff() < 0 || tri.maxCoeff() >= n)
            return fail(ErrorCode::kInvalidArgument, "ray caster: triangle " + std::to_string(t) +
                                                         " has a vertex index " + "outside 0.." +
                                                         std::to_string(n - 1));
    }
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        if (!mesh.vertices.world_position(v).allFinite())
            return fail(ErrorCode::kInvalidArgument,
                        "ray caster: vertex " + std::to_string(v) + " is not finite");
    }
    return {};
}

// Copies vertices and indices into a new Embree triangle geometry of `scene`.
void attach_triangles(RTCDevice device, RTCScene scene, const Mesh& mesh) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices.size()));
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const Eigen::Vector3d p = mesh.vertices.world_position(v);
        for (int a = 0; a < 3; ++a) vertices[3 * v + a] = static_cast<float>(p[a]);
    }
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles.size()));
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        for (int a = 0; a < 3; ++a)
            indices[3 * t + a] = static_cast<unsigned>(mesh.triangles[t][a]);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
}

std::vector<Eigen::Vector3d> triangle_normals(const Mesh& mesh) {
    std::vector<Eigen::Vector3d> normals(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        const Eigen::Vector3d a = mesh.vertices.world_position(tri[0]);
        const Eigen::Vector3d n = (mesh.vertices.world_position(tri[1]) - a)
                                      .cross(mesh.vertices.world_position(tri[2]) - a);
        normals[t] = n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
    }
    return normals;
}

// State of one nearest-point query (Embree calls `closer` for each candidate triangle).
struct NearestQuery {
    const std::vector<Eigen::Vector3d>* vertices = nullptr;
    const std::vector<Eigen::Vector3i>* triangles = nullptr;
    Eigen::Vector3d point;
    SurfacePoint best;
};

bool closer(RTCPointQueryFunctionArguments* args) {
    auto* q = static_cast<NearestQuery*>(args->userPtr);
    const Eigen::Vector3i& tri = (*q->triangles)[args->primID];
    const std::vector<Eigen::Vector3d>& v = *q->vertices;
    const Eigen::Vector3d c =
        detail::closest_point_on_triangle(q->point, v[tri[0]], v[tri[1]], v[tri[2]]);
    const double d = (c - q->point).norm();
    if (d >= q->best.distance_m) return false;
    q->best = SurfacePoint{.distance_m = d, .triangle = int(args->primID), .point = c};
    args->query->radius = float(d) * (1.0f + 1e-6f) + 1e-7f;  // Float BVH bounds: keep a margin.
    return true;
}

RTCRay make_ray(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_min_m,
                double t_max_m) {
    RTCRay ray{};
    ray.org_x = static_cast<float>(origin.x());
    ray.org_y = static_cast<float>(origin.y());
    ray.org_z = static_cast<float>(origin.z());
    ray.dir_x = static_cast<float>(direction.x());
    ray.dir_y = static_cast<float>(direction.y());
    ray.dir_z = static_cast<float>(direction.z());
    ray.tnear = static_cast<float>(t_min_m);
    ray.tfar = std::isfinite(t_max_m) ? static_cast<float>(t_max_m) : INFINITY;
    ray.mask = 0xFFFFFFFFu;
    return ray;
}

}  // namespace

Expected<RayCaster> RayCaster::create(const Mesh& mesh) {
    if (auto ok = check_mesh(mesh); !ok) return fail(ok.error());
    auto impl = std::make_unique<Impl>();
    impl->device = rtcNewDevice(nullptr);
    if (!impl->device) return fail(ErrorCode::kIo, "ray caster: cannot create an Embree device");
    impl->scene = rtcNewScene(impl->device);
    rtcSetSceneBuildQuality(impl->scene, RTC_BUILD_QUALITY_HIGH);
    attach_triangles(impl->device, impl->scene, mesh);
    rtcCommitScene(impl->scene);
    if (const RTCError error = rtcGetDeviceError(impl->device); error != RTC_ERROR_NONE)
        return fail(ErrorCode::kIo, "ray caster: Embree error " + std::to_string(error) +
                                        " while building the BVH");
    impl->triangle_normals = triangle_normals(mesh);
    impl->triangle_offsets_m.resize(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        impl->triangle_offsets_m[t] =
            impl->triangle_normals[t].dot(mesh.vertices.world_position(mesh.triangles[t][0]));
    }
    impl->vertices.resize(mesh.vertices.size());
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        impl->vertices[v] = mesh.vertices.world_position(v);
    impl->triangles = mesh.triangles;
    return RayCaster(std::move(impl));
}

RayCaster::RayCaster(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;
RayCaster::~RayCaster() = default;

std::size_t RayCaster::triangle_count() const { return impl_->triangle_normals.size(); }

std::optional<RayHit> RayCaster::cast(const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction, double t_min_m,
                                      double t_max_m) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit ray_hit{};
    ray_hit.ray = make_ray(origin, direction, t_min_m, t_max_m);
    ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    ray_hit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &context, &ray_hit);
    if (ray_hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    const int triangle = static_cast<int>(ray_hit.hit.primID);
    const Eigen::Vector3d& n = impl_->triangle_normals[triangle];
    // Embree intersects in float; the distance is recomputed in double on the hit plane.
    double distance_m = ray_hit.ray.tfar;
    const double n_dot_d = n.dot(direction);
    if (std::abs(n_dot_d) > 1e-6)
        distance_m = (impl_->triangle_offsets_m[triangle] - n.dot(origin)) / n_dot_d;
    return RayHit{.distance_m = distance_m, .triangle = triangle, .normal = n};
}

std::optional<SurfacePoint> RayCaster::closest_point(const Eigen::Vector3d& point,
                                                     double max_distance_m) const {
    NearestQuery q{.vertices = &impl_->vertices,
                   .triangles = &impl_->triangles,
                   .point = point,
                   .best = {.distance_m = max_distance_m}};
    RTCPointQuery query{};
    query.x = float(point.x());
    query.y = float(point.y());
    query.z = float(point.z());
    query.radius = float(max_distance_m) * (1.0f + 1e-6f) + 1e-7f;
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(impl_->scene, &query, &context, closer, &q);
    if (q.best.triangle < 0) return std::nullopt;
    return q.best;
}

bool RayCaster::occluded(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         double t_min_m, double t_max_m) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = make_ray(origin, direction, t_min_m, t_max_m);
    rtcOccluded1(impl_->scene, &context, &ray);
    return ray.tfar == -INFINITY;  // Embree marks an occluded ray so.
}

}  // namespace anascan::sim
