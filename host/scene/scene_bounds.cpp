// Bounding spheres of the SDF tree, node by node.
#include "scene/scene_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>

namespace clmarch {

BoundingSphere enclosing(const BoundingSphere& a, const BoundingSphere& b) {
  const double gain = std::max(a.gain, b.gain);
  const double distance = glm::length(b.center - a.center);
  if (distance + b.radius <= a.radius) return {a.center, a.radius, gain};
  if (distance + a.radius <= b.radius) return {b.center, b.radius, gain};
  const double radius = 0.5 * (distance + a.radius + b.radius);
  const glm::dvec3 center = a.center + (b.center - a.center) * ((radius - a.radius) / distance);
  return {center, radius, gain};
}

namespace {

/// A flat shape of these corners, thickened: about their mean, out to the farthest.
BoundingSphere corners_bounds(std::initializer_list<glm::dvec3> corners, double thickness) {
  glm::dvec3 center(0.0);
  for (const glm::dvec3& c : corners) center += c / static_cast<double>(corners.size());
  double radius = 0.0;
  for (const glm::dvec3& c : corners) radius = std::max(radius, glm::length(c - center));
  return {center, radius + thickness};
}

/// Each primitive's bounding sphere, written by hand for its kind (none: an unbounded one).
std::optional<BoundingSphere> primitive_bounds(const NodeParams& params) {
  struct Visitor {
    std::optional<BoundingSphere> operator()(const Sphere& s) const { return BoundingSphere{s.center, s.radius}; }
    std::optional<BoundingSphere> operator()(const Box& b) const {
      return BoundingSphere{b.center, glm::length(b.half_size)};
    }
    std::optional<BoundingSphere> operator()(const RoundBox& b) const {
      return BoundingSphere{b.center, glm::length(b.half_size)};
    }
    std::optional<BoundingSphere> operator()(const BoxFrame& b) const {
      return BoundingSphere{b.center, glm::length(b.half_size)};
    }
    std::optional<BoundingSphere> operator()(const Torus& t) const {
      return BoundingSphere{t.center, t.major_radius + t.minor_radius};
    }
    std::optional<BoundingSphere> operator()(const Plane&) const { return std::nullopt; }
    std::optional<BoundingSphere> operator()(const InfiniteCylinder&) const { return std::nullopt; }
    // Its vertices are the farthest points, size from the centre.
    std::optional<BoundingSphere> operator()(const Octahedron& o) const { return BoundingSphere{o.center, o.size}; }
    // Its corners are radius / cos 30 from the axis.
    std::optional<BoundingSphere> operator()(const HexPrism& h) const {
      return BoundingSphere{h.center, std::hypot(h.radius * 2.0 / std::sqrt(3.0), h.half_height)};
    }
    std::optional<BoundingSphere> operator()(const CappedCone& c) const {
      return BoundingSphere{c.center, std::hypot(std::max(c.bottom_radius, c.top_radius), c.half_height)};
    }
    // Quilez's bound falls short of the distance far away: with a_i = l_i / r_i, k0^2 / k1 =
    // sum a^2 / sqrt(sum a^2 / r^2) >= |l| / G by Kantorovich's inequality, G = (M^2 + m^2) / (2 M m)
    // for the largest and smallest semi-axes M, m; and k0 (k0 - 1) / k1 >= (|l| - M) / G as |l| / k0
    // <= M. So the field is below tau only within M + G tau of the centre.
    std::optional<BoundingSphere> operator()(const Ellipsoid& e) const {
      const double most = std::max({e.radii.x, e.radii.y, e.radii.z});
      const double least = std::min({e.radii.x, e.radii.y, e.radii.z});
      return BoundingSphere{e.center, most, (most * most + least * least) / (2.0 * most * least)};
    }
    // The smallest sphere through the apex and the rim, its centre on the axis within the cone.
    std::optional<BoundingSphere> operator()(const Cone& c) const {
      const double rim = c.height * std::tan(c.angle * std::numbers::pi / 180.0);
      const double below = std::min((rim * rim + c.height * c.height) / (2.0 * c.height), c.height);
      return BoundingSphere{c.center - glm::dvec3(0.0, below, 0.0), std::max(below, std::hypot(rim, c.height - below))};
    }
    std::optional<BoundingSphere> operator()(const RoundedCylinder& c) const {
      return BoundingSphere{c.center, std::hypot(c.radius, c.half_height)};
    }
    // The hull of two balls lies in any sphere holding both (the loader keeps either out of the other).
    std::optional<BoundingSphere> operator()(const RoundCone& c) const {
      const double length = glm::length(c.b - c.a);
      const double radius = 0.5 * (length + c.radius_a + c.radius_b);
      return BoundingSphere{c.a + (c.b - c.a) * ((radius - c.radius_a) / length), radius};
    }
    // About the axis' midpoint, the rims are the farthest points.
    std::optional<BoundingSphere> operator()(const CappedCylinder& c) const {
      return BoundingSphere{0.5 * (c.a + c.b), std::hypot(c.radius, 0.5 * glm::length(c.b - c.a))};
    }
    std::optional<BoundingSphere> operator()(const Frustum& f) const {
      return BoundingSphere{0.5 * (f.a + f.b),
                            std::hypot(std::max(f.radius_a, f.radius_b), 0.5 * glm::length(f.b - f.a))};
    }
    std::optional<BoundingSphere> operator()(const CappedTorus& t) const {
      return BoundingSphere{t.center, t.major_radius + t.minor_radius};
    }
    std::optional<BoundingSphere> operator()(const Link& l) const {
      return BoundingSphere{l.center, l.half_length + l.major_radius + l.minor_radius};
    }
    // Above the centre the cap lies within its rim's radius of the disc's centre.
    std::optional<BoundingSphere> operator()(const CutSphere& c) const {
      if (c.cut_height <= 0.0) return BoundingSphere{c.center, c.radius};
      return BoundingSphere{c.center + glm::dvec3(0.0, c.cut_height, 0.0),
                            std::sqrt(c.radius * c.radius - c.cut_height * c.cut_height)};
    }
    // The smallest sphere through the apex and the base's corners, its centre on the axis.
    std::optional<BoundingSphere> operator()(const Pyramid& p) const {
      const double corner = std::sqrt(2.0) * p.half_width;
      const double up = std::clamp((p.height * p.height - corner * corner) / (2.0 * p.height), 0.0, p.height);
      return BoundingSphere{p.center + glm::dvec3(0.0, up, 0.0), std::max(p.height - up, std::hypot(corner, up))};
    }
    std::optional<BoundingSphere> operator()(const Triangle& t) const {
      return corners_bounds({t.a, t.b, t.c}, t.thickness);
    }
    std::optional<BoundingSphere> operator()(const Quad& q) const {
      return corners_bounds({q.a, q.b, q.c, q.d}, q.thickness);
    }
    // The field is the largest of the face planes' distances: below tau it holds the prism grown
    // by tau on each face, whose triangle reaches radius + 2 tau and whose caps half_length + tau,
    // within |(radius, half_length)| + sqrt(5) tau of the centre.
    std::optional<BoundingSphere> operator()(const TriangularPrism& t) const {
      return BoundingSphere{t.center, std::hypot(t.radius, t.half_length), std::sqrt(5.0)};
    }
    std::optional<BoundingSphere> operator()(const SolidAngle& s) const { return BoundingSphere{s.center, s.radius}; }
    // Below the centre the bowl lies within its rim's radius of the rim's centre.
    std::optional<BoundingSphere> operator()(const CutHollowSphere& c) const {
      if (c.cut_height >= 0.0) return BoundingSphere{c.center, c.radius + c.thickness};
      const double rim = std::sqrt(c.radius * c.radius - c.cut_height * c.cut_height);
      return BoundingSphere{c.center + glm::dvec3(0.0, c.cut_height, 0.0), rim + c.thickness};
    }
    std::optional<BoundingSphere> operator()(const DeathStar& d) const { return BoundingSphere{d.center, d.radius}; }
    std::optional<BoundingSphere> operator()(const Rhombus& r) const {
      return BoundingSphere{r.center,
                            std::hypot(std::max(r.half_width, r.half_depth) + r.corner_radius, r.half_height)};
    }
    std::optional<BoundingSphere> operator()(const Capsule& c) const {
      return BoundingSphere{0.5 * (c.a + c.b), 0.5 * glm::length(c.b - c.a) + c.radius};
    }
    std::optional<BoundingSphere> operator()(const Cylinder& c) const {
      return BoundingSphere{c.center, std::hypot(c.radius, c.half_height)};
    }
    // The estimator is never below the distance to the ball that holds the whole set.
    std::optional<BoundingSphere> operator()(const Mandelbulb& m) const {
      return BoundingSphere{m.center, mandelbulb_radius(m.power)};
    }
    // The sponge is the cube with holes cut out: max(box, ...) >= the box's distance.
    std::optional<BoundingSphere> operator()(const Menger& m) const {
      return BoundingSphere{m.center, m.half_size * std::sqrt(3.0)};
    }
    // Every level lies in the first tetrahedron, and the estimate is never below the ball's distance.
    std::optional<BoundingSphere> operator()(const Sierpinski& s) const {
      return BoundingSphere{s.center, s.size * std::sqrt(3.0)};
    }
    // Both estimates are never below the distance to the ball that holds the set.
    std::optional<BoundingSphere> operator()(const Mandelbox& m) const {
      return BoundingSphere{m.center, mandelbox_half_size(m.scale) * std::sqrt(3.0)};
    }
    std::optional<BoundingSphere> operator()(const Julia& j) const {
      return BoundingSphere{j.center, julia_radius(j.c)};
    }
    std::optional<BoundingSphere> operator()(const Terrain&) const { return std::nullopt; }
    // User code is bounded where its scene file says so (`bounds:`), else nowhere.
    std::optional<BoundingSphere> operator()(const Glsl& g) const {
      if (!g.program->bounds_center) return std::nullopt;
      return BoundingSphere{*g.program->bounds_center, g.program->bounds_radius};
    }
    // A profile alone is a prism along z without end; revolve and extrude bound its section
    // (section_bounds).
#define CLMARCH_PROFILE(Kind, name, quality, cost, params_list) \
  std::optional<BoundingSphere> operator()(const Kind&) const { return std::nullopt; }
    // Operators have operator_bounds instead.
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) \
  std::optional<BoundingSphere> operator()(const Kind&) const { return std::nullopt; }
#include "scene/node_kinds.def"
  };
  return std::visit(Visitor{}, params);
}

}  // namespace

BoundingSphere turned_bounds(const BoundingSphere& child, int axis) {
  glm::dvec3 center(0.0);
  center[axis] = child.center[axis];
  return BoundingSphere{center, std::hypot(turn_reach(child, axis), child.radius), 1.0};
}

double turn_reach(const BoundingSphere& child, int axis) {
  glm::dvec3 across = child.center;
  across[axis] = 0.0;
  return glm::length(across) + child.radius;
}

namespace {

/// The disc in the xy plane that holds a profile (as a sphere centred in that plane).
std::optional<BoundingSphere> profile_disc(const NodeParams& params) {
  struct Visitor {
    std::optional<BoundingSphere> operator()(const Circle& c) const { return BoundingSphere{c.center, c.radius}; }
    std::optional<BoundingSphere> operator()(const Rectangle& r) const {
      return BoundingSphere{r.center, std::hypot(r.half_width, r.half_height)};
    }
    std::optional<BoundingSphere> operator()(const RoundedRectangle& r) const {
      return BoundingSphere{r.center, std::hypot(r.half_width, r.half_height)};
    }
    std::optional<BoundingSphere> operator()(const Segment& s) const {
      return BoundingSphere{0.5 * (s.a + s.b), 0.5 * glm::length(glm::dvec2(s.b - s.a)) + s.radius};
    }
    std::optional<BoundingSphere> operator()(const RegularPolygon& r) const {
      return BoundingSphere{r.center, r.radius};
    }
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) \
  std::optional<BoundingSphere> operator()(const Kind&) const { return std::nullopt; }
#define CLMARCH_PROFILE(Kind, name, quality, cost, params_list)
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) \
  std::optional<BoundingSphere> operator()(const Kind&) const { return std::nullopt; }
#include "scene/node_kinds.def"
  };
  std::optional<BoundingSphere> disc = std::visit(Visitor{}, params);
  if (disc) disc->center.z = 0.0;
  return disc;
}

/// Where the child's section at z = 0 (what revolve and extrude take of it) has its field below a
/// threshold: a profile's disc, placed by its transform when that keeps the xy plane (a turn
/// about z; a shift along z changes no profile), or the child's bounding sphere.
std::optional<BoundingSphere> section_bounds(const Node& child) {
  if (!is_profile(child.kind)) return node_bounds(child);
  const Transform& t = child.transform;
  if (t.rotate_degrees.x != 0.0 || t.rotate_degrees.y != 0.0) return std::nullopt;
  std::optional<BoundingSphere> b = profile_disc(child.params);
  if (!b) return std::nullopt;
  b->center = t.translate + t.world_from_local_rotation() * (t.scale * b->center);
  b->center.z = 0.0;
  b->radius *= t.scale;
  b->gain /= child.step_factor;
  return b;
}

/// The sphere holding every child's; nothing if one is unbounded.
std::optional<BoundingSphere> enclosing_children(const Node& node) {
  std::optional<BoundingSphere> all;
  for (const Node& child : node.children) {
    const std::optional<BoundingSphere> b = node_bounds(child);
    if (!b) return std::nullopt;
    all = all ? enclosing(*all, *b) : *b;
  }
  return all;
}

/// The smallest bounded child's sphere: an intersection lies inside every operand.
std::optional<BoundingSphere> smallest_child(const Node& node) {
  std::optional<BoundingSphere> best;
  for (const Node& child : node.children) {
    const std::optional<BoundingSphere> b = node_bounds(child);
    if (b && (!best || b->radius < best->radius)) best = b;
  }
  return best;
}

/// The node's sphere grown by growth (in its field's units, so times its gain).
std::optional<BoundingSphere> node_bounds_grown(const Node& node, double growth) {
  std::optional<BoundingSphere> b = node_bounds(node);
  if (b) b->radius += b->gain * growth;
  return b;
}

/// How far one fold of a union blend can put its surface outside its operands' union: where the
/// field is below tau >= 0, min(a, b) < tau + growth. Chamfer: (a + b - r) / sqrt 2 < tau gives
/// min(a, b) <= (a + b) / 2 < r / 2 + tau / sqrt 2 (reached at a = b = r / 2, the bevel's middle).
/// Round: r - |(r - a, r - b)| < tau with m = min(a, b) < r gives sqrt 2 (r - m) > r - tau, so
/// m < r (1 - 1 / sqrt 2) + tau / sqrt 2 (the fillet's middle). Stairs: their field is at least
/// (a + b - r) / 2, so m < r / 2 + tau (the corners lie on a + b = r). Columns: at least
/// (a + b - r) / sqrt 2 (the columns reach the line a + b = r), so as the chamfer. Xor is never
/// below min(a, b). For tau < 0 (deep inside) the chamfer, round and columns fall faster than
/// min(a, b) (they are estimates), which these spheres do not cover.
double union_blend_growth(const Node& node) {
  switch (node.kind) {
    case NodeKind::UnionChamfer:
      return params_of<UnionChamfer>(node).radius / 2.0;
    case NodeKind::UnionRound:
      return params_of<UnionRound>(node).radius * (1.0 - std::sqrt(0.5));
    case NodeKind::UnionStairs:
      return params_of<UnionStairs>(node).radius / 2.0;
    case NodeKind::UnionColumns:
      return params_of<UnionColumns>(node).radius / 2.0;
    case NodeKind::IntersectionChamfer:
    case NodeKind::DifferenceChamfer:
    case NodeKind::IntersectionRound:
    case NodeKind::DifferenceRound:
    case NodeKind::IntersectionStairs:
    case NodeKind::DifferenceStairs:
    case NodeKind::IntersectionColumns:
    case NodeKind::DifferenceColumns:
    case NodeKind::Xor:
    case NodeKind::Pipe:
    case NodeKind::Engrave:
    case NodeKind::Groove:
    case NodeKind::Tongue:
      // Every kind that is not a blend.
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) case NodeKind::Kind:
#define CLMARCH_BLEND(Kind, name, min_children, params_list)
#include "scene/node_kinds.def"
      return 0.0;
  }
  return 0.0;
}

/// The blends' spheres. Folded over n children, a union blend's growth adds up n - 1 times: each
/// fold's left operand may itself lie growth outside the one before. Intersections and differences
/// are never below max(a, b) or a (they only remove): as the hard ones. The pipe is never below
/// max(|a|, |b|) - r, so inside each operand grown by r per fold it follows; the tongue never below
/// a - ra; engrave and groove never below a.
std::optional<BoundingSphere> blend_bounds(const Node& node) {
  const double folds = static_cast<double>(node.children.size() - 1);
  switch (node.kind) {
    case NodeKind::UnionChamfer:
    case NodeKind::UnionRound:
    case NodeKind::UnionStairs:
    case NodeKind::UnionColumns:
    case NodeKind::Xor: {
      std::optional<BoundingSphere> all = enclosing_children(node);
      if (all) all->radius += all->gain * folds * union_blend_growth(node);
      return all;
    }
    case NodeKind::IntersectionChamfer:
    case NodeKind::IntersectionRound:
    case NodeKind::IntersectionStairs:
    case NodeKind::IntersectionColumns:
      return smallest_child(node);
    case NodeKind::DifferenceChamfer:
    case NodeKind::DifferenceRound:
    case NodeKind::DifferenceStairs:
    case NodeKind::DifferenceColumns:
    case NodeKind::Engrave:
    case NodeKind::Groove:
      return node_bounds(node.children.front());
    case NodeKind::Tongue:
      return node_bounds_grown(node.children.front(), folds * params_of<Tongue>(node).ra);
    case NodeKind::Pipe: {
      // The last child within r, the left operand within r, so the child before within 2 r, ...;
      // the first two children within folds * r.
      const double r = params_of<Pipe>(node).radius;
      std::optional<BoundingSphere> best;
      for (std::size_t i = 0; i < node.children.size(); ++i) {
        const double steps = folds - static_cast<double>(std::max<std::size_t>(i, 1)) + 1.0;
        const std::optional<BoundingSphere> b = node_bounds_grown(node.children[i], steps * r);
        if (b && (!best || b->radius < best->radius)) best = b;
      }
      return best;
    }
    // Every kind that is not a blend.
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) case NodeKind::Kind:
#define CLMARCH_BLEND(Kind, name, min_children, params_list)
#include "scene/node_kinds.def"
      return std::nullopt;
  }
  return std::nullopt;
}

std::optional<BoundingSphere> operator_bounds(const Node& node) {
  switch (node.kind) {
    case NodeKind::Repeat:
      return std::nullopt;
    case NodeKind::Displace: {
      // (d + displacement) / L < tau needs d < L tau + amplitude, and the child's field is below
      // that within radius + gain (L tau + amplitude): the amplitude counts with the child's gain.
      std::optional<BoundingSphere> child = node_bounds(node.children.front());
      if (!child) return std::nullopt;
      child->radius += child->gain * params_of<Displace>(node).amplitude;
      child->gain *= displacement_lipschitz(node);
      return child;
    }
    case NodeKind::Union:
    case NodeKind::SmoothUnion:
      return enclosing_children(node);
    case NodeKind::Intersection:
    case NodeKind::SmoothIntersection:
      return smallest_child(node);
    case NodeKind::Subtraction:
    case NodeKind::SmoothSubtraction:
      return node_bounds(node.children.front());
    case NodeKind::Elongate: {
      // p = q + clamp(p, -h, h) with q in the child's sphere: within |h| more of its centre.
      std::optional<BoundingSphere> child = node_bounds(node.children.front());
      if (child) child->radius += glm::length(params_of<Elongate>(node).h);
      return child;
    }
    case NodeKind::Onion:
    case NodeKind::Round: {
      // d' < tau needs d < tau + amount: the child's sphere grown by its gain times amount.
      std::optional<BoundingSphere> child = node_bounds(node.children.front());
      const double amount =
          node.kind == NodeKind::Onion ? params_of<Onion>(node).thickness : params_of<Round>(node).radius;
      if (child) child->radius += child->gain * amount;
      return child;
    }
    case NodeKind::Mirror: {
      // The child's sphere and its mirror images: about the centre moved onto the mirror planes.
      std::optional<BoundingSphere> child = node_bounds(node.children.front());
      if (!child) return std::nullopt;
      const glm::bvec3& axes = params_of<Mirror>(node).axes;
      glm::dvec3 center = child->center;
      for (int a = 0; a < 3; ++a) {
        if (axes[a]) center[a] = 0.0;
      }
      child->radius += glm::length(child->center - center);
      child->center = center;
      return child;
    }
    case NodeKind::RepeatPolar: {
      // Every copy's sphere is as far from the y axis as the child's, at the child's height.
      std::optional<BoundingSphere> child = node_bounds(node.children.front());
      if (!child) return std::nullopt;
      child->radius += std::hypot(child->center.x, child->center.z);
      child->center = {0.0, child->center.y, 0.0};
      return child;
    }
    case NodeKind::RepeatLimited: {
      // The copies' centres span period * [min, max] on each repeated axis.
      std::optional<BoundingSphere> child = node_bounds(node.children.front());
      if (!child) return std::nullopt;
      const RepeatLimited& repeat = params_of<RepeatLimited>(node);
      glm::dvec3 half_span(0.0);
      for (int a = 0; a < 3; ++a) {
        if (!(repeat.period[a] > 0.0)) continue;
        child->center[a] += repeat.period[a] * 0.5 * (repeat.min[a] + repeat.max[a]);
        half_span[a] = repeat.period[a] * 0.5 * (repeat.max[a] - repeat.min[a]);
      }
      child->radius += glm::length(half_span);
      return child;
    }
    case NodeKind::Revolve: {
      // The child's section at z = 0 lies in its sphere: profile x' = length(p.xz) - offset within
      // r of c.x, y within r of c.y. (d < tau puts (x', y) within r + gain tau of (c.x, c.y), so
      // the point within sqrt(2) gain tau more of the sphere's.)
      const std::optional<BoundingSphere> child = section_bounds(node.children.front());
      if (!child) return std::nullopt;
      const double reach = std::abs(child->center.x + params_of<Revolve>(node).offset) + child->radius;
      return BoundingSphere{
          {0.0, child->center.y, 0.0}, std::hypot(reach, child->radius), std::sqrt(2.0) * child->gain};
    }
    case NodeKind::Extrude: {
      // The section's disc, extruded to |z| <= half_length (d < tau: the section's field and
      // |z| - half_length are both below tau).
      const std::optional<BoundingSphere> child = section_bounds(node.children.front());
      if (!child) return std::nullopt;
      return BoundingSphere{{child->center.x, child->center.y, 0.0},
                            std::hypot(child->radius, params_of<Extrude>(node).half_length),
                            std::sqrt(2.0) * std::max(child->gain, 1.0)};
    }
    case NodeKind::Twist:
    case NodeKind::Bend: {
      // Both turn points about an axis (y, z), keeping their distance from it and their height
      // along it: the child's surface stays in the cylinder round its sphere. Their fields are never
      // below the distance to this sphere (the code generator and the reference take the larger of the
      // two), so its gain is 1.
      const std::optional<BoundingSphere> child = node_bounds(node.children.front());
      if (!child) return std::nullopt;
      return turned_bounds(*child, node.kind == NodeKind::Twist ? 1 : 2);
    }
    case NodeKind::NonuniformScale: {
      // p = factors q: the sphere stretched by the largest factor; the field scaled by the smallest.
      std::optional<BoundingSphere> child = node_bounds(node.children.front());
      if (!child) return std::nullopt;
      const glm::dvec3& f = params_of<NonuniformScale>(node).factors;
      const double largest = std::max({f.x, f.y, f.z}), smallest = std::min({f.x, f.y, f.z});
      return BoundingSphere{child->center * f, child->radius * largest, child->gain * largest / smallest};
    }
#define CLMARCH_BLEND(Kind, name, min_children, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
      return blend_bounds(node);
      // Primitives have primitive_bounds instead.
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

std::optional<BoundingSphere> local_bounds(const Node& node) {
  std::optional<BoundingSphere> b = is_primitive(node.kind) ? primitive_bounds(node.params) : operator_bounds(node);
  if (!b) return std::nullopt;
  // The polynomial smooth minimum and maximum undershoot the hard ones by at most k / 4 a fold:
  // (n - 1) k / 4 over n children.
  if (is_smooth_operator(node.kind)) {
    b->radius += b->gain * smooth_k(node) / 4.0 * static_cast<double>(node.children.size() - 1);
  }
  return b;
}

std::optional<BoundingSphere> node_bounds(const Node& node) {
  std::optional<BoundingSphere> b = local_bounds(node);
  if (!b) return std::nullopt;
  // p_parent = translate + R (scale p_local); the field is scale * f(p_local) * step_factor.
  b->center =
      node.transform.translate + node.transform.world_from_local_rotation() * (node.transform.scale * b->center);
  b->radius *= node.transform.scale;
  b->gain /= node.step_factor;
  return b;
}

double hit_growth(const Scene& scene) {
  // The largest hit threshold along a camera ray, which ends at max_distance.
  const double threshold =
      std::max(scene.render.epsilon, hit_cone_slope(scene.render, scene.camera) * scene.render.max_distance);
  const double glow = scene.shading.glow ? scene.shading.glow->radius : 0.0;
  return threshold + glow;
}

namespace {

// b grown by hit_growth and a margin for float rounding: outside it the field exceeds all of them.
BoundingSphere grown_for_hits(const Scene& scene, BoundingSphere b, const glm::dvec3& origin) {
  const double rounding = 1e-4 * (b.radius + glm::length(origin - b.center));
  b.radius += b.gain * hit_growth(scene) + rounding;
  return b;
}

}  // namespace

std::optional<BoundingSphere> camera_ray_bounds(const Scene& scene) {
  if (scene.render.bounds == RayBounds::None || scene.tiling) return std::nullopt;
  const std::optional<BoundingSphere> b = node_bounds(scene.sdf);
  if (!b) return std::nullopt;
  return grown_for_hits(scene, *b, scene.camera.position);
}

std::optional<BoundingSphere> cell_bounds(const Scene& scene) {
  if (scene.render.bounds == RayBounds::None || !uses_cells_tiling(scene)) return std::nullopt;
  const std::optional<BoundingSphere> b = node_bounds(scene.sdf);
  if (!b) return std::nullopt;
  // The rays march in the cell's frame: the rounding margin is the cell's size, not the camera's distance.
  return grown_for_hits(scene, *b, scene.tiling->cell);
}

bool uses_cone_pass(const Scene& scene) {
  if (uses_cells_tiling(scene)) return false;
  if (scene.render.coarse_pass != CoarsePass::Auto) return scene.render.coarse_pass == CoarsePass::Cone;
  // Rays clipped to a bounding sphere start next to their object already; the pass shortens the
  // step counts that step-count occlusion shades by.
  return !camera_ray_bounds(scene) && scene.shading.step_ao == 0.0;
}

RenderSettings resolved_render_settings(const Scene& scene) {
  RenderSettings render = scene.render;
  render.coarse_pass = uses_cone_pass(scene) ? CoarsePass::Cone : CoarsePass::None;
  render.over_relaxation = camera_over_relaxation(scene);
  return render;
}

std::optional<RaySpan> ray_sphere_span(const glm::dvec3& origin, const glm::dvec3& dir, const BoundingSphere& sphere) {
  const glm::dvec3 offset = origin - sphere.center;
  const double b = glm::dot(offset, dir);
  // b^2 - c computed as r^2 - |offset - b dir|^2, which keeps its precision far from the sphere.
  const glm::dvec3 closest = offset - b * dir;
  const double h = sphere.radius * sphere.radius - glm::dot(closest, closest);
  if (h < 0.0) return std::nullopt;
  const double root = std::sqrt(h);
  return RaySpan{-b - root, -b + root};
}

}  // namespace clmarch
