// The reference distance field in double: primitives, operators with their color rules, and the
// recursive walk of the node tree with transforms and inherited colors.
#include "reference/reference_sdf.hpp"

#include "reference/reference_fractals.hpp"
#include "reference/reference_noise.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace clmarch {
namespace {

// mix as the scene format defines it, x + (y - x) * h; glm::mix rounds differently.
double mix(double x, double y, double h) { return x + (y - x) * h; }
glm::dvec3 mix(const glm::dvec3& x, const glm::dvec3& y, double h) { return x + (y - x) * h; }

double max_component(const glm::dvec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

// Shared by sd_box and sd_round_box: the box of half size h (already subtracted) in q.
double box_from_q(const glm::dvec3& q) {
  return glm::length(glm::max(q, 0.0)) + std::min(max_component(q), 0.0);
}

// Blend weights of the smooth operators; the sample overloads reuse them for colors.
double smooth_union_weight(double a, double b, double k) {
  return std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
}
double smooth_intersection_weight(double a, double b, double k) {
  return std::clamp(0.5 - 0.5 * (b - a) / k, 0.0, 1.0);
}
double smooth_subtraction_weight(double a, double b, double k) {
  return std::clamp(0.5 - 0.5 * (a + b) / k, 0.0, 1.0);
}

[[noreturn]] void malformed(const Node& node, const std::string& what) {
  throw std::invalid_argument("reference_sdf: " + std::string(node_kind_name(node.kind)) + " node " + what);
}

template <class T>
const T& params(const Node& node) {
  if (const T* p = std::get_if<T>(&node.params)) return *p;
  malformed(node, "carries the parameters of another kind");
}

SdfSample sample_node(const Node& node, const glm::dvec3& p_parent, const Material& parent);

template <class Op>
SdfSample fold_children(const Node& node, const glm::dvec3& p, const Material& color, Op op) {
  if (node.children.empty()) malformed(node, "has no children");
  SdfSample acc = sample_node(node.children.front(), p, color);
  for (std::size_t i = 1; i < node.children.size(); ++i) acc = op(acc, sample_node(node.children[i], p, color));
  return acc;
}

template <class Op>
SdfSample fold_smooth(const Node& node, double k, const glm::dvec3& p, const Material& color, Op op) {
  if (!(k > 0.0)) malformed(node, "needs k > 0 (got " + std::to_string(k) + ")");
  return fold_children(node, p, color, [&](const SdfSample& a, const SdfSample& b) { return op(a, b, k); });
}

SdfSample only_child(const Node& node, const glm::dvec3& p, const Material& color) {
  if (node.children.size() != 1) malformed(node, "needs exactly one child");
  return sample_node(node.children.front(), p, color);
}

// The node's own kind in its local frame p; material is its effective material (leaves get their
// surface parameters in sample_node).
SdfSample sample_local(const Node& node, const glm::dvec3& p, const Material& material) {
  using S = SdfSample;
  const glm::dvec3& color = material.albedo;
  // One switch over every kind, without default, so -Wswitch flags a kind added to the list.
  switch (node.kind) {
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) \
  case NodeKind::Kind: return S{sd_##name(p, params<Kind>(node)), color};
#include "scene/node_kinds.def"
    case NodeKind::Union:
      return fold_children(node, p, material, [](const S& a, const S& b) { return op_union(a, b); });
    case NodeKind::Intersection:
      return fold_children(node, p, material, [](const S& a, const S& b) { return op_intersection(a, b); });
    case NodeKind::Subtraction:
      return fold_children(node, p, material, [](const S& a, const S& b) { return op_subtraction(a, b); });
    case NodeKind::SmoothUnion:
      return fold_smooth(node, params<SmoothUnion>(node).k, p, material,
                         [](const S& a, const S& b, double k) { return op_smooth_union(a, b, k); });
    case NodeKind::SmoothIntersection:
      return fold_smooth(node, params<SmoothIntersection>(node).k, p, material,
                         [](const S& a, const S& b, double k) { return op_smooth_intersection(a, b, k); });
    case NodeKind::SmoothSubtraction:
      return fold_smooth(node, params<SmoothSubtraction>(node).k, p, material,
                         [](const S& a, const S& b, double k) { return op_smooth_subtraction(a, b, k); });
    case NodeKind::Repeat: {
      glm::dvec3 q = p;
      for (int a = 0; a < 3; ++a) {
        const double c = params<Repeat>(node).period[a];
        if (c > 0.0) q[a] = p[a] - c * std::floor(p[a] / c + 0.5);
      }
      return only_child(node, q, material);
    }
    case NodeKind::Displace: {
      S s = only_child(node, p, material);
      const Displace& displace = params<Displace>(node);
      const double f = displace.frequency;
      const double texture = displace.amplitude * std::sin(f * p.x) * std::sin(f * p.y) * std::sin(f * p.z);
      s.distance = (s.distance + texture) / displacement_lipschitz(node);
      return s;
    }
  }
  malformed(node, "has an unknown kind");
}

SdfSample sample_node(const Node& node, const glm::dvec3& p_parent, const Material& parent) {
  const Transform& xf = node.transform;
  glm::dvec3 p = p_parent - xf.translate;
  // Skipping the identity rotation is only a speed-up: R would be exactly the identity matrix.
  if (xf.rotate_degrees != glm::dvec3(0.0)) p = glm::transpose(xf.world_from_local_rotation()) * p;
  p /= xf.scale;
  Material material = parent;
  if (node.color) material.albedo = *node.color;
  if (node.metallic) material.metallic = *node.metallic;
  if (node.roughness) material.roughness = *node.roughness;
  if (node.reflectivity) material.reflectivity = *node.reflectivity;
  SdfSample s = sample_local(node, p, material);
  if (is_primitive(node.kind)) s.surface = {material.metallic, material.roughness, material.reflectivity};
  s.distance *= xf.scale;
  // A bound for fields steeper than 1 (terrain, fractals): the march takes shorter steps.
  s.distance *= node.step_factor;
  return s;
}

}  // namespace

double reference_distance(const Node& root, const glm::dvec3& p) { return reference_sample(root, p).distance; }

SdfSample reference_sample(const Node& root, const glm::dvec3& p) { return sample_node(root, p, Material{}); }

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
  const glm::dvec2 d = glm::abs(glm::dvec2(glm::length(glm::dvec2(q.x, q.z)), q.y)) -
                       glm::dvec2(cylinder.radius, cylinder.half_height);
  return std::min(std::max(d.x, d.y), 0.0) + glm::length(glm::max(d, 0.0));
}

double sd_infinite_cylinder(const glm::dvec3& p, const InfiniteCylinder& cylinder) {
  return glm::length(glm::dvec2(p.x - cylinder.center.x, p.z - cylinder.center.z)) - cylinder.radius;
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
  return {op_subtraction(a.distance, b.distance), kept.color, kept.surface};
}

SdfSample op_smooth_union(const SdfSample& a, const SdfSample& b, double k) {
  const double h = smooth_union_weight(a.distance, b.distance, k);
  return {op_smooth_union(a.distance, b.distance, k), mix(b.color, a.color, h), mix(b.surface, a.surface, h)};
}

SdfSample op_smooth_intersection(const SdfSample& a, const SdfSample& b, double k) {
  const double h = smooth_intersection_weight(a.distance, b.distance, k);
  return {op_smooth_intersection(a.distance, b.distance, k), mix(b.color, a.color, h), mix(b.surface, a.surface, h)};
}

SdfSample op_smooth_subtraction(const SdfSample& a, const SdfSample& b, double k) {
  const double h = smooth_subtraction_weight(a.distance, b.distance, k);
  return {op_smooth_subtraction(a.distance, b.distance, k), mix(a.color, b.color, h), mix(a.surface, b.surface, h)};
}

}  // namespace clmarch
