// March loops of the reference.
#include "reference/reference_march.hpp"

#include "reference/reference_sdf.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/tiling_model.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace clmarch {
namespace {

/// Folds a distance sample h at depth t into the closest approach and the penumbra; previous is
/// the sample before it (the improved variant estimates the closest point between the two).
void track_approach(MarchEnd& end, double h, double t, double previous, const MarchLimits& limits) {
  end.closest = std::min(end.closest, h);
  if (limits.soft_mode == 1) {
    end.penumbra = std::min(end.penumbra, limits.soft_k * h / std::max(t, 1e-6));
  } else if (limits.soft_mode == 2) {
    const double y = h * h / (2.0 * previous);
    const double d = std::sqrt(std::max(h * h - y * y, 0.0));
    end.penumbra = std::min(end.penumbra, limits.soft_k * d / std::max(t - y, 1e-6));
  }
}

// As in the kernel, never below the spacing of t in the arithmetic in use (here double's, 2^-52 t):
// a smaller step leaves t + d == t and the ray would stall until its budget ran out.
double hit_threshold(const MarchLimits& limits, double t) {
  return std::max({limits.hit_cone_slope * t, limits.epsilon, std::numeric_limits<double>::epsilon() * t});
}

// Over-relaxation (Keinert et al. 2014, "Enhanced Sphere Tracing", with the safe fall-back): steps
// are omega * d while the unbounding spheres of consecutive samples overlap, i.e. while
// t - d <= safe = t_prev + d_prev (where plain sphere tracing would be). A sample that fails this
// may lie past the surface: it is discarded without a hit test, t goes back to safe and the ray
// marches plainly from there (omega = 1 for the rest of the ray).
MarchEnd march_plain(const Field& field, const glm::dvec3& origin, const glm::dvec3& direction, double t_start,
                     double t_end, const MarchLimits& limits) {
  MarchEnd end;
  double t = t_start;
  double previous = 1e20;
  bool relaxing = limits.over_relaxation > 1.0;
  double safe = std::numeric_limits<double>::infinity();
  for (int i = 0; i < limits.max_steps; ++i) {
    const double d = field(origin + t * direction);
    ++end.steps;
    track_approach(end, d, t, previous, limits);
    previous = d;
    if (relaxing && d < t - safe) {
      relaxing = false;
      t = safe;
    } else {
      if (d < hit_threshold(limits, t)) {
        end.hit = true;
        break;
      }
      safe = t + d;
      t += relaxing ? limits.over_relaxation * d : d;
    }
    if (t >= t_end) break;
  }
  end.depth = t;
  end.exhausted = !end.hit && t < t_end;
  end.local = origin + t * direction;
  return end;
}

// The unit-cell traversal: inside the current cell the ray is entry + s * direction; when the
// wall it heads for is no farther along the ray than the surface (or than the cell content's
// bounding sphere, cell_bounds), it steps exactly onto that wall and re-enters the neighbouring
// cell at the opposite wall (several axes at once at edges and corners).
MarchEnd march_cells(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction, double t_start,
                     double t_end, const MarchLimits& limits) {
  const glm::dvec3 cell = scene.tiling->cell;
  MarchEnd end;
  glm::dvec3 entry = floor_mod(origin + t_start * direction, cell);
  double t_entry = t_start, s = 0.0;
  double previous = 1e20;
  // Over-relaxation as in march_plain, in the cell's coordinate s: a relaxed step ends at the wall
  // at the latest, and a wall step (exact) leaves nothing to undo.
  bool relaxing = limits.over_relaxation > 1.0;
  double safe = std::numeric_limits<double>::infinity();
  const std::optional<BoundingSphere> bounds = cell_bounds(scene);
  for (int i = 0; i < limits.max_steps; ++i) {
    const glm::dvec3 p = entry + s * direction;
    const double d = reference_distance(scene.sdf, p);
    // The stretch ahead free of the cell's content: the distance, or up to the bounds' sphere.
    double clear = d, reach = 0.0;
    if (bounds) {
      const std::optional<RaySpan> span = ray_sphere_span(p, direction, *bounds);
      reach = !span || span->t_exit <= 0.0 ? std::numeric_limits<double>::infinity() : std::max(span->t_enter, 0.0);
      clear = std::max(d, reach);
    }
    glm::dvec3 wall_axis(std::numeric_limits<double>::infinity());
    for (int a = 0; a < 3; ++a) {
      if (direction[a] == 0.0) continue;
      const double to_wall = direction[a] > 0.0 ? cell[a] - p[a] : -p[a];
      wall_axis[a] = std::max(to_wall / direction[a], 0.0);
    }
    const double wall = std::min({wall_axis.x, wall_axis.y, wall_axis.z});
    ++end.steps;
    track_approach(end, d, t_entry + s, previous, limits);
    previous = d;
    if (relaxing && d < s - safe) {
      relaxing = false;
      s = safe;
    } else if (d < hit_threshold(limits, t_entry + s)) {
      end.hit = true;
      break;
    } else if (wall <= clear) {
      ++end.wall_steps;
      const glm::dvec3 at_wall = p + wall * direction;
      for (int a = 0; a < 3; ++a) {
        entry[a] = wall_axis[a] == wall ? (direction[a] > 0.0 ? 0.0 : cell[a]) : std::clamp(at_wall[a], 0.0, cell[a]);
      }
      t_entry += s + wall;
      s = 0.0;
      safe = std::numeric_limits<double>::infinity();
    } else {
      safe = s + clear;
      // Only the distance is relaxed: the stretch before the bounds' sphere is clear as it is.
      s += relaxing ? std::min(std::max(limits.over_relaxation * d, reach), wall) : clear;
    }
    if (t_entry + s >= t_end) break;
  }
  end.depth = t_entry + s;
  end.exhausted = !end.hit && end.depth < t_end;
  end.local = entry + s * direction;
  return end;
}

}  // namespace

MarchLimits camera_march_limits(const Scene& scene) {
  MarchLimits limits;
  limits.max_steps = scene.render.max_steps;
  limits.epsilon = scene.render.epsilon;
  limits.over_relaxation = camera_over_relaxation(scene);
  limits.hit_cone_slope = hit_cone_slope(scene.render, scene.camera);
  return limits;
}

Field scene_field(const Scene& scene) {
  if (scene.tiling && scene.tiling->method == TilingMethod::Mod) {
    return [&scene](const glm::dvec3& p) { return reference_distance(scene.sdf, floor_mod(p, scene.tiling->cell)); };
  }
  return [&scene](const glm::dvec3& p) { return reference_distance(scene.sdf, p); };
}

MarchEnd reference_march(const Scene& scene, const glm::dvec3& origin, const glm::dvec3& direction, double t_start,
                         double t_end, const MarchLimits& limits) {
  if (uses_cells_tiling(scene)) {
    return march_cells(scene, origin, direction, t_start, t_end, limits);
  }
  MarchEnd end = march_plain(scene_field(scene), origin, direction, t_start, t_end, limits);
  if (scene.tiling) end.local = floor_mod(end.local, scene.tiling->cell);
  return end;
}

glm::dvec3 camera_origin_in_frame(const Scene& scene) {
  if (uses_cells_tiling(scene)) return offset_in_cell(scene.camera.position, scene.tiling->cell);
  return scene.camera.position;
}

}  // namespace clmarch
