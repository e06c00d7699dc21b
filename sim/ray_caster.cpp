#include "sim/ray_caster.hpp"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/analytic_shapes.hpp"

namespace rangefit::sim {
namespace {

using Eigen::Vector3d;

// One Embree geometry: a mesh (world-space double vertices kept for exact refinement) or an
// analytic primitive (intersected in the user-geometry callbacks).
struct Geometry {
  int object = -1;
  const SceneObject* source = nullptr;
  std::vector<Vector3d> vertices;  // world frame, meshes only
  const std::vector<std::array<std::uint32_t, 3>>* triangles = nullptr;
};

void user_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
  const Eigen::AlignedBox3d local = local_bounds(g->source->shape);
  Eigen::AlignedBox3d world;
  for (int i = 0; i < 8; ++i) {
    world.extend(g->source->T_world_object *
                 local.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i)));
  }
  constexpr double kPad = 1e-3;  // float rounding of the bounds must not cut off the surface
  args->bounds_o->lower_x = static_cast<float>(world.min().x() - kPad);
  args->bounds_o->lower_y = static_cast<float>(world.min().y() - kPad);
  args->bounds_o->lower_z = static_cast<float>(world.min().z() - kPad);
  args->bounds_o->upper_x = static_cast<float>(world.max().x() + kPad);
  args->bounds_o->upper_y = static_cast<float>(world.max().y() + kPad);
  args->bounds_o->upper_z = static_cast<float>(world.max().z() + kPad);
}

template <class Args>
std::optional<ShapeHit> user_hit(const Args* args, RTCRayN* ray, unsigned i) {
  const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
  const unsigned n = args->N;
  const Vector3d o(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i), RTCRayN_org_z(ray, n, i));
  const Vector3d d(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i), RTCRayN_dir_z(ray, n, i));
  return intersect_shape(g->source->shape, g->source->T_world_object, o, d,
                         RTCRayN_tnear(ray, n, i), RTCRayN_tfar(ray, n, i));
}

void user_intersect(const RTCIntersectFunctionNArguments* args) {
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const auto h = user_hit(args, ray, i);
    if (!h) continue;
    const unsigned n = args->N;
    RTCRayN_tfar(ray, n, i) = static_cast<float>(h->t);
    RTCHitN_Ng_x(hit, n, i) = static_cast<float>(h->normal.x());
    RTCHitN_Ng_y(hit, n, i) = static_cast<float>(h->normal.y());
    RTCHitN_Ng_z(hit, n, i) = static_cast<float>(h->normal.z());
    RTCHitN_u(hit, n, i) = 0.0f;
    RTCHitN_v(hit, n, i) = 0.0f;
    RTCHitN_primID(hit, n, i) = args->primID;
    RTCHitN_geomID(hit, n, i) = args->geomID;
    RTCHitN_instID(hit, n, i, 0) = args->context->instID[0];
  }
}

void user_occluded(const RTCOccludedFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    if (user_hit(args, args->ray, i)) {
      RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
  }
}

RTCRay to_rtc(const Ray& r) {
  RTCRay out{};
  out.org_x = static_cast<float>(r.origin.x());
  out.org_y = static_cast<float>(r.origin.y());
  out.org_z = static_cast<float>(r.origin.z());
  out.dir_x = static_cast<float>(r.dir.x());
  out.dir_y = static_cast<float>(r.dir.y());
  out.dir_z = static_cast<float>(r.dir.z());
  out.tnear = static_cast<float>(r.t_min);
  out.tfar = static_cast<float>(std::min(r.t_max, 1e30));
  out.mask = 0xFFFFFFFFu;
  out.flags = 0;
  return out;
}

}  // namespace

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<SceneObject> objects;
  std::vector<Geometry> geometries;  // index = Embree geomID
  std::size_t triangles = 0;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  // Exact double hit on geometry g for ray r; falls back to Embree's float t if the double test
  // disagrees at a triangle edge.
  Hit refine(const Ray& r, unsigned geom_id, unsigned prim_id, float t_float) const {
    const Geometry& g = geometries[geom_id];
    Hit h;
    h.valid = true;
    h.object = g.object;
    h.t = t_float;
    if (g.triangles) {
      const auto& tri = (*g.triangles)[prim_id];
      const Vector3d &a = g.vertices[tri[0]], &b = g.vertices[tri[1]], &c = g.vertices[tri[2]];
      if (const auto t = intersect_triangle(a, b, c, r.origin, r.dir, r.t_min, r.t_max)) h.t = *t;
      h.normal = (b - a).cross(c - a).normalized();
    } else if (const auto s = intersect_shape(g.source->shape, g.source->T_world_object, r.origin,
                                              r.dir, r.t_min, r.t_max)) {
      h.t = s->t;
      h.normal = s->normal;
    }
    h.point = r.origin + h.t * r.dir;
    return h;
  }
};

RayCaster::RayCaster(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.device = rtcNewDevice("threads=1");
  if (!m.device) throw std::runtime_error("Embree: cannot create a device");
  m.scene = rtcNewScene(m.device);
  rtcSetSceneBuildQuality(m.scene, RTC_BUILD_QUALITY_HIGH);
  m.objects = scene.objects;
  m.geometries.reserve(m.objects.size());
  for (std::size_t i = 0; i < m.objects.size(); ++i) {
    const SceneObject& obj = m.objects[i];
    Geometry g;
    g.object = static_cast<int>(i);
    g.source = &obj;
    RTCGeometry geom = nullptr;
    if (const auto* mesh = std::get_if<MeshShape>(&obj.shape)) {
      if (mesh->mesh.triangles.empty()) continue;
      geom = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
      g.triangles = &mesh->mesh.triangles;
      auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                             RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                             mesh->mesh.vertices.size()));
      auto* ib = static_cast<unsigned*>(
          rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                  3 * sizeof(unsigned), mesh->mesh.triangles.size()));
      for (std::size_t v = 0; v < mesh->mesh.vertices.size(); ++v) {
        const Vector3d w = obj.T_world_object * mesh->mesh.vertices[v];
        g.vertices.push_back(w);
        for (int k = 0; k < 3; ++k) vb[3 * v + k] = static_cast<float>(w[k]);
      }
      for (std::size_t t = 0; t < mesh->mesh.triangles.size(); ++t) {
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t idx = mesh->mesh.triangles[t][k];
          if (idx >= mesh->mesh.vertices.size()) {
            rtcReleaseGeometry(geom);
            throw std::runtime_error("mesh '" + obj.name + "': triangle " + std::to_string(t) +
                                     " has vertex index " + std::to_string(idx) + " out of range");
          }
          ib[3 * t + k] = idx;
        }
      }
      m.triangles += mesh->mesh.triangles.size();
    } else {
      geom = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(geom, 1);
      rtcSetGeometryBoundsFunction(geom, user_bounds, nullptr);
      rtcSetGeometryIntersectFunction(geom, user_intersect);
      rtcSetGeometryOccludedFunction(geom, user_occluded);
    }
    m.geometries.push_back(std::move(g));
    rtcSetGeometryUserData(geom, &m.geometries.back());
    rtcCommitGeometry(geom);
    const unsigned id = rtcAttachGeometry(m.scene, geom);
    rtcReleaseGeometry(geom);
    if (id != m.geometries.size() - 1) throw std::runtime_error("Embree: unexpected geometry id");
  }
  rtcCommitScene(m.scene);
  if (rtcGetDeviceError(m.device) != RTC_ERROR_NONE) {
    throw std::runtime_error("Embree: building the scene failed");
  }
}

RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

std::size_t RayCaster::triangle_count() const { return impl_->triangles; }

Hit RayCaster::cast(const Ray& ray) const {
  Hit h;
  cast(std::span<const Ray>(&ray, 1), std::span<Hit>(&h, 1));
  return h;
}

void RayCaster::cast(std::span<const Ray> rays, std::span<Hit> hits) const {
  constexpr std::size_t kChunk = 256;  // stream size: big enough for coherence, small on stack
  RTCRayHit batch[kChunk];
  RTCIntersectContext context;
  const std::size_t n = std::min(rays.size(), hits.size());
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t count = std::min(kChunk, n - begin);
    for (std::size_t i = 0; i < count; ++i) {
      batch[i].ray = to_rtc(rays[begin + i]);
      batch[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      batch[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect1M(impl_->scene, &context, batch, static_cast<unsigned>(count), sizeof(RTCRayHit));
    for (std::size_t i = 0; i < count; ++i) {
      const RTCRayHit& rh = batch[i];
      hits[begin + i] =
          rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
              ? Hit{}
              : impl_->refine(rays[begin + i], rh.hit.geomID, rh.hit.primID, rh.ray.tfar);
    }
  }
}

bool RayCaster::occluded(const Ray& ray) const {
  std::uint8_t blocked = 0;
  occluded(std::span<const Ray>(&ray, 1), std::span<std::uint8_t>(&blocked, 1));
  return blocked != 0;
}

void RayCaster::occluded(std::span<const Ray> rays, std::span<std::uint8_t> blocked) const {
  constexpr std::size_t kChunk = 256;
  RTCRay batch[kChunk];
  RTCIntersectContext context;
  const std::size_t n = std::min(rays.size(), blocked.size());
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const std::size_t count = std::min(kChunk, n - begin);
    for (std::size_t i = 0; i < count; ++i) batch[i] = to_rtc(rays[begin + i]);
    rtcInitIntersectContext(&context);
    rtcOccluded1M(impl_->scene, &context, batch, static_cast<unsigned>(count), sizeof(RTCRay));
    for (std::size_t i = 0; i < count; ++i) {
      blocked[begin + i] = std::isinf(batch[i].tfar) && batch[i].tfar < 0.0f ? 1 : 0;
    }
  }
}

Hit RayCaster::cast_brute_force(const Ray& ray) const {
  Hit best;
  double t_max = ray.t_max;
  for (const Geometry& g : impl_->geometries) {
    if (g.triangles) {
      for (const auto& tri : *g.triangles) {
        const auto t =
            intersect_triangle(g.vertices[tri[0]], g.vertices[tri[1]], g.vertices[tri[2]],
                               ray.origin, ray.dir, ray.t_min, t_max);
        if (!t) continue;
        t_max = *t;
        best.valid = true;
        best.t = *t;
        best.object = g.object;
        best.normal = (g.vertices[tri[1]] - g.vertices[tri[0]])
                          .cross(g.vertices[tri[2]] - g.vertices[tri[0]]);
      }
    } else if (const auto s = intersect_shape(g.source->shape, g.source->T_world_object, ray.origin,
                                              ray.dir, ray.t_min, t_max)) {
      t_max = s->t;
      best = Hit{true, s->t, Vector3d::Zero(), s->normal, g.object};
    }
  }
  if (best.valid) {
    best.point = ray.origin + best.t * ray.dir;
    best.normal.normalize();
  }
  return best;
}

}  // namespace rangefit::sim
