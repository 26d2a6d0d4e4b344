// The reference renderer: camera rays through the march, normals, shading, mirror bounces, fog
// and tone mapping in double, and the row-parallel frame loop.
#include "reference/reference_renderer.hpp"

#include "common/cancellation.hpp"
#include "common/progress.hpp"
#include "frame/antialias.hpp"
#include "reference/reference_cones.hpp"
#include "reference/reference_march.hpp"
#include "reference/reference_sdf.hpp"
#include "reference/reference_shading.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/scene_box.hpp"
#include "scene/tiling_model.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <limits>

namespace clmarch {
namespace {

glm::dvec3 central_normal(const Field& f, const glm::dvec3& p, double h) {
  const glm::dvec3 x(h, 0.0, 0.0), y(0.0, h, 0.0), z(0.0, 0.0, h);
  return normalize_or_zero(glm::dvec3(f(p + x) - f(p - x), f(p + y) - f(p - y), f(p + z) - f(p - z)));
}

// Inigo Quilez's four-sample tetrahedron; cheaper than central differences but only first order.
glm::dvec3 tetrahedral_normal(const Field& f, const glm::dvec3& p, double h) {
  const glm::dvec3 xyy(1.0, -1.0, -1.0), yyx(-1.0, -1.0, 1.0), yxy(-1.0, 1.0, -1.0), xxx(1.0, 1.0, 1.0);
  return normalize_or_zero(xyy * f(p + xyy * h) + yyx * f(p + yyx * h) + yxy * f(p + yxy * h) + xxx * f(p + xxx * h));
}

// Forward differences: four taps like the tetrahedron, all on one side of p; first order.
glm::dvec3 forward_normal(const Field& f, const glm::dvec3& p, double h) {
  const double here = f(p);
  return normalize_or_zero(glm::dvec3(f(p + glm::dvec3(h, 0.0, 0.0)) - here, f(p + glm::dvec3(0.0, h, 0.0)) - here,
                                      f(p + glm::dvec3(0.0, 0.0, h)) - here));
}

glm::dvec3 normal_of(const Field& f, const glm::dvec3& p, NormalMethod method, double h) {
  switch (method) {
    case NormalMethod::Central:
      return central_normal(f, p, h);
    case NormalMethod::Tetrahedral:
      return tetrahedral_normal(f, p, h);
    case NormalMethod::Forward:
      return forward_normal(f, p, h);
  }
  return glm::dvec3(0.0);
}

/// The material of the tree at the surface's point (in its frame), and the primitive it is of.
void set_material(const Scene& scene, SurfacePoint& s) {
  const SdfSample sample = reference_sample(scene.sdf, s.local, root_material(scene));
  s.material.albedo = sample.color;
  s.material.metallic = sample.surface.x;
  s.material.roughness = sample.surface.y;
  s.material.reflectivity = sample.surface.z;
  s.material.specular = sample.finish.x;
  s.material.shininess = sample.finish.y;
  s.material.emission = sample.emission;
  s.primitive = sample.primitive;
}

/// The surface where a march from world point world_origin along direction ended with a hit.
SurfacePoint surface_at(const Scene& scene, const MarchEnd& end, const glm::dvec3& world_origin,
                        const glm::dvec3& direction) {
  SurfacePoint s;
  s.local = end.local;
  s.world = world_origin + end.depth * direction;
  s.normal = normal_of(scene_field(scene), end.local, scene.render.normal_method, scene.render.normal_epsilon);
  set_material(scene, s);
  s.steps = end.steps;
  return s;
}

// The PBR course's mirror bounces: each bounce's color weighted by the product of the
// reflectivities met so far; a bounce that misses shows the sky.
glm::dvec3 add_reflections(const Scene& scene, glm::dvec3 color, SurfacePoint hit, glm::dvec3 direction) {
  // Mirror rays march plainly with the fixed epsilon: the pixel cone is the camera's.
  const MarchLimits limits{scene.render.max_steps, scene.render.epsilon, 0, 0.0};
  const double offset = reflection_offset(scene.render);
  double weight = 1.0;
  for (int bounce = 0; bounce < scene.shading.reflection_bounces; ++bounce) {
    weight *= hit.material.reflectivity;
    if (!(weight > 0.0)) break;
    direction = glm::reflect(direction, hit.normal);
    const glm::dvec3 origin = hit.local + hit.normal * offset;
    const glm::dvec3 world_origin = hit.world + hit.normal * offset;
    const MarchEnd end = reference_march(scene, origin, direction, 0.0, scene.render.max_distance, limits);
    if (!end.hit) {
      color += weight * reference_miss_color(scene, direction, end.closest);
      break;
    }
    hit = surface_at(scene, end, world_origin, direction);
    color += weight * reference_shade(scene, hit, direction);
  }
  return color;
}

}  // namespace

glm::dvec3 reference_normal(const Node& root, const glm::dvec3& p, NormalMethod method, double h) {
  return normal_of([&](const glm::dvec3& q) { return reference_distance(root, q); }, p, method, h);
}

namespace {

/// The world point origin in the frame the march runs in: under the cells tiling the march runs
/// in the camera's cell.
glm::dvec3 march_frame_origin(const Scene& scene, const glm::dvec3& origin) {
  return uses_cells_tiling(scene) ? origin - scene.camera.position + camera_origin_in_frame(scene) : origin;
}

/// What a camera ray's hit shows: its color, and the terms of its lit color as they reach the camera.
struct HitColor {
  glm::dvec3 color;
  LightTerms layers;
};

/// The color of a camera ray's hit at depth (shading, mirror bounces, fog and tone mapping), and
/// its layers: each term of the lit color through the fog, which is affine in the color (c f + g),
/// as fog(term) - fog(0).
HitColor hit_color(const Scene& scene, const SurfacePoint& hit, const glm::dvec3& direction, double depth) {
  const LightTerms terms = reference_light_terms(scene, hit, direction);
  glm::dvec3 color = reference_lit_color(scene, terms, hit.steps);
  if (scene.shading.reflection_bounces > 0) color = add_reflections(scene, color, hit, direction);
  const glm::dvec3 fog_alone = reference_fog(scene, glm::dvec3(0.0), direction, depth);
  const auto fogged = [&](const glm::dvec3& term) { return reference_fog(scene, term, direction, depth) - fog_alone; };
  return {reference_tone_map(scene, reference_fog(scene, color, direction, depth)),
          {fogged(terms.ambient), fogged(terms.diffuse), fogged(terms.specular)}};
}

/// Writes the layers of a ray into the buffers' layer channels at pixel (i, j).
void store_layers(FrameBuffers& fb, int i, int j, const LightTerms& layers) {
  const glm::dvec3 terms[3] = {layers.ambient, layers.diffuse, layers.specular};
  for (int k = 0; k < 9; ++k) fb.at(kLayerChannels[k], i, j) = static_cast<float>(terms[k / 3][k % 3]);
}

/// What camera rays are clipped to (computed once per image): the scene's bounding sphere and box.
struct RayClip {
  std::optional<BoundingSphere> sphere;
  std::optional<BoundingBox> box;
};

RayClip ray_clip(const Scene& scene) { return {camera_ray_bounds(scene), camera_ray_box(scene)}; }

// The trace of a camera ray clipped to bounds, starting no nearer than t_min (its block's cone
// start under the coarse pass).
RayResult trace_within(const Scene& scene, const RayClip& bounds, const glm::dvec3& origin, const glm::dvec3& direction,
                       double t_min = 0.0) {
  const MarchLimits limits = camera_march_limits(scene);
  // origin is a world position; the march runs in its own frame.
  const glm::dvec3 frame_origin = march_frame_origin(scene, origin);
  // Camera rays march only inside the scene's bounding sphere and box, where it has them
  // (scene_bounds.hpp, scene_box.hpp), as kernels/march_loop.cl clips them.
  double t_start = 0.0;
  double t_end = scene.render.max_distance;
  bool marching = true;
  if (bounds.sphere) {
    const std::optional<RaySpan> span = ray_sphere_span(origin, direction, *bounds.sphere);
    if (span) {
      t_start = std::max(span->t_enter, 0.0);
      t_end = std::min(span->t_exit, t_end);
    }
    marching = span && t_end > t_start;
  }
  if (bounds.box) {
    // Only rays that meet both move their start: a ray that misses keeps it (the status channel).
    const RaySpan span = ray_box_span(origin, direction, *bounds.box);
    const bool meets = span.t_enter <= span.t_exit;
    if (marching && meets) t_start = std::max(t_start, span.t_enter);
    t_end = std::min(t_end, span.t_exit);
    marching = marching && meets && t_end > t_start;
  }
  t_start = std::max(t_start, t_min);
  marching = marching && t_end > t_start;
  MarchEnd end;
  // A ray that does not march ends where it starts, as in the kernel (kernels/march.cl).
  end.depth = t_start;
  if (marching) end = reference_march(scene, frame_origin, direction, t_start, t_end, limits);
  RayResult r;
  r.steps = end.steps;
  r.wall_steps = end.wall_steps;
  r.status = end.hit                                  ? RayStatus::Hit
             : end.exhausted                          ? RayStatus::OutOfSteps
             : end.depth >= scene.render.max_distance ? RayStatus::OutOfDistance
                                                      : RayStatus::Miss;
  if (!end.hit) {
    // Running out of steps shades as a miss (the status channel tells them apart).
    r.depth = std::numeric_limits<double>::infinity();
    r.color = reference_tone_map(scene, reference_miss_color(scene, direction, end.closest));
    return r;
  }
  r.hit = true;
  r.depth = end.depth;
  const SurfacePoint hit = surface_at(scene, end, origin, direction);
  r.normal = hit.normal;
  r.primitive = hit.primitive;
  const HitColor seen = hit_color(scene, hit, direction, end.depth);
  r.color = seen.color;
  r.layers = seen.layers;
  return r;
}

}  // namespace

RayResult reference_trace(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction) {
  return trace_within(scene, ray_clip(scene), origin, direction);
}

FrameBuffers render_reference(const Scene& scene) { return render_reference(scene, reference_cones_if_used(scene)); }

FrameBuffers render_reference(const Scene& scene, const std::optional<ConeStarts>& cones) {
  const int width = scene.render.width;
  const int height = scene.render.height;
  const CameraBasis basis = camera_basis(scene.camera, width, height);
  const RayClip bounds = ray_clip(scene);
  FrameBuffers fb(width, height);
  fb.has_ids = fb.has_layers = true;
  fb.has_depth_lo = scene.render.precision == Precision::Double;
  fb.has_status = true;
  ProgressLine progress("reference rows", height, scene.render.width);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      // Ctrl-C: a row not yet begun is never begun (progress.advance() below polls too, but only
      // after its row; keep both).
      throw_if_cancelled();
      for (int i = 0; i < width; ++i) {
        const RayResult r = trace_within(scene, bounds, basis.origin, pixel_ray_direction(basis, i, j),
                                         cones ? cones->at_pixel(i, j) : 0.0);
        fb.at(Channel::R, i, j) = static_cast<float>(r.color.r);
        fb.at(Channel::G, i, j) = static_cast<float>(r.color.g);
        fb.at(Channel::B, i, j) = static_cast<float>(r.color.b);
        fb.at(Channel::Depth, i, j) = static_cast<float>(r.depth);
        if (fb.has_depth_lo && r.hit)
          fb.at(Channel::DepthLo, i, j) = static_cast<float>(r.depth - static_cast<float>(r.depth));
        fb.at(Channel::Steps, i, j) = static_cast<float>(r.steps);
        fb.at(Channel::Status, i, j) = static_cast<float>(r.status);
        fb.at(Channel::NX, i, j) = static_cast<float>(r.normal.x);
        fb.at(Channel::NY, i, j) = static_cast<float>(r.normal.y);
        fb.at(Channel::NZ, i, j) = static_cast<float>(r.normal.z);
        fb.at(Channel::WallSteps, i, j) = static_cast<float>(r.wall_steps);
        fb.at(Channel::Id, i, j) = r.hit ? static_cast<float>(r.primitive) : kMissId;
        store_layers(fb, i, j, r.layers);
      }
      progress.advance();
    }
  });
  if (scene.render.samples == 1) {
    set_single_sample_coverage(fb);
    return fb;
  }
  // Anti-aliasing: the pixels the centre rays show edges at get the other samples, marched like
  // the device's refining passes without the cones' starts (made for the centre rays).
  const int count = scene.render.samples;
  SampleSums sums(fb, pixels_to_refine(fb, scene.render.adaptive), true);
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      throw_if_cancelled();
      for (int i = 0; i < width; ++i) {
        const std::size_t at = static_cast<std::size_t>(j) * width + i;
        if (!sums.refine()[at]) continue;
        for (int k = 1; k < count; ++k) {
          const glm::dvec2 point = sample_point(k, count);
          const RayResult r =
              trace_within(scene, bounds, basis.origin, camera_ray_direction(basis, i + point.x, j + point.y));
          const glm::dvec3 terms[3] = {r.layers.ambient, r.layers.diffuse, r.layers.specular};
          float values[13] = {static_cast<float>(r.color.r), static_cast<float>(r.color.g),
                              static_cast<float>(r.color.b), r.hit ? 1.0f : 0.0f};
          for (int k = 0; k < 9; ++k) values[4 + k] = static_cast<float>(terms[k / 3][k % 3]);
          sums.add(at, values);
        }
      }
    }
  });
  sums.finish(fb, count);
  return fb;
}

FrameBuffers reshade_hits(const Scene& scene, const FrameBuffers& render) {
  const CameraBasis basis = camera_basis(scene.camera, render.width, render.height);
  const glm::dvec3 frame_origin = march_frame_origin(scene, basis.origin);
  FrameBuffers fb = render;
  tbb::parallel_for(tbb::blocked_range<int>(0, render.height), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j) {
      throw_if_cancelled();
      for (int i = 0; i < render.width; ++i) {
        const double depth = render.at(Channel::Depth, i, j);
        if (!std::isfinite(depth)) continue;
        const glm::dvec3 direction = pixel_ray_direction(basis, i, j);
        SurfacePoint hit;
        hit.local = frame_origin + depth * direction;
        if (scene.tiling) hit.local = floor_mod(hit.local, scene.tiling->cell);
        hit.world = basis.origin + depth * direction;
        // The float normal is unit only to float's rounding, which 1 - (n.h)^2 in the GGX
        // distribution would turn into its whole value at a low roughness (a^2 ~ 1e-7).
        hit.normal = normalize_or_zero(
            glm::dvec3(render.at(Channel::NX, i, j), render.at(Channel::NY, i, j), render.at(Channel::NZ, i, j)));
        set_material(scene, hit);
        hit.steps = static_cast<int>(render.at(Channel::Steps, i, j));
        const HitColor seen = hit_color(scene, hit, direction, depth);
        fb.at(Channel::R, i, j) = static_cast<float>(seen.color.r);
        fb.at(Channel::G, i, j) = static_cast<float>(seen.color.g);
        fb.at(Channel::B, i, j) = static_cast<float>(seen.color.b);
        store_layers(fb, i, j, seen.layers);
      }
    }
  });
  return fb;
}

}  // namespace clmarch
