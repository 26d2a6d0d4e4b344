// Scenes of every node kind from its declaration (kind_scenes.hpp).
#include "support/kind_scenes.hpp"

#include "support/test_support.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <type_traits>

namespace clmarch::testing {
namespace {

/// A value for a required parameter, from its kind of value and range: what a scene would give.
std::string required_value(const ParamSpec& spec, int integer_vectors_before) {
  switch (spec.type) {
    case ParamType::Scalar:
      // A twist's or bend's rate, in degrees a unit, wants more than 0.15.
      if (spec.range.contains(30.0) && spec.range.contains(-30.0)) return "30";
      if (spec.range.contains(0.15)) return "0.15";
      break;
    case ParamType::Integer:
      return spec.range.contains(3.0) ? "3" : fmt::format("{}", spec.range.low);
    case ParamType::Vector:
      return spec.range.contains(0.0) ? "[1.2, 0, 0]" : "[1.2, 0.8, 1]";
    // min before max, as repeat_limited declares them.
    case ParamType::IntegerVector:
      return integer_vectors_before == 0 ? "[-1, 0, 0]" : "[1, 0, 0]";
    case ParamType::Axes:
      return "[x, z]";
    case ParamType::Point:
    case ParamType::Direction:
    case ParamType::Choice:
    case ParamType::Vector4:
    case ParamType::Program:
      break;
  }
  throw std::logic_error(fmt::format("no value for a required parameter {}", spec.key));
}

/// Settings for kinds whose defaults the float render cannot follow closely enough to compare:
/// the Mandelbox's orbit at scale 2 multiplies float's rounding by up to 8 an iteration
/// (CheckFeatures.TheMandelboxAndTheJuliaSet compares scale 2 at 6 iterations). At scale -1.5 its
/// faces are dust finer than a pixel, which rays at a fixed epsilon pass through or not by
/// rounding; the pixel cone stops them at the dust's pixel-sized envelope.
std::string kind_settings(NodeKind kind) {
  if (kind == NodeKind::Mandelbox) return "scale: -1.5, ";
  // A rounded box in user code, with a helper function, bounded by the sphere about its corners.
  if (kind == NodeKind::Glsl) {
    return "code: 'float box(vec3 p, vec3 b) { vec3 q = abs(p) - b; return length(max(q, 0.0)) + "
           "min(max(q.x, max(q.y, q.z)), 0.0); } float map(vec3 p) { return box(p, vec3(0.5, 0.4, 0.3)) - 0.1; }', "
           "bounds: {radius: 0.9}, ";
  }
  return "";
}

}  // namespace

std::string kind_render_settings(NodeKind kind) {
  return kind == NodeKind::Mandelbox ? "hit_threshold: pixel_cone, " : "";
}

std::string kind_node(NodeKind kind, const glm::dvec3& offset) {
  const std::string name(node_kind_name(kind));
  std::string params = kind_settings(kind);
  bool has_points = false;
  int integer_vectors = 0;
  for (const ParamSpec& spec : param_table(kind)) {
    if (!spec.required) continue;
    params += fmt::format("{}: {}, ", spec.key, required_value(spec, integer_vectors));
    if (spec.type == ParamType::IntegerVector) ++integer_vectors;
  }
  if (is_primitive(kind)) {
    const Scene local = scene_from_yaml(fmt::format("sdf:\n  {}: {{{}}}\n", name, params));
    std::visit(
        [&](const auto& values) {
          for_each_param(values, [&](const ParamSpec& spec, const auto& value) {
            if constexpr (std::is_same_v<std::decay_t<decltype(value)>, glm::dvec3>) {
              if (spec.type != ParamType::Point) return;
              const glm::dvec3 moved = value + offset;
              params += fmt::format("{}: [{}, {}, {}], ", spec.key, moved.x, moved.y, moved.z);
              has_points = true;
            }
          });
        },
        local.sdf.params);
  } else {
    const std::string children = max_children(kind) == 1
                                     ? "[{box: {half_size: [0.45, 0.35, 0.4]}}]"
                                     : "[{sphere: {center: [-0.35, 0, 0], radius: 0.6}}, "
                                       "{box: {center: [0.35, 0.15, 0.1], half_size: [0.45, 0.45, 0.45]}}]";
    params += "children: " + children + ", ";
  }
  if (!has_points) params += fmt::format("translate: [{}, {}, {}], ", offset.x, offset.y, offset.z);
  return fmt::format("{}: {{{}}}", name, params.substr(0, params.size() - 2));
}

}  // namespace clmarch::testing
