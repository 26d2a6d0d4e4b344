// Pixel-by-pixel comparison of two renders. Every tolerance is derived per pixel from the scene's
// settings; docs/accuracy.md gives the reasoning behind each.
#include "check/cross_check.hpp"

#include "codegen/kernel_source.hpp"
#include "codegen/sdf_codegen.hpp"
#include "prune/operand_grid.hpp"
#include "reference/reference_shading.hpp"
#include "scene/camera_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace clmarch {
namespace {

/// Rounding steps between a ray parameter and a distance value: the position o + t*d, the
/// direction's normalisation and the distance function each round a few times.
constexpr double kRoundingSteps = 16.0;
/// Below this |cos| between ray and normal a ray is grazing; its depth bound stops growing.
constexpr double kGrazingCosine = 0.1;
/// Colors are delivered in 8 bits: half a step is the smallest difference that can show.
constexpr double kColorQuantum = 0.5 / 255.0;
/// Share of pixels whose figure may exceed its tolerance (the p99 criteria).
constexpr double kQuantile = 0.99;

/// Depths are stored as floats in both renders' buffers whatever the arithmetic: the true depths
/// differ by at most the buffers' difference plus one float rounding of each, 2 u_float t. In
/// float programs the 16 roundings of the arithmetic cover it; in double it is what bounds how far
/// apart the two hit points may be (docs/accuracy.md).
constexpr double kDepthBufferRounding = 2.0 * 0x1p-24;
/// Both renders store normals as floats: each component rounds by at most u_float, the angle
/// between the stored and the computed normal by at most sqrt(3) u_float, twice over. Below
/// float's arithmetic it never shows; in double, where t < h, it can be the larger term.
constexpr double kNormalBufferRounding = 2.0 * 1.7320508075688772 * 0x1p-24;

/// The unit roundoff of the OpenCL render's arithmetic (render.precision): float's or double's.
double unit_roundoff(const Scene& scene) { return scene.render.precision == Precision::Double ? 0x1p-53 : 0x1p-24; }

/// The size of the coordinates the OpenCL render computes with, whose rounding the tolerances allow
/// for: the camera's distance from the map frame origin, where map() keeps every position relative
/// to it (host/codegen/sdf_codegen.cpp); from the world origin where map() takes absolute points
/// or the mod tiling wraps world positions; the cell's diagonal under the cells tiling, whose march
/// runs inside the camera's cell.
double coordinate_size(const Scene& scene, const CameraBasis& basis) {
  if (scene.tiling && scene.tiling->method == TilingMethod::Cells) return glm::length(scene.tiling->cell);
  if (scene.tiling || takes_absolute_points(scene.sdf, map_frame_origin(scene))) return glm::length(basis.origin);
  return glm::length(basis.origin - map_frame_origin(scene));
}

/// How far the program's scene is from the reference's where the program computes in double: its
/// literals are floats (host/codegen/sdf_codegen.hpp), each off by at most delta, which moves a
/// coordinate of a point p by delta (1 + |p|) at most through one transform's row or offset,
/// sqrt(3) that over the three: here delta (1 + size) with the coordinates' size, per unit of
/// size. An operand grid keeps its operands' numbers in float in its data, whose rounding is
/// bounded by float's unit roundoff. 0 for float programs, whose rounding covers their literals.
double literal_rounding(const Scene& scene) {
  if (scene.render.precision != Precision::Double) return 0.0;
  if (grid_union(scene) != nullptr) return std::sqrt(3.0) * 0x1p-24;
  return std::sqrt(3.0) * march_scene_code(scene).literal_rounding;
}

/// The name of the OpenCL render's arithmetic, for messages.
const char* precision_name(const Scene& scene) { return kPrecisionNames[static_cast<int>(scene.render.precision)]; }
/// Hit/miss flips away from edges need a ray whose closest approach sits within rounding of
/// epsilon, or a step budget that ends within one step of a hit: 1 pixel in 1000 at most.
constexpr double kInteriorMismatchShare = 0.001;
/// Of the pixels on a hit/miss edge, the share that may flip (they are decided by a margin of
/// order epsilon at the silhouette).
constexpr double kSilhouetteMismatchShare = 0.1;

ErrorSummary summarise(std::vector<double> values) {
  ErrorSummary s;
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  const auto at = [&](double q) {
    return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1))];
  };
  s.p50 = at(0.5);
  s.p99 = at(kQuantile);
  s.max = values.back();
  double squares = 0.0;
  for (double v : values) squares += v * v;
  s.rms = std::sqrt(squares / static_cast<double>(values.size()));
  return s;
}

bool is_hit(const FrameBuffers& b, int i, int j) { return std::isfinite(b.at(Channel::Depth, i, j)); }

glm::dvec3 normal_at(const FrameBuffers& b, int i, int j) {
  return {b.at(Channel::NX, i, j), b.at(Channel::NY, i, j), b.at(Channel::NZ, i, j)};
}

double angle_between(const glm::dvec3& a, const glm::dvec3& b) {
  const double la = glm::length(a), lb = glm::length(b);
  // A NaN must not reach the sorts of the p99s; has_non_finite_value fails the pixel anyway.
  if (!std::isfinite(la) || !std::isfinite(lb)) return M_PI;
  // Both zero: both found a vanishing gradient (a camera at a sphere's centre), which agrees.
  if (la == 0.0 && lb == 0.0) return 0.0;
  if (la == 0.0 || lb == 0.0) return M_PI;
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0));
}

/// A light's radiance in its brightest channel, before its reach.
double brightest_radiance(const Light& light) {
  return light.intensity * std::max({light.color.r, light.color.g, light.color.b});
}

/// The share of the light's radiance reaching the world point (light_reach; 1 for directional lights).
double reach_at(const Light& light, const glm::dvec3& point) {
  if (light.kind == LightKind::Directional) return 1.0;
  const glm::dvec3 to_light = light.position - point;
  const double d = glm::length(to_light);
  return d > 0.0 ? light_reach(light, to_light / d, d) : 0.0;
}

/// The lights' radiance reaching the world point, summed over their brightest channels.
double light_radiance_at(const Scene& scene, const glm::dvec3& point) {
  double radiance = 0.0;
  for (const Light& light : scene.lights) radiance += brightest_radiance(light) * reach_at(light, point);
  return radiance;
}

/// The least roughness of the tree's materials (0.5 where none is set).
double least_roughness(const Node& node) {
  double least = node.roughness.value_or(Material{}.roughness);
  for (const Node& child : node.children) least = std::min(least, least_roughness(child));
  return least;
}

/// The largest specular weight times shininess of the tree's materials (the specular term's
/// slope per radian), from the scene's defaults where no node sets them.
double largest_specular_slope(const Node& node, const Material& inherited) {
  const Material m = node.material_over(inherited);
  double largest = m.specular * m.shininess;
  for (const Node& child : node.children) largest = std::max(largest, largest_specular_slope(child, m));
  return largest;
}

/// Largest change of PBR's lit color per radian of normal change, per unit of radiance. The GGX
/// distribution D = a^2 / (pi q^2), q = a^2 + (1 - a^2) sin^2(theta), a = roughness^2, peaks at
/// 1 / (pi a^2) and changes with the normal's angle theta to the half vector at most
/// 4 a^2 (1 - a^2) sin cos / (pi q^3), whose largest value is at the root s = sin^2 below. The
/// rest of the specular term, K = G1(n.v) G1(n.l) n.l / (4 n.v n.l), is at most 1 / (4 k) <= 2
/// (Smith k = (r + 1)^2 / 8 >= 1/8) and moves at most (1 - k) / (4 k^2) + 1 / (4 k^2) <= 30 per
/// radian; Fresnel depends on h.v alone, and the diffuse term moves at most 1 / pi.
double pbr_color_per_radian(double roughness) {
  const double a2 = std::pow(roughness, 4.0), b = 1.0 - a2;
  const double p = 5.0 * b + 2.0 * a2;
  // The smaller root of 4 b s^2 - p s + a^2 = 0; at roughness 1, D is flat (b = 0).
  const double s = b > 0.0 ? (p - std::sqrt(p * p - 16.0 * b * a2)) / (8.0 * b) : 0.0;
  const double q = a2 + b * s;
  const double peak = 1.0 / (M_PI * a2);
  const double steepest = 4.0 * a2 * b * std::sqrt(s * (1.0 - s)) / (M_PI * q * q * q);
  return 1.0 / M_PI + 2.0 * steepest + 30.0 * peak;
}

/// Largest change of the shaded color per radian of normal change per unit of radiance: the slope
/// of the diffuse and specular terms (which also bounds their size).
double lit_color_per_radian(const Scene& scene) {
  const Shading& s = scene.shading;
  if (s.model == ShadingModel::Pbr) return pbr_color_per_radian(least_roughness(scene.sdf));
  const double specular_slope =
      s.model == ShadingModel::Lambert ? 0.0 : largest_specular_slope(scene.sdf, root_material(scene));
  return s.diffuse + specular_slope;
}

/// How far a hit's lit color may move: per radian of its normal's error, and per unit of its
/// point's displacement (the depths' difference), which turns the direction to a point or spot
/// light d away by up to 1 / d radians a unit and moves the share of its radiance that arrives
/// (falloff, range, cone: light_reach) by its gradient.
struct LitColorSlopes {
  double per_radian = 0.0;
  double per_unit_shift = 0.0;
};

LitColorSlopes lit_color_slopes(const Scene& scene, double per_radian, const glm::dvec3& point) {
  LitColorSlopes slopes;
  for (const Light& light : scene.lights) {
    const double radiance = brightest_radiance(light) * per_radian;
    if (light.kind == LightKind::Directional) {
      slopes.per_radian += radiance;
      continue;
    }
    const double d = glm::length(light.position - point);
    const double reach = reach_at(light, point);
    slopes.per_radian += radiance * reach;
    if (d > 0.0) slopes.per_unit_shift += radiance * reach / d;
    if (light.shaped()) {
      // Central differences a millionth of the distance wide: the reach is smooth but for a spot's
      // hard edge, where the gradient grows with 1 / h and fails nothing it should not.
      const double h = 1e-6 * std::max(d, 1e-6);
      glm::dvec3 gradient(0.0);
      for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 step(0.0);
        step[axis] = h;
        gradient[axis] = (reach_at(light, point + step) - reach_at(light, point - step)) / (2.0 * h);
      }
      slopes.per_unit_shift += radiance * glm::length(gradient);
    }
  }
  return slopes;
}

/// Largest change of a miss's color per unit of its closest approach: Crum's glow adds
/// color (1 - closest / radius)^2, whose slope is at most 2 color / radius.
double color_per_closest_approach(const Shading& s) {
  if (!s.glow) return 0.0;
  return 2.0 * std::max({s.glow->color.r, s.glow->color.g, s.glow->color.b}) / s.glow->radius;
}

/// |a - b|; a NaN or an infinity on either side differs infinitely, so that it never passes (a NaN
/// would drop out of every max and sort).
double difference(float a, float b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
  return std::abs(static_cast<double>(a) - static_cast<double>(b));
}

double max_color_difference(const FrameBuffers& a, const FrameBuffers& b, int i, int j) {
  double diff = 0.0;
  for (Channel c : {Channel::R, Channel::G, Channel::B})
    diff = std::max(diff, difference(a.at(c, i, j), b.at(c, i, j)));
  return diff;
}

/// A value the contract says is a number that is not: a color channel, a hit's normal, or a NaN
/// depth (a miss's depth is +inf).
bool has_non_finite_value(const FrameBuffers& b, int i, int j) {
  for (Channel c : {Channel::R, Channel::G, Channel::B}) {
    if (!std::isfinite(b.at(c, i, j))) return true;
  }
  if (std::isnan(b.at(Channel::Depth, i, j))) return true;
  if (!is_hit(b, i, j)) return false;
  return !std::isfinite(b.at(Channel::NX, i, j)) || !std::isfinite(b.at(Channel::NY, i, j)) ||
         !std::isfinite(b.at(Channel::NZ, i, j));
}

/// Pixels where the two renders disagree (a hit against a miss, one primitive against another),
/// the tolerance the check sets for them, and what they are.
struct Disagreements {
  int count;
  int& limit;
  const char* what;
};

/// Sets the limits of pixels that disagree, away from an edge one in a thousand of the image,
/// next to one (edge_pixels of them) a tenth of those and 2, and records a failure past either.
void limit_disagreements(CheckReport& r, const Disagreements& interior, const Disagreements& edge, int edge_pixels) {
  interior.limit = static_cast<int>(std::ceil(kInteriorMismatchShare * r.pixels));
  edge.limit = static_cast<int>(std::ceil(kSilhouetteMismatchShare * edge_pixels)) + 2;
  if (interior.count > interior.limit) {
    r.failures.push_back(fmt::format("{} {} (at most {})", interior.count, interior.what, interior.limit));
  }
  if (edge.count > edge.limit) {
    r.failures.push_back(
        fmt::format("{} {} (at most {} of {} edge pixels)", edge.count, edge.what, edge.limit, edge_pixels));
  }
}

/// Whether pixel (i, j) of b has a neighbour with another primitive number (a miss's included).
bool next_to_another_id(const FrameBuffers& b, int i, int j) {
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      const int ni = i + di, nj = j + dj;
      if (ni < 0 || nj < 0 || ni >= b.width || nj >= b.height) continue;
      if (b.at(Channel::Id, ni, nj) != b.at(Channel::Id, i, j)) return true;
    }
  }
  return false;
}

/// Compares the id channels of the pixels both renders hit. A number is decided by which operand's
/// distance is least (or largest, or heavier) at the hit: where two surfaces meet the two renders'
/// hits, an epsilon apart, can fall on either side, so a mismatch next to an id edge is allowed as
/// a hit/miss flip at a silhouette is, and elsewhere as rarely as an interior flip.
void compare_ids(CheckReport& r, const FrameBuffers& opencl, const FrameBuffers& reference) {
  int edge_pixels = 0;
  for (int j = 0; j < opencl.height; ++j) {
    for (int i = 0; i < opencl.width; ++i) {
      if (!is_hit(opencl, i, j) || !is_hit(reference, i, j)) continue;
      ++r.ids_compared;
      const bool edge = next_to_another_id(opencl, i, j) || next_to_another_id(reference, i, j);
      edge_pixels += edge;
      if (opencl.at(Channel::Id, i, j) != reference.at(Channel::Id, i, j))
        (edge ? r.id_mismatch_edge : r.id_mismatch_interior) += 1;
    }
  }
  limit_disagreements(
      r,
      {r.id_mismatch_interior, r.tolerances.id_mismatch_interior, "pixels away from id edges hit different primitives"},
      {r.id_mismatch_edge, r.tolerances.id_mismatch_edge, "pixels at id edges hit different primitives"}, edge_pixels);
}

}  // namespace

CheckReport cross_check(const Scene& scene, const FrameBuffers& opencl, const FrameBuffers& reference) {
  CheckReport r;
  const int w = reference.width, h = reference.height;
  r.pixels = w * h;
  if (opencl.has_status) r.out_of_steps_opencl = opencl.rays_with_status(RayStatus::OutOfSteps);
  if (reference.has_status) r.out_of_steps_reference = reference.rays_with_status(RayStatus::OutOfSteps);
  const CameraBasis basis = camera_basis(scene.camera, w, h);
  const double eps = scene.render.epsilon;
  const double cone_slope = hit_cone_slope(scene.render, scene.camera);
  const double normal_h = scene.render.normal_epsilon;
  const double origin_size = coordinate_size(scene, basis);
  const double unit = unit_roundoff(scene);
  const double literal_error = literal_rounding(scene);
  // The kernel's hit threshold is never below REAL_EPSILON t = 2u t, the spacing of t at most (a
  // smaller step would leave t + d == t: kernels/march_loop.cl); the double reference has no floor.
  const double spacing_of_t = 2.0 * unit;
  r.steps_one_sided = grid_union(scene) != nullptr;
  const double color_per_radian = lit_color_per_radian(scene);
  const double glow_slope = color_per_closest_approach(scene.shading);

  std::vector<double> depth_abs, depth_rel, depth_eps, depth_tol, normal_deg, normal_tol, color_abs, color_tol;
  double max_dt = 0.0;
  std::vector<double> miss_color_abs, miss_color_tol;
  double steps_sum = 0.0, squared_color = 0.0;
  int edge_pixels = 0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const bool hit_cl = is_hit(opencl, i, j), hit_ref = is_hit(reference, i, j);
      bool edge = false;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          const int ni = i + di, nj = j + dj;
          if (ni < 0 || nj < 0 || ni >= w || nj >= h) continue;
          edge = edge || is_hit(reference, ni, nj) != hit_ref || is_hit(opencl, ni, nj) != hit_cl;
        }
      }
      edge_pixels += edge;
      const double steps_short = reference.at(Channel::Steps, i, j) - opencl.at(Channel::Steps, i, j);
      const double step_diff = r.steps_one_sided ? std::max(steps_short, 0.0) : std::abs(steps_short);
      steps_sum += step_diff;
      r.steps_diff_max = std::max(r.steps_diff_max, step_diff);
      r.non_finite_opencl += has_non_finite_value(opencl, i, j);
      r.non_finite_reference += has_non_finite_value(reference, i, j);
      for (Channel c : {Channel::R, Channel::G, Channel::B}) {
        const double diff = difference(opencl.at(c, i, j), reference.at(c, i, j));
        squared_color += diff * diff;
        r.color_max_abs = std::max(r.color_max_abs, diff);
      }
      if (hit_cl != hit_ref) {
        (edge ? r.mask_mismatch_silhouette : r.mask_mismatch_interior) += 1;
        continue;
      }
      if (!hit_ref) {
        // A miss's color is the sky's, a function of the ray's direction alone, plus the glow of
        // its closest approach, which both marches find at the same steps when they take the same
        // number, up to the rounding of each step's t.
        if (edge || (glow_slope > 0.0 && step_diff != 0.0)) continue;
        const double steps = reference.at(Channel::Steps, i, j);
        const double closest_rounding = (kRoundingSteps + steps) * unit * (origin_size + scene.render.max_distance) +
                                        literal_error * (1.0 + origin_size + scene.render.max_distance);
        const double diff = max_color_difference(opencl, reference, i, j);
        miss_color_abs.push_back(diff);
        miss_color_tol.push_back(diff / (glow_slope * closest_rounding + kColorQuantum));
        continue;
      }
      ++r.both_hit;
      const double t_ref = reference.at(Channel::Depth, i, j);
      const double dt = std::abs(static_cast<double>(opencl.at(Channel::Depth, i, j)) - t_ref);
      const glm::dvec3 dir = pixel_ray_direction(basis, i, j);
      const glm::dvec3 n_ref = normal_at(reference, i, j);
      const double cosine = std::max(std::abs(glm::dot(dir, n_ref)), kGrazingCosine);
      const double rounding = kRoundingSteps * unit * (origin_size + t_ref) +
                              literal_error * (1.0 + origin_size + t_ref) + kDepthBufferRounding * t_ref;
      // Both marches stop within threshold / cos short of the surface; the threshold is epsilon, or
      // the pixel cone's radius at that depth, and never below float's spacing of t.
      const double threshold = std::max({eps, cone_slope * t_ref, spacing_of_t * t_ref});
      const double depth_tolerance = threshold / cosine + rounding;
      depth_abs.push_back(dt);
      depth_rel.push_back(dt / std::max(t_ref, 1e-30));
      depth_eps.push_back(dt / eps);
      depth_tol.push_back(dt / depth_tolerance);
      // Finite differences of a 1-Lipschitz field move by at most the shift of the point: the
      // normal estimates of points dt apart differ by at most sqrt(3) (dt + rounding) / h, and
      // each buffer holds them as floats.
      const double rounding_tolerance = std::sqrt(3.0) * rounding / normal_h;
      const double normal_tolerance = std::sqrt(3.0) * dt / normal_h + rounding_tolerance + kNormalBufferRounding;
      // Angles lie in [0, pi]: a tolerance past pi would pass any normal, and checks nothing. Where
      // rounding alone takes it there, the precision is to blame; else the depths' difference.
      r.normal_tolerance_past_pi += normal_tolerance >= M_PI;
      r.normal_rounding_past_pi += rounding_tolerance >= M_PI;
      max_dt = std::max(max_dt, dt);
      const double angle = angle_between(normal_at(opencl, i, j), n_ref);
      normal_deg.push_back(angle * 180.0 / M_PI);
      normal_tol.push_back(angle / normal_tolerance);
      if (step_diff == 0.0) {
        const double diff = max_color_difference(opencl, reference, i, j);
        const LitColorSlopes slopes = lit_color_slopes(scene, color_per_radian, basis.origin + dir * t_ref);
        color_abs.push_back(diff);
        color_tol.push_back(
            diff / (slopes.per_radian * normal_tolerance + slopes.per_unit_shift * (dt + rounding) + kColorQuantum));
      }
    }
  }
  r.depth_abs = summarise(depth_abs);
  r.depth_rel = summarise(depth_rel);
  r.depth_in_epsilons = summarise(depth_eps);
  r.depth_in_tolerances = summarise(depth_tol);
  r.steps_diff_mean = r.pixels ? steps_sum / r.pixels : 0.0;
  r.normal_angle_p99 = summarise(normal_deg).p99;
  r.color_p99_abs = summarise(color_abs).p99;
  r.miss_color_p99_abs = summarise(miss_color_abs).p99;
  r.color_compared = static_cast<int>(color_abs.size() + miss_color_abs.size());
  r.misses_compared = static_cast<int>(miss_color_abs.size());
  const double mse = squared_color / (3.0 * std::max(r.pixels, 1));
  r.color_psnr_db = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();

  CheckReport::Tolerances& t = r.tolerances;
  t.depth_in_tolerances_p99 = 1.0;
  t.steps_diff_mean = 1.0;
  const double normal_ratio_p99 = summarise(normal_tol).p99;
  const double color_ratio_p99 = summarise(color_tol).p99;
  const double miss_color_ratio_p99 = summarise(miss_color_tol).p99;
  r.ratios.normal_p99 = normal_ratio_p99;
  r.ratios.color_p99 = color_ratio_p99;
  r.ratios.miss_color_p99 = miss_color_ratio_p99;
  t.normal_angle_p99 = r.normal_angle_p99 / std::max(normal_ratio_p99, 1e-300);
  t.color_p99_abs = r.color_p99_abs / std::max(color_ratio_p99, 1e-300);
  t.miss_color_p99_abs = r.miss_color_p99_abs / std::max(miss_color_ratio_p99, 1e-300);

  // A criterion whose tolerance outgrows its quantity's range passes whatever the render holds: where
  // that is so at more pixels than the p99 leaves out, the check fails, saying why: the precision's
  // rounding (the scene is beyond its reach), or depths too far apart to compare normals.
  const double past_pi_limit = (1.0 - kQuantile) * r.both_hit;
  t.normal_past_pi = past_pi_limit;
  if (r.normal_rounding_past_pi > past_pi_limit) {
    r.failures.push_back(fmt::format(
        "the normal tolerance exceeds pi at {} of {} pixels both hit, so it checks nothing there: {}'s rounding of "
        "coordinates "
        "of size {:.3g} is too coarse for render.normal_epsilon {:g}; the scene is beyond {}'s reach{}",
        r.normal_tolerance_past_pi, r.both_hit, precision_name(scene), origin_size, normal_h, precision_name(scene),
        scene.render.precision == Precision::Float ? " (render it with render.precision: double)" : ""));
  } else if (r.normal_tolerance_past_pi > past_pi_limit) {
    r.failures.push_back(fmt::format(
        "the normal tolerance exceeds pi at {} of {} pixels both hit, so it checks nothing there: the two renders' "
        "depths "
        "differ by up to {:.3g}, too much for normals estimated render.normal_epsilon {:g} apart to be compared",
        r.normal_tolerance_past_pi, r.both_hit, max_dt, normal_h));
  }
  if (r.non_finite_opencl + r.non_finite_reference > 0) {
    r.failures.push_back(
        fmt::format("{} OpenCL and {} reference pixels hold a NaN or an infinity (color, a hit's "
                    "normal, or a NaN depth)",
                    r.non_finite_opencl, r.non_finite_reference));
  }
  limit_disagreements(
      r, {r.mask_mismatch_interior, t.mask_mismatch_interior, "interior pixels hit on one side only"},
      {r.mask_mismatch_silhouette, t.mask_mismatch_silhouette, "silhouette pixels hit on one side only"}, edge_pixels);
  if (r.depth_in_tolerances.p99 > t.depth_in_tolerances_p99) {
    r.failures.push_back(
        fmt::format("depth error p99 is {:.3g} times its per-pixel tolerance (epsilon / cos + rounding)",
                    r.depth_in_tolerances.p99));
  }
  if (r.steps_diff_mean > t.steps_diff_mean) {
    r.failures.push_back(
        fmt::format("steps differ by {:.3g} on average (at most {})", r.steps_diff_mean, t.steps_diff_mean));
  }
  if (normal_ratio_p99 > 1.0) {
    r.failures.push_back(
        fmt::format("normal angle error p99 is {:.3g} times its per-pixel tolerance", normal_ratio_p99));
  }
  if (color_ratio_p99 > 1.0) {
    r.failures.push_back(fmt::format("color error p99 is {:.3g} times its per-pixel tolerance", color_ratio_p99));
  }
  if (miss_color_ratio_p99 > 1.0) {
    r.failures.push_back(
        fmt::format("color error of misses p99 is {:.3g} times its per-pixel tolerance", miss_color_ratio_p99));
  }
  if (!r.failures.empty()) return r;
  // Ratios at most 1 mean the tolerance in absolute units is at least the measured p99.
  if (normal_ratio_p99 == 0.0) t.normal_angle_p99 = 0.0;
  if (color_ratio_p99 == 0.0) t.color_p99_abs = 0.0;
  if (miss_color_ratio_p99 == 0.0) t.miss_color_p99_abs = 0.0;
  return r;
}

CheckReport cross_check(const Scene& scene, const FrameBuffers& opencl, const FrameBuffers& reference,
                        const FrameBuffers& reshaded) {
  CheckReport r = cross_check(scene, opencl, reference);
  if (opencl.has_ids && reference.has_ids) compare_ids(r, opencl, reference);
  // Both sides shade the same depth, normal and steps, so only float arithmetic separates them (in
  // the color and in each layer),
  // inside the shading and along its shadow, occlusion and mirror rays: within half a step of 8
  // bits of the color's own size (HDR colors above 1 keep float's relative precision), plus the
  // specular power's rounding (x^shininess multiplies the relative rounding of x by shininess),
  // but for the rare secondary ray that ends on the other side of a surface (a shadow's edge),
  // which the 1 % the p99 leaves out allows for.
  const Shading& shading = scene.shading;
  const bool powered = shading.model == ShadingModel::Phong || shading.model == ShadingModel::BlinnPhong;
  const double power_slope =
      powered ? kRoundingSteps * unit_roundoff(scene) * largest_specular_slope(scene.sdf, root_material(scene)) : 0.0;
  const CameraBasis basis = camera_basis(scene.camera, opencl.width, opencl.height);
  double power_rounding = 0.0;
  std::vector<double> diffs, ratios;
  int pixels_compared = 0;
  // The color, and each of the layers (ao, diffuse, specular) as a color of its own where both
  // renders have them.
  const Channel triples[4][3] = {{Channel::R, Channel::G, Channel::B},
                                 {Channel::AoR, Channel::AoG, Channel::AoB},
                                 {Channel::DiffuseR, Channel::DiffuseG, Channel::DiffuseB},
                                 {Channel::SpecularR, Channel::SpecularG, Channel::SpecularB}};
  const std::size_t triples_compared = opencl.has_layers && reshaded.has_layers ? std::size(triples) : 1;
  for (int j = 0; j < opencl.height; ++j) {
    for (int i = 0; i < opencl.width; ++i) {
      // An anti-aliased pixel's color is the mean of its rays, not its centre hit's shading.
      if (!is_hit(opencl, i, j) || opencl.at(Channel::Samples, i, j) > 1.0f) continue;
      ++pixels_compared;
      const glm::dvec3 hit =
          basis.origin + pixel_ray_direction(basis, i, j) * static_cast<double>(opencl.at(Channel::Depth, i, j));
      power_rounding = power_slope * light_radiance_at(scene, hit);
      for (std::size_t t = 0; t < triples_compared; ++t) {
        const Channel(&triple)[3] = triples[t];
        double size = 1.0, diff = 0.0;
        for (Channel c : triple) {
          size = std::max(size, std::abs(static_cast<double>(reshaded.at(c, i, j))));
          diff = std::max(diff, difference(opencl.at(c, i, j), reshaded.at(c, i, j)));
        }
        diffs.push_back(diff);
        ratios.push_back(diff / (kColorQuantum * size + power_rounding));
      }
    }
  }
  const ErrorSummary summary = summarise(diffs);
  r.shading_max_abs = summary.max;
  r.shading_p99_abs = summary.p99;
  r.shading_compared = pixels_compared;
  const double ratio_p99 = summarise(ratios).p99;
  r.ratios.shading_p99 = ratio_p99;
  r.tolerances.shading_p99_abs = ratio_p99 > 0.0 ? summary.p99 / ratio_p99 : kColorQuantum + power_rounding;
  if (ratio_p99 > 1.0) {
    r.failures.push_back(
        fmt::format("shading error p99 is {:.3g} times its per-pixel tolerance (half a step of 8 bits "
                    "of the color's size; against the reference's color of the same hits)",
                    ratio_p99));
  }
  return r;
}

nlohmann::json CheckReport::to_json() const {
  const auto summary = [](const ErrorSummary& s) {
    return nlohmann::json{{"p50", s.p50}, {"p99", s.p99}, {"max", s.max}, {"rms", s.rms}};
  };
  const auto or_null = [](const std::optional<std::uint64_t>& n) {
    return n ? nlohmann::json(*n) : nlohmann::json(nullptr);
  };
  return {{"passed", passed()},
          {"pixels", pixels},
          {"both_hit", both_hit},
          {"out_of_steps", {{"opencl", or_null(out_of_steps_opencl)}, {"reference", or_null(out_of_steps_reference)}}},
          {"mask_mismatch", {{"silhouette", mask_mismatch_silhouette}, {"interior", mask_mismatch_interior}}},
          {"depth_abs", summary(depth_abs)},
          {"depth_rel", summary(depth_rel)},
          {"depth_in_epsilons", summary(depth_in_epsilons)},
          {"depth_in_tolerances", summary(depth_in_tolerances)},
          {"steps_diff", {{"mean", steps_diff_mean}, {"max", steps_diff_max}}},
          {"normal_angle_deg_p99", normal_angle_p99},
          {"normal_tolerance_past_pi", normal_tolerance_past_pi},
          {"normal_rounding_past_pi", normal_rounding_past_pi},
          {"color",
           {{"max_abs", color_max_abs},
            {"p99_abs", color_p99_abs},
            {"psnr_db", color_psnr_db},
            {"miss_p99_abs", miss_color_p99_abs},
            {"compared", color_compared},
            {"misses_compared", misses_compared}}},
          {"shading", {{"max_abs", shading_max_abs}, {"p99_abs", shading_p99_abs}, {"compared", shading_compared}}},
          {"id_mismatch", {{"edge", id_mismatch_edge}, {"interior", id_mismatch_interior}, {"compared", ids_compared}}},
          {"non_finite", {{"opencl", non_finite_opencl}, {"reference", non_finite_reference}}},
          {"tolerances",
           {{"mask_mismatch_interior", tolerances.mask_mismatch_interior},
            {"mask_mismatch_silhouette", tolerances.mask_mismatch_silhouette},
            {"depth_in_tolerances_p99", tolerances.depth_in_tolerances_p99},
            {"steps_diff_mean", tolerances.steps_diff_mean},
            {"shading_p99_abs", tolerances.shading_p99_abs},
            {"id_mismatch_interior", tolerances.id_mismatch_interior},
            {"id_mismatch_edge", tolerances.id_mismatch_edge},
            {"normal_past_pi", tolerances.normal_past_pi}}},
          {"ratios_p99",
           {{"normal", ratios.normal_p99},
            {"color", ratios.color_p99},
            {"miss_color", ratios.miss_color_p99},
            {"shading", ratios.shading_p99}}},
          {"failures", failures}};
}

std::string CheckReport::to_text() const {
  // Lines that decide the check start with PASS or FAIL and name their limit; the others are figures.
  const auto decided = [](bool pass) { return pass ? "PASS " : "FAIL "; };
  const std::string figure = "     ";
  const auto count = [](const std::optional<std::uint64_t>& n) { return n ? std::to_string(*n) : std::string("n/a"); };
  std::string out;
  out += fmt::format("{}pixels            {} ({} hit on both sides)\n", figure, pixels, both_hit);
  out += fmt::format(
      "{}out of steps      OpenCL {}, reference {} (rays neither hit nor past their end: reported, not checked)\n",
      figure, count(out_of_steps_opencl), count(out_of_steps_reference));
  out += fmt::format("{}non-finite        OpenCL {}, reference {} pixels (max 0)\n",
                     decided(non_finite_opencl + non_finite_reference == 0), non_finite_opencl, non_finite_reference);
  out += fmt::format("{}hit-mask mismatch silhouette {} (max {}), interior {} (max {})\n",
                     decided(mask_mismatch_silhouette <= tolerances.mask_mismatch_silhouette &&
                             mask_mismatch_interior <= tolerances.mask_mismatch_interior),
                     mask_mismatch_silhouette, tolerances.mask_mismatch_silhouette, mask_mismatch_interior,
                     tolerances.mask_mismatch_interior);
  out += fmt::format("{}depth / tolerance p99 {:.3g} (max {:g})  p50 {:.3g}  max {:.3g}\n",
                     decided(depth_in_tolerances.p99 <= tolerances.depth_in_tolerances_p99), depth_in_tolerances.p99,
                     tolerances.depth_in_tolerances_p99, depth_in_tolerances.p50, depth_in_tolerances.max);
  out += fmt::format("{}depth abs         p50 {:.3g}  p99 {:.3g}  max {:.3g}\n", figure, depth_abs.p50, depth_abs.p99,
                     depth_abs.max);
  out += fmt::format("{}depth rel         p50 {:.3g}  p99 {:.3g}  max {:.3g}\n", figure, depth_rel.p50, depth_rel.p99,
                     depth_rel.max);
  out += fmt::format("{}depth / epsilon   p50 {:.3g}  p99 {:.3g}  max {:.3g}\n", figure, depth_in_epsilons.p50,
                     depth_in_epsilons.p99, depth_in_epsilons.max);
  out += fmt::format(
      "{}steps difference  mean {:.3g} (max {:g})  max {}{}\n", decided(steps_diff_mean <= tolerances.steps_diff_mean),
      steps_diff_mean, tolerances.steps_diff_mean, steps_diff_max,
      steps_one_sided ? "  (steps short of the reference's only: an operand grid bounds its union outside)" : "");
  out += fmt::format("{}normal angle p99  {:.3g} deg: {:.3g} of its per-pixel tolerance (max 1)\n",
                     decided(ratios.normal_p99 <= 1.0), normal_angle_p99, ratios.normal_p99);
  out += fmt::format("{}normal tolerance  past pi at {} pixels both hit (max {:.0f}: there it would pass any normal)\n",
                     decided(normal_tolerance_past_pi <= tolerances.normal_past_pi), normal_tolerance_past_pi,
                     std::floor(tolerances.normal_past_pi));
  out += fmt::format(
      "{}color of hits     p99 abs {:.3g}: {:.3g} of its per-pixel tolerance (max 1)  max abs {:.3g}  PSNR {:.1f} dB\n",
      decided(ratios.color_p99 <= 1.0), color_p99_abs, ratios.color_p99, color_max_abs, color_psnr_db);
  out += fmt::format(
      "{}color of misses   p99 abs {:.3g}: {:.3g} of its per-pixel tolerance (max 1)  ({} misses compared)\n",
      decided(ratios.miss_color_p99 <= 1.0), miss_color_p99_abs, ratios.miss_color_p99, misses_compared);
  if (shading_compared > 0) {
    out += fmt::format(
        "{}shading           p99 abs {:.3g}: {:.3g} of its per-pixel tolerance (max 1)  max abs {:.3g}  "
        "({} hits shaded by both: color, ao, diffuse, specular)\n",
        decided(ratios.shading_p99 <= 1.0), shading_p99_abs, ratios.shading_p99, shading_max_abs, shading_compared);
  }
  if (ids_compared > 0) {
    out += fmt::format("{}id mismatch       edge {} (max {}), interior {} (max {})  ({} hits compared)\n",
                       decided(id_mismatch_edge <= tolerances.id_mismatch_edge &&
                               id_mismatch_interior <= tolerances.id_mismatch_interior),
                       id_mismatch_edge, tolerances.id_mismatch_edge, id_mismatch_interior,
                       tolerances.id_mismatch_interior, ids_compared);
  }
  out += passed() ? "check passed\n" : "check FAILED:\n";
  for (const std::string& f : failures) out += "  " + f + "\n";
  return out;
}

FrameBuffers difference_image(const FrameBuffers& a, const FrameBuffers& b) {
  FrameBuffers out(a.width, a.height);
  for (int c = 0; c < kChannelCount; ++c) {
    for (std::size_t i = 0; i < out.planes[c].size(); ++i) {
      const float x = a.planes[c][i], y = b.planes[c][i];
      out.planes[c][i] = (std::isinf(x) && std::isinf(y)) ? 0.0f : std::abs(x - y);
    }
  }
  return out;
}

}  // namespace clmarch
