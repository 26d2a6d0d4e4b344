// The blend operators in double, each from the shape it draws in the plane of the operands'
// distances (a, b): the union's corner is the quadrant a, b > 0.
#include "reference/reference_blends.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace clmarch {
namespace {

const double kSqrtHalf = std::sqrt(0.5);

/// The distance to the half plane a + b <= c.
double below_diagonal(double a, double b, double c) { return (a + b - c) * kSqrtHalf; }

double union_chamfer(double a, double b, double r) { return std::min({a, b, below_diagonal(a, b, r)}); }
double intersection_chamfer(double a, double b, double r) { return std::max({a, b, -below_diagonal(-a, -b, r)}); }

/// The fillet: the circle of radius r centred at (r, r), where both operands are nearer than r.
double union_round(double a, double b, double r) {
  if (a < r && b < r) return r - std::hypot(r - a, r - b);
  return std::min(a, b);
}
/// The circle centred at (-r, -r), where both operands are above -r.
double intersection_round(double a, double b, double r) {
  if (a > -r && b > -r) return std::hypot(a + r, b + r) - r;
  return std::max(a, b);
}

/// The steps: for each step j the quadrant below its outer corner ((j + 1/2) s, r - (j + 1/2) s),
/// s = r / steps, measured as max(a - corner.a, b - corner.b); with a and b, the nearest.
double union_stairs(double a, double b, double r, int steps) {
  const double s = r / steps;
  double d = std::min(a, b);
  for (int j = 0; j < steps; ++j) {
    const double corner = (j + 0.5) * s;
    d = std::min(d, std::max(a - corner, b - (r - corner)));
  }
  return d;
}

/// The columns: steps disks of radius c tangent to each other, to a = 0 and b = 0 at the ends, and
/// to the line a + b = r, with the triangle behind their centres' line a + b = r - sqrt 2 c filled.
/// Their centres step by 2 c along the direction (1, -1) / sqrt 2.
double union_columns(double a, double b, double r, int steps) {
  const double c = r / (std::sqrt(2.0) * (steps + std::sqrt(2.0)));
  double d = std::min({a, b, below_diagonal(a, b, r - std::sqrt(2.0) * c)});
  // The first centre touches b = 0 (its b is c), on the centres' line.
  const double first_b = c;
  const double first_a = r - std::sqrt(2.0) * c - first_b;
  for (int k = 0; k < steps; ++k) {
    const double shift = 2.0 * c * k * kSqrtHalf;
    d = std::min(d, std::hypot(a - (first_a - shift), b - (first_b + shift)) - c);
  }
  return d;
}

/// The blend's parameter of this key (radius, steps, ra, rb), found through its declaration.
double param(const Node& node, std::string_view key) {
  std::optional<double> found;
  std::visit(
      [&](const auto& params) {
        for_each_param(params, [&](const ParamSpec& spec, const auto& value) {
          if constexpr (std::is_arithmetic_v<std::decay_t<decltype(value)>>) {
            if (key == spec.key) found = static_cast<double>(value);
          }
        });
      },
      node.params);
  if (!found)
    throw std::logic_error("reference_blends: " + std::string(node_kind_name(node.kind)) + " has no " +
                           std::string(key));
  return *found;
}

double radius(const Node& node) { return param(node, "radius"); }
int steps(const Node& node) { return static_cast<int>(param(node, "steps")); }

double engrave_cut(double a, double b, double r) { return (a + r - std::abs(b)) * kSqrtHalf; }
double groove_cut(double a, double b, double ra, double rb) { return std::min(a + ra, rb - std::abs(b)); }
double tongue_part(double a, double b, double ra, double rb) { return std::max(a - ra, std::abs(b) - rb); }

}  // namespace

double blend_distance(const Node& node, double a, double b) {
  switch (node.kind) {
    case NodeKind::UnionChamfer:
      return union_chamfer(a, b, radius(node));
    case NodeKind::IntersectionChamfer:
      return intersection_chamfer(a, b, radius(node));
    case NodeKind::DifferenceChamfer:
      return intersection_chamfer(a, -b, radius(node));
    case NodeKind::UnionRound:
      return union_round(a, b, radius(node));
    case NodeKind::IntersectionRound:
      return intersection_round(a, b, radius(node));
    case NodeKind::DifferenceRound:
      return intersection_round(a, -b, radius(node));
    case NodeKind::UnionStairs:
      return union_stairs(a, b, radius(node), steps(node));
    case NodeKind::IntersectionStairs:
      return -union_stairs(-a, -b, radius(node), steps(node));
    case NodeKind::DifferenceStairs:
      return -union_stairs(-a, b, radius(node), steps(node));
    case NodeKind::UnionColumns:
      return union_columns(a, b, radius(node), steps(node));
    case NodeKind::IntersectionColumns:
      return -union_columns(-a, -b, radius(node), steps(node));
    case NodeKind::DifferenceColumns:
      return -union_columns(-a, b, radius(node), steps(node));
    case NodeKind::Xor:
      return std::max(std::min(a, b), -std::max(a, b));
    case NodeKind::Pipe:
      return std::hypot(a, b) - radius(node);
    case NodeKind::Engrave:
      return std::max(a, engrave_cut(a, b, radius(node)));
    case NodeKind::Groove:
      return std::max(a, groove_cut(a, b, param(node, "ra"), param(node, "rb")));
    case NodeKind::Tongue:
      return std::min(a, tongue_part(a, b, param(node, "ra"), param(node, "rb")));
      // Every kind that is not a blend.
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) case NodeKind::Kind:
#define CLMARCH_BLEND(Kind, name, min_children, params_list)
#include "scene/node_kinds.def"
      break;
  }
  throw std::logic_error("blend_distance() of a kind that is not a blend");
}

SdfSample blend_sample(const Node& node, const SdfSample& a, const SdfSample& b) {
  const double da = a.distance, db = b.distance;
  bool first = true;
  switch (node.kind) {
    case NodeKind::UnionChamfer:
    case NodeKind::UnionRound:
    case NodeKind::UnionStairs:
    case NodeKind::UnionColumns:
      first = !(db < da);
      break;
    case NodeKind::IntersectionChamfer:
    case NodeKind::IntersectionRound:
    case NodeKind::IntersectionStairs:
    case NodeKind::IntersectionColumns:
      first = !(db > da);
      break;
    case NodeKind::DifferenceChamfer:
    case NodeKind::DifferenceRound:
    case NodeKind::DifferenceStairs:
    case NodeKind::DifferenceColumns:
      first = da >= -db;
      break;
    case NodeKind::Xor:
    case NodeKind::Pipe:
      first = std::abs(da) <= std::abs(db);
      break;
    case NodeKind::Engrave:
      first = da >= engrave_cut(da, db, radius(node));
      break;
    case NodeKind::Groove:
      first = da >= groove_cut(da, db, param(node, "ra"), param(node, "rb"));
      break;
    case NodeKind::Tongue:
      first = da <= tongue_part(da, db, param(node, "ra"), param(node, "rb"));
      break;
      // Every kind that is not a blend.
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) case NodeKind::Kind:
#define CLMARCH_BLEND(Kind, name, min_children, params_list)
#include "scene/node_kinds.def"
      throw std::logic_error("blend_sample() of a kind that is not a blend");
  }
  SdfSample out = first ? a : b;
  out.distance = blend_distance(node, da, db);
  return out;
}

}  // namespace clmarch
