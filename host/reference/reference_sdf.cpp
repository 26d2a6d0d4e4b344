// The reference distance field in double: primitives, operators with their color rules, and the
// recursive walk of the node tree with transforms and inherited colors.
#include "reference/reference_sdf.hpp"

#include "reference/reference_blends.hpp"
#include "reference/reference_patterns.hpp"

#include "reference/reference_fractals.hpp"
#include "reference/reference_geometry.hpp"
#include "reference/reference_noise.hpp"
#include "scene/scene_bounds.hpp"

#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/rotate_vector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace clmarch {
namespace {

using geometry::convex_polygon_distance;
using geometry::distance_to_segment;
using geometry::distance_to_triangle;
using geometry::extrude;

// mix as the scene format defines it, x + (y - x) * h; glm::mix rounds differently.
double mix(double x, double y, double h) { return x + (y - x) * h; }
glm::dvec3 mix(const glm::dvec3& x, const glm::dvec3& y, double h) { return x + (y - x) * h; }

double max_component(const glm::dvec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

// Shared by sd_box and sd_round_box: the box of half size h (already subtracted) in q.
double box_from_q(const glm::dvec3& q) { return glm::length(glm::max(q, 0.0)) + std::min(max_component(q), 0.0); }

// Blend weights of the smooth operators; the sample overloads reuse them for colors.
double smooth_union_weight(double a, double b, double k) { return std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0); }
double smooth_intersection_weight(double a, double b, double k) {
  return std::clamp(0.5 - 0.5 * (b - a) / k, 0.0, 1.0);
}
double smooth_subtraction_weight(double a, double b, double k) { return std::clamp(0.5 - 0.5 * (a + b) / k, 0.0, 1.0); }

[[noreturn]] void malformed(const Node& node, const std::string& what) {
  throw std::invalid_argument("reference_sdf: " + std::string(node_kind_name(node.kind)) + " node " + what);
}

template <class T>
const T& params(const Node& node) {
  if (const T* p = std::get_if<T>(&node.params)) return *p;
  malformed(node, "carries the parameters of another kind");
}

SdfSample sample_node(const Node& node, const glm::dvec3& p_parent, const Material& parent, bool colored);

template <class Op>
SdfSample fold_children(const Node& node, const glm::dvec3& p, const Material& color, bool colored, Op op) {
  if (node.children.empty()) malformed(node, "has no children");
  SdfSample acc = sample_node(node.children.front(), p, color, colored);
  // Each child numbers its own primitives from 0: the later ones follow the earlier children's.
  int first_primitive = primitive_count(node.children.front());
  for (std::size_t i = 1; i < node.children.size(); ++i) {
    SdfSample next = sample_node(node.children[i], p, color, colored);
    next.primitive += first_primitive;
    first_primitive += primitive_count(node.children[i]);
    acc = op(acc, next);
  }
  return acc;
}

template <class Op>
SdfSample fold_smooth(const Node& node, double k, const glm::dvec3& p, const Material& color, bool colored, Op op) {
  if (!(k > 0.0)) malformed(node, "needs k > 0 (got " + std::to_string(k) + ")");
  return fold_children(node, p, color, colored, [&](const SdfSample& a, const SdfSample& b) { return op(a, b, k); });
}

SdfSample only_child(const Node& node, const glm::dvec3& p, const Material& color, bool colored) {
  if (node.children.size() != 1) malformed(node, "needs exactly one child");
  return sample_node(node.children.front(), p, color, colored);
}

// Twist (about y by rate y) and bend (about z by rate x): the child at p turned, its distance divided
// by the largest stretch of the turning map on the way to the surface, and never below the
// distance to the sphere that holds the turned child.
SdfSample sample_turned(const Node& node, const glm::dvec3& p, const Material& material, bool colored) {
  const bool twist = node.kind == NodeKind::Twist;
  const double rate = glm::radians(twist ? params<Twist>(node).rate : params<Bend>(node).rate);
  const std::optional<BoundingSphere> child_bounds = node_bounds(node.children.front());
  if (!child_bounds) malformed(node, "needs a bounded child");
  const int axis = twist ? 1 : 2;
  const glm::dvec3 axis_vector = twist ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
  const double angle = rate * (twist ? p.y : p.x);
  const glm::dvec3 turned = glm::rotate(p, angle, axis_vector);
  SdfSample s = only_child(node, turned, material, colored);
  glm::dvec3 across = p;
  across[axis] = 0.0;
  const double a = std::abs(rate) * std::max(glm::length(across), turn_reach(*child_bounds, axis));
  // Twist's Jacobian, I + v e_y^T with v (|v| = a) across the axis: singular value (a + sqrt(a^2 + 4)) / 2.
  // Bend's, I + u e_x^T with u in the xy plane: at most 1 + a.
  const double stretch = twist ? 0.5 * (a + std::sqrt(a * a + 4.0)) : 1.0 + a;
  const BoundingSphere ball = turned_bounds(*child_bounds, axis);
  s.distance = std::max(s.distance / stretch, glm::length(p - ball.center) - ball.radius);
  return s;
}

// The node's own kind in its local frame p; material is its effective material (leaves get their
// surface parameters in sample_node).
SdfSample sample_local(const Node& node, const glm::dvec3& p, const Material& material, bool colored) {
  using S = SdfSample;
  const glm::dvec3& color = material.albedo;
  // One switch over every kind, without default, so -Wswitch flags a kind added to the list.
  switch (node.kind) {
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) \
  case NodeKind::Kind:                                            \
    return S{sd_##name(p, params<Kind>(node)), color};
#include "scene/node_kinds.def"
    case NodeKind::Union:
      return fold_children(node, p, material, colored, [](const S& a, const S& b) { return op_union(a, b); });
    case NodeKind::Intersection:
      return fold_children(node, p, material, colored, [](const S& a, const S& b) { return op_intersection(a, b); });
    case NodeKind::Subtraction:
      return fold_children(node, p, material, colored, [](const S& a, const S& b) { return op_subtraction(a, b); });
    case NodeKind::SmoothUnion:
      return fold_smooth(node, params<SmoothUnion>(node).k, p, material, colored,
                         [](const S& a, const S& b, double k) { return op_smooth_union(a, b, k); });
    case NodeKind::SmoothIntersection:
      return fold_smooth(node, params<SmoothIntersection>(node).k, p, material, colored,
                         [](const S& a, const S& b, double k) { return op_smooth_intersection(a, b, k); });
    case NodeKind::SmoothSubtraction:
      return fold_smooth(node, params<SmoothSubtraction>(node).k, p, material, colored,
                         [](const S& a, const S& b, double k) { return op_smooth_subtraction(a, b, k); });
#define CLMARCH_BLEND(Kind, name, min_children, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
      return fold_children(node, p, material, colored,
                           [&](const S& a, const S& b) { return blend_sample(node, a, b); });
    case NodeKind::Repeat: {
      glm::dvec3 q = p;
      for (int a = 0; a < 3; ++a) {
        const double c = params<Repeat>(node).period[a];
        if (c > 0.0) q[a] = p[a] - c * std::floor(p[a] / c + 0.5);
      }
      return only_child(node, q, material, colored);
    }
    case NodeKind::Displace: {
      S s = only_child(node, p, material, colored);
      const Displace& displace = params<Displace>(node);
      const double f = displace.frequency;
      const double texture = displace.amplitude * std::sin(f * p.x) * std::sin(f * p.y) * std::sin(f * p.z);
      s.distance = (s.distance + texture) / displacement_lipschitz(node);
      return s;
    }
    case NodeKind::Elongate: {
      const glm::dvec3& h = params<Elongate>(node).h;
      return only_child(node, p - glm::clamp(p, -h, h), material, colored);
    }
    case NodeKind::Onion: {
      S s = only_child(node, p, material, colored);
      s.distance = std::abs(s.distance) - params<Onion>(node).thickness;
      return s;
    }
    case NodeKind::Round: {
      S s = only_child(node, p, material, colored);
      s.distance -= params<Round>(node).radius;
      return s;
    }
    case NodeKind::Mirror: {
      const glm::bvec3& axes = params<Mirror>(node).axes;
      glm::dvec3 q = p;
      for (int a = 0; a < 3; ++a) {
        if (axes[a]) q[a] = std::abs(p[a]);
      }
      return only_child(node, q, material, colored);
    }
    case NodeKind::RepeatPolar: {
      // The nearest copy's angle, and p in that copy's frame: the rotation by minus that angle.
      const double sector = 2.0 * std::numbers::pi / params<RepeatPolar>(node).count;
      const double turn = sector * std::round(std::atan2(p.z, p.x) / sector);
      const double radius = std::hypot(p.x, p.z);
      const double angle = std::atan2(p.z, p.x) - turn;
      return only_child(node, {radius * std::cos(angle), p.y, radius * std::sin(angle)}, material, colored);
    }
    case NodeKind::Revolve: {
      const double radial = std::hypot(p.x, p.z) - params<Revolve>(node).offset;
      return only_child(node, {radial, p.y, 0.0}, material, colored);
    }
    case NodeKind::Extrude: {
      // The section's distance and the distance past the end caps, combined as a 2D box's are.
      S s = only_child(node, {p.x, p.y, 0.0}, material, colored);
      const glm::dvec2 w(s.distance, std::abs(p.z) - params<Extrude>(node).half_length);
      s.distance = std::min(std::max(w.x, w.y), 0.0) + glm::length(glm::max(w, 0.0));
      return s;
    }
    case NodeKind::Twist:
    case NodeKind::Bend:
      return sample_turned(node, p, material, colored);
    case NodeKind::NonuniformScale: {
      const glm::dvec3& f = params<NonuniformScale>(node).factors;
      S s = only_child(node, p / f, material, colored);
      s.distance *= std::min({f.x, f.y, f.z});
      return s;
    }
    case NodeKind::RepeatLimited: {
      const RepeatLimited& repeat = params<RepeatLimited>(node);
      glm::dvec3 q = p;
      for (int a = 0; a < 3; ++a) {
        const double c = repeat.period[a];
        if (c > 0.0) q[a] = p[a] - c * std::clamp(std::round(p[a] / c), double(repeat.min[a]), double(repeat.max[a]));
      }
      return only_child(node, q, material, colored);
    }
  }
  malformed(node, "has an unknown kind");
}

SdfSample sample_node(const Node& node, const glm::dvec3& p_parent, const Material& parent, bool colored) {
  const Transform& xf = node.transform;
  glm::dvec3 p = p_parent - xf.translate;
  // Skipping the identity rotation is only a speed-up: R would be exactly the identity matrix.
  if (xf.rotate_degrees != glm::dvec3(0.0)) p = glm::transpose(xf.world_from_local_rotation()) * p;
  p /= xf.scale;
  Material material = node.material_over(parent);
  if (node.color_pattern && colored) {
    // One color at this point for the whole subtree: the pattern's, in this node's frame.
    material.albedo = reference_pattern_color(*node.color_pattern, p);
    material.pattern = nullptr;
  }
  SdfSample s = sample_local(node, p, material, colored);
  if (node.kind == NodeKind::Glsl && colored) {
    // The code's colour function, where it has one, over the node's color.
    const GlslProgram& program = *params_of<Glsl>(node).program;
    if (program.module.color_function >= 0) s.color = program.interpreter->color(p, program.time);
  }
  if (is_primitive(node.kind)) {
    s.surface = {material.metallic, material.roughness, material.reflectivity};
    s.finish = {material.specular, material.shininess};
    s.emission = material.emission;
  }
  s.distance *= xf.scale;
  // A bound for fields steeper than 1 (terrain, fractals): the march takes shorter steps.
  s.distance *= node.step_factor;
  return s;
}

}  // namespace

double reference_distance(const Node& root, const glm::dvec3& p) {
  // The march and the normals need no material: a color pattern (a parse of its expressions)
  // costs more than the distance.
  return sample_node(root, p, Material{}, false).distance;
}

SdfSample reference_sample(const Node& root, const glm::dvec3& p, const Material& root_material) {
  return sample_node(root, p, root_material, true);
}

double sd_sphere(const glm::dvec3& p, const Sphere& sphere) { return glm::length(p - sphere.center) - sphere.radius; }

double sd_box(const glm::dvec3& p, const Box& box) { return box_from_q(glm::abs(p - box.center) - box.half_size); }

double sd_round_box(const glm::dvec3& p, const RoundBox& box) {
  return box_from_q(glm::abs(p - box.center) - box.half_size + box.radius) - box.radius;
}

double sd_box_frame(const glm::dvec3& p, const BoxFrame& frame) {
  const double e = frame.thickness;
  const glm::dvec3 a = glm::abs(p - frame.center) - frame.half_size;
  const glm::dvec3 q = glm::abs(a + e) - e;
  // One bar family per axis: along x the bar is bounded by a.x, across it by q.y and q.z.
  const auto bar = [](double along, double across1, double across2) {
    const glm::dvec3 v(along, across1, across2);
    return glm::length(glm::max(v, 0.0)) + std::min(max_component(v), 0.0);
  };
  return std::min(bar(a.x, q.y, q.z), std::min(bar(q.x, a.y, q.z), bar(q.x, q.y, a.z)));
}

double sd_torus(const glm::dvec3& p, const Torus& torus) {
  const glm::dvec3 l = p - torus.center;
  const glm::dvec2 q(glm::length(glm::dvec2(l.x, l.z)) - torus.major_radius, l.y);
  return glm::length(q) - torus.minor_radius;
}

double sd_plane(const glm::dvec3& p, const Plane& plane) { return glm::dot(plane.normal, p) + plane.offset; }

double sd_capsule(const glm::dvec3& p, const Capsule& capsule) {
  const glm::dvec3 pa = p - capsule.a;
  const glm::dvec3 ba = capsule.b - capsule.a;
  const double h = std::clamp(glm::dot(pa, ba) / glm::dot(ba, ba), 0.0, 1.0);
  return glm::length(pa - ba * h) - capsule.radius;
}

double sd_cylinder(const glm::dvec3& p, const Cylinder& cylinder) {
  const glm::dvec3 q = p - cylinder.center;
  const glm::dvec2 d =
      glm::abs(glm::dvec2(glm::length(glm::dvec2(q.x, q.z)), q.y)) - glm::dvec2(cylinder.radius, cylinder.half_height);
  return std::min(std::max(d.x, d.y), 0.0) + glm::length(glm::max(d, 0.0));
}

double sd_infinite_cylinder(const glm::dvec3& p, const InfiniteCylinder& cylinder) {
  return glm::length(glm::dvec2(p.x - cylinder.center.x, p.z - cylinder.center.z)) - cylinder.radius;
}

double sd_octahedron(const glm::dvec3& p, const Octahedron& octahedron) {
  // By symmetry the nearest face lies in p's octant: the triangle of the three vertices there.
  const glm::dvec3 a = glm::abs(p - octahedron.center);
  const double s = octahedron.size;
  const double plane = (a.x + a.y + a.z - s) / std::sqrt(3.0);
  if (plane <= 0.0) return plane;
  return distance_to_triangle(a, {s, 0.0, 0.0}, {0.0, s, 0.0}, {0.0, 0.0, s});
}

double sd_hex_prism(const glm::dvec3& p, const HexPrism& prism) {
  const glm::dvec3 l = p - prism.center;
  // The hexagon in the xz plane (x right, z up in the plane): corners at 0, 60, ... degrees on
  // the circle through them, radius / cos 30 from the centre, so that one side is at z = radius.
  std::vector<glm::dvec2> corners;
  const double corner_radius = prism.radius / std::cos(std::numbers::pi / 6.0);
  for (int i = 0; i < 6; ++i) {
    const double angle = i * std::numbers::pi / 3.0;
    corners.emplace_back(corner_radius * std::cos(angle), corner_radius * std::sin(angle));
  }
  return extrude(convex_polygon_distance({l.x, l.z}, corners), l.y, prism.half_height);
}

// The profiles: distances in the xy plane, z unused.
double sd_circle(const glm::dvec3& p, const Circle& circle) {
  return glm::length(glm::dvec2(p) - glm::dvec2(circle.center)) - circle.radius;
}

namespace {

/// The rectangle's corners about centre, counter-clockwise.
std::vector<glm::dvec2> rectangle_corners(const glm::dvec3& center, double half_width, double half_height) {
  const glm::dvec2 c(center);
  return {c + glm::dvec2(-half_width, -half_height), c + glm::dvec2(half_width, -half_height),
          c + glm::dvec2(half_width, half_height), c + glm::dvec2(-half_width, half_height)};
}

}  // namespace

double sd_rectangle(const glm::dvec3& p, const Rectangle& rectangle) {
  return convex_polygon_distance(glm::dvec2(p),
                                 rectangle_corners(rectangle.center, rectangle.half_width, rectangle.half_height));
}

double sd_rounded_rectangle(const glm::dvec3& p, const RoundedRectangle& rectangle) {
  // The points within radius of the rectangle shrunk by radius.
  const double r = rectangle.radius;
  return convex_polygon_distance(
             glm::dvec2(p), rectangle_corners(rectangle.center, rectangle.half_width - r, rectangle.half_height - r)) -
         r;
}

double sd_segment(const glm::dvec3& p, const Segment& segment) {
  return distance_to_segment(glm::dvec2(p), glm::dvec2(segment.a), glm::dvec2(segment.b)) - segment.radius;
}

double sd_regular_polygon(const glm::dvec3& p, const RegularPolygon& polygon) {
  std::vector<glm::dvec2> corners;
  for (int i = 0; i < polygon.sides; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / polygon.sides;
    corners.push_back(glm::dvec2(polygon.center) + polygon.radius * glm::dvec2(std::cos(angle), std::sin(angle)));
  }
  return convex_polygon_distance(glm::dvec2(p), corners);
}

double sd_capped_cone(const glm::dvec3& p, const CappedCone& cone) {
  // The solid of revolution of the trapezoid (0, -h), (r1, -h), (r2, h), (0, h) in the (r, y)
  // half plane; its edge on the axis is no boundary of the solid.
  const glm::dvec3 l = p - cone.center;
  const glm::dvec2 q(glm::length(glm::dvec2(l.x, l.z)), l.y);
  const double h = cone.half_height;
  const glm::dvec2 bottom_axis(0.0, -h), bottom_rim(cone.bottom_radius, -h), top_rim(cone.top_radius, h),
      top_axis(0.0, h);
  const double nearest =
      std::min({distance_to_segment(q, bottom_axis, bottom_rim), distance_to_segment(q, bottom_rim, top_rim),
                distance_to_segment(q, top_rim, top_axis)});
  const double radius_at_y = cone.bottom_radius + (cone.top_radius - cone.bottom_radius) * (q.y + h) / (2.0 * h);
  const bool inside = std::abs(q.y) <= h && q.x <= radius_at_y;
  return inside ? -nearest : nearest;
}

double sd_ellipsoid(const glm::dvec3& p, const Ellipsoid& ellipsoid) {
  const glm::dvec3 l = p - ellipsoid.center;
  const double k0 = glm::length(l / ellipsoid.radii);
  const double k1 = glm::length(l / (ellipsoid.radii * ellipsoid.radii));
  if (k1 == 0.0) return -std::min({ellipsoid.radii.x, ellipsoid.radii.y, ellipsoid.radii.z});
  return k0 * (k0 - 1.0) / k1;
}

double op_union(double a, double b) { return std::min(a, b); }
double op_intersection(double a, double b) { return std::max(a, b); }
double op_subtraction(double a, double b) { return std::max(a, -b); }

double op_smooth_union(double a, double b, double k) {
  const double h = smooth_union_weight(a, b, k);
  return mix(b, a, h) - k * h * (1.0 - h);
}

double op_smooth_intersection(double a, double b, double k) {
  const double h = smooth_intersection_weight(a, b, k);
  return mix(b, a, h) + k * h * (1.0 - h);
}

double op_smooth_subtraction(double a, double b, double k) {
  const double h = smooth_subtraction_weight(a, b, k);
  return mix(a, -b, h) + k * h * (1.0 - h);
}

SdfSample op_union(const SdfSample& a, const SdfSample& b) { return b.distance < a.distance ? b : a; }
SdfSample op_intersection(const SdfSample& a, const SdfSample& b) { return b.distance > a.distance ? b : a; }

SdfSample op_subtraction(const SdfSample& a, const SdfSample& b) {
  const SdfSample& kept = a.distance >= -b.distance ? a : b;
  return {op_subtraction(a.distance, b.distance), kept.color, kept.surface, kept.primitive, kept.finish, kept.emission};
}

SdfSample op_smooth_union(const SdfSample& a, const SdfSample& b, double k) {
  const double h = smooth_union_weight(a.distance, b.distance, k);
  return {op_smooth_union(a.distance, b.distance, k), mix(b.color, a.color, h),   mix(b.surface, a.surface, h),
          h >= 0.5 ? a.primitive : b.primitive,       mix(b.finish, a.finish, h), mix(b.emission, a.emission, h)};
}

SdfSample op_smooth_intersection(const SdfSample& a, const SdfSample& b, double k) {
  const double h = smooth_intersection_weight(a.distance, b.distance, k);
  return {op_smooth_intersection(a.distance, b.distance, k),
          mix(b.color, a.color, h),
          mix(b.surface, a.surface, h),
          h >= 0.5 ? a.primitive : b.primitive,
          mix(b.finish, a.finish, h),
          mix(b.emission, a.emission, h)};
}

SdfSample op_smooth_subtraction(const SdfSample& a, const SdfSample& b, double k) {
  const double h = smooth_subtraction_weight(a.distance, b.distance, k);
  return {op_smooth_subtraction(a.distance, b.distance, k),
          mix(a.color, b.color, h),
          mix(a.surface, b.surface, h),
          h >= 0.5 ? b.primitive : a.primitive,
          mix(a.finish, b.finish, h),
          mix(a.emission, b.emission, h)};
}

}  // namespace clmarch
