// CPU reference of the distance field: evaluates the scene IR's node tree directly in double.
// Deliberately shares no code with kernels/, so the two can be compared pixel by pixel; the
// formulas are Inigo Quilez's, and each says whether it returns an exact distance or a bound.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

namespace clmarch {

/// The field at a point: signed distance and the material of the surface there.
struct SdfSample {
  double distance = 0.0;
  glm::dvec3 color;
  /// metallic, roughness, reflectivity (defaults of Material until the tree walk sets them).
  glm::dvec3 surface{0.0, 0.5, 0.0};
  /// The primitive whose material it is (its number in the subtree, primitive_count's order): the
  /// color rules' operand, or the heavier one of a smooth blend (the first at weight 1/2).
  int primitive = 0;
  /// Phong and Blinn-Phong's specular weight and shininess, and the light emitted, blended like color.
  glm::dvec2 finish{0.0, 32.0};
  glm::dvec3 emission{0.0};
};

/// Signed distance of the whole tree at the world point p (throws std::invalid_argument on a
/// malformed tree: operator without children, a blend radius k <= 0, parameters of the wrong kind).
double reference_distance(const Node& root, const glm::dvec3& p);
/// Distance and albedo at p, and the primitive they are of; colors follow the rules of op_union
/// and friends below.
SdfSample reference_sample(const Node& root, const glm::dvec3& p, const Material& root_material = Material{});

// Primitives, p in the primitive's local frame: sd_<name>(p, parameters) for each primitive of
// scene/node_kinds.def, which says whether it is exact.
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) \
  double sd_##name(const glm::dvec3& p, const Kind& params);
#include "scene/node_kinds.def"

// Operators on distances. Union of exact distances is exact outside and a bound inside;
// intersection, subtraction and the smooth operators return bounds.

/// min(a, b).
double op_union(double a, double b);
/// max(a, b).
double op_intersection(double a, double b);
/// a minus b: max(a, -b).
double op_subtraction(double a, double b);
/// Polynomial smooth minimum with blend radius k > 0.
double op_smooth_union(double a, double b, double k);
/// Polynomial smooth maximum with blend radius k > 0.
double op_smooth_intersection(double a, double b, double k);
/// Smooth a minus b with blend radius k > 0.
double op_smooth_subtraction(double a, double b, double k);

// The same operators on samples: same distance, plus the color rule of the scene format.

/// Color of the nearer operand (the first on a tie).
SdfSample op_union(const SdfSample& a, const SdfSample& b);
/// Color of the farther operand (the first on a tie).
SdfSample op_intersection(const SdfSample& a, const SdfSample& b);
/// Color of a where a >= -b, else of b.
SdfSample op_subtraction(const SdfSample& a, const SdfSample& b);
/// Color mix(b, a, h) with the blend weight h of the distance.
SdfSample op_smooth_union(const SdfSample& a, const SdfSample& b, double k);
/// Color mix(b, a, h) with the blend weight h of the distance.
SdfSample op_smooth_intersection(const SdfSample& a, const SdfSample& b, double k);
/// Color mix(a, b, h) with the blend weight h of the distance.
SdfSample op_smooth_subtraction(const SdfSample& a, const SdfSample& b, double k);

}  // namespace clmarch
