// Axis-aligned bounding boxes of the SDF tree, node by node.
#include "scene/scene_box.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clmarch {
namespace {

BoundingBox centred(const glm::dvec3& center, const glm::dvec3& half) { return {center - half, center + half}; }

BoundingBox merged(const BoundingBox& a, const BoundingBox& b) {
  return {glm::min(a.low, b.low), glm::max(a.high, b.high), std::max(a.gain, b.gain)};
}

/// Both boxes' promises at once: the field is below tau only inside each grown by its gain, so
/// inside their intersection grown by the larger gain.
BoundingBox intersected(const BoundingBox& a, const BoundingBox& b) {
  return {glm::max(a.low, b.low), glm::min(a.high, b.high), std::max(a.gain, b.gain)};
}

/// The box a primitive's shape fills where it is boxier than its sphere; nothing for the other
/// kinds, whose sphere's cube is their box.
std::optional<BoundingBox> primitive_box(const Node& node) {
  if (node.kind == NodeKind::Box) return centred(params_of<Box>(node).center, params_of<Box>(node).half_size);
  if (node.kind == NodeKind::RoundBox)
    return centred(params_of<RoundBox>(node).center, params_of<RoundBox>(node).half_size);
  if (node.kind == NodeKind::BoxFrame)
    return centred(params_of<BoxFrame>(node).center, params_of<BoxFrame>(node).half_size);
  if (node.kind == NodeKind::Menger) {
    const Menger& m = params_of<Menger>(node);
    return centred(m.center, glm::dvec3(m.half_size));
  }
  if (node.kind == NodeKind::Torus) {
    const Torus& t = params_of<Torus>(node);
    const double across = t.major_radius + t.minor_radius;
    return centred(t.center, {across, t.minor_radius, across});
  }
  return std::nullopt;
}

/// The box the children's boxes give the hard union, intersection and subtraction (the smooth ones
/// grow it as local_box does); nothing for the other operators, which keep their sphere's cube.
std::optional<BoundingBox> operator_box(const Node& node) {
  if (node.kind == NodeKind::Union || node.kind == NodeKind::SmoothUnion) {
    std::optional<BoundingBox> all;
    for (const Node& child : node.children) {
      const std::optional<BoundingBox> b = node_box(child);
      if (!b) return std::nullopt;
      all = all ? merged(*all, *b) : *b;
    }
    return all;
  }
  if (node.kind == NodeKind::Intersection || node.kind == NodeKind::SmoothIntersection) {
    std::optional<BoundingBox> common;
    for (const Node& child : node.children) {
      const std::optional<BoundingBox> b = node_box(child);
      if (b) common = common ? intersected(*common, *b) : *b;
    }
    return common;
  }
  if (node.kind == NodeKind::Subtraction || node.kind == NodeKind::SmoothSubtraction)
    return node_box(node.children.front());
  return std::nullopt;
}

/// The box in the node's own frame, before its transform, step_factor and scale.
std::optional<BoundingBox> local_box(const Node& node) {
  const std::optional<BoundingSphere> sphere = local_bounds(node);
  if (!sphere) return std::nullopt;
  BoundingBox box{sphere->center - sphere->radius, sphere->center + sphere->radius, sphere->gain};
  std::optional<BoundingBox> own = is_primitive(node.kind) ? primitive_box(node) : operator_box(node);
  if (own && is_smooth_operator(node.kind)) {
    // As local_bounds: the smooth minimum and maximum undershoot the hard ones by k / 4 a fold.
    const double growth = own->gain * smooth_k(node) / 4.0 * static_cast<double>(node.children.size() - 1);
    own->low -= growth;
    own->high += growth;
  }
  return own ? intersected(box, *own) : box;
}

}  // namespace

std::optional<BoundingBox> node_box(const Node& node) {
  const std::optional<BoundingBox> local = local_box(node);
  if (!local) return std::nullopt;
  // p_parent = translate + R (scale p_local): the centre moves, and the half sizes become those of
  // the turned box, |R| times the scaled half sizes.
  const Transform& t = node.transform;
  const glm::dmat3 rotation = t.world_from_local_rotation();
  const glm::dvec3 center = t.translate + rotation * (t.scale * 0.5 * (local->low + local->high));
  const glm::dvec3 half = t.scale * 0.5 * (local->high - local->low);
  glm::dvec3 turned(0.0);
  for (int column = 0; column < 3; ++column) {
    for (int row = 0; row < 3; ++row) turned[row] += std::abs(rotation[column][row]) * half[column];
  }
  BoundingBox box = centred(center, turned);
  box.gain = local->gain / node.step_factor;
  return box;
}

std::optional<BoundingBox> camera_ray_box(const Scene& scene) {
  // Step-count occlusion shades by the steps taken, which the box would cut: such scenes keep the
  // look the sphere alone gives them.
  if (scene.render.bounds != RayBounds::Box || scene.tiling || scene.shading.step_ao > 0.0) return std::nullopt;
  std::optional<BoundingBox> b = node_box(scene.sdf);
  if (!b) return std::nullopt;
  const double half_diagonal = 0.5 * glm::length(b->high - b->low);
  const double rounding = 1e-4 * (half_diagonal + glm::length(scene.camera.position - 0.5 * (b->low + b->high)));
  const double growth = b->gain * hit_growth(scene) + rounding;
  b->low -= growth;
  b->high += growth;
  return b;
}

RaySpan ray_box_span(const glm::dvec3& origin, const glm::dvec3& dir, const BoundingBox& box) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  RaySpan span{-kInfinity, kInfinity};
  for (int a = 0; a < 3; ++a) {
    const double low = box.low[a] - origin[a], high = box.high[a] - origin[a];
    if (dir[a] == 0.0) {
      if (low > 0.0 || high < 0.0) return {kInfinity, -kInfinity};
      continue;
    }
    const double t0 = low / dir[a], t1 = high / dir[a];
    span.t_enter = std::max(span.t_enter, std::min(t0, t1));
    span.t_exit = std::min(span.t_exit, std::max(t0, t1));
  }
  return span;
}

}  // namespace clmarch
