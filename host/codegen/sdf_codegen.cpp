// Code generation of the scene's distance function: one statement per node, in SSA temporaries,
// so that the dumped kernel reads as the tree it came from.
#include "codegen/sdf_codegen.hpp"

#include "codegen/blend_code.hpp"
#include "codegen/color_pattern_code.hpp"
#include "codegen/glsl_code.hpp"

#include "codegen/cl_literals.hpp"
#include "codegen/embedded_kernels.hpp"
#include "common/available_memory.hpp"
#include "common/errors.hpp"
#include "device_types.h"
#include "prune/operand_grid.hpp"
#include "prune/operand_groups.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/tiling_model.hpp"

#include <fmt/format.h>

#include <glm/gtc/matrix_access.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace clmarch {
namespace {

/// A material's surface vector as map_color returns it: the shading model's two numbers (PBR:
/// metallic, roughness; the others: specular, shininess), then reflectivity.
glm::dvec3 surface_vector(const Material& m, ShadingModel model) {
  return model == ShadingModel::Pbr ? glm::dvec3(m.metallic, m.roughness, m.reflectivity)
                                    : glm::dvec3(m.specular, m.shininess, m.reflectivity);
}

/// A parameter as an argument of its sd_ function. Positions are baked relative to offset, in
/// double, so p stays small where the camera is far from the origin (map_frame_origin).
std::string argument(const ParamSpec& spec, const glm::dvec3& value, const glm::dvec3& offset, Literals& lit) {
  return lit.f4(spec.type == ParamType::Point ? value - offset : value);
}
std::string argument(const ParamSpec&, const glm::dvec4& value, const glm::dvec3&, Literals& lit) {
  return lit.f4(value);
}
std::string argument(const ParamSpec&, double value, const glm::dvec3&, Literals& lit) { return lit.f(value); }
std::string argument(const ParamSpec&, int value, const glm::dvec3&, Literals&) { return std::to_string(value); }
std::string argument(const ParamSpec&, std::uint32_t value, const glm::dvec3&, Literals&) {
  return fmt::format("{}u", value);
}

/// sd_<name>(p, parameters...) at the point p + offset, the arguments in the order of the kind's
/// declaration (scene/node_kinds.def). A choice is not an argument: it selects the function
/// sd_<name>_<choice>.
template <class Params>
std::string declared_call(std::string_view name, const Params& params, const std::string& p, const glm::dvec3& offset,
                          Literals& lit) {
  std::string function = fmt::format("sd_{}", name);
  std::string arguments = p;
  for_each_param(params, [&](const ParamSpec& spec, const auto& value) {
    using Value = std::decay_t<decltype(value)>;
    if constexpr (std::is_enum_v<Value>) {
      function += fmt::format("_{}", spec.choices[static_cast<std::size_t>(value)]);
    } else if constexpr (std::is_same_v<Value, std::shared_ptr<const GlslProgram>>) {
      throw std::logic_error("a glsl node's call is glsl_call's, not a declared one");
    } else {
      arguments += ", " + argument(spec, value, offset, lit);
    }
  });
  return fmt::format("{}({})", function, arguments);
}

/// The call of a primitive at the point p + offset: its declared call, but for the kinds whose
/// call is written here.
std::string primitive_call(const Node& node, const std::string& p, const glm::dvec3& offset, Literals& lit) {
  const std::string_view name = node_kind_name(node.kind);
  if (const Plane* plane = std::get_if<Plane>(&node.params)) {
    // dot(n, p + offset) + c = dot(n, p) + (c + dot(n, offset))
    return fmt::format("sd_plane({}, {}, {})", p, lit.f4(plane->normal),
                       lit.f(plane->offset + glm::dot(plane->normal, offset)));
  }
  if (const Mandelbulb* bulb = std::get_if<Mandelbulb>(&node.params); bulb && bulb->power == 8.0) {
    // Power 8 has a form without transcendentals in the loop (kernels/fractals.cl).
    return fmt::format("sd_mandelbulb8({}, {}, {}, {})", p, lit.f4(bulb->center - offset), bulb->iterations,
                       lit.f(bulb->bailout));
  }
  return std::visit(
      [&](const auto& params) -> std::string {
        if constexpr (kIsPrimitiveParams<std::decay_t<decltype(params)>>) {
          return declared_call(name, params, p, offset, lit);
        } else {
          throw std::logic_error("primitive_call() of an operator");
        }
      },
      node.params);
}

/// The factor between a terrain's octaves' frequencies, as kernels/noise.cl steps them.
double terrain_lacunarity(const Terrain& terrain) { return terrain.noise == TerrainNoise::Derivative ? 2.75 : 2.0; }

/// A rough cost of evaluating a subtree, in sphere evaluations: what decides whether a bounding
/// sphere (about one sphere evaluation and a branch) can pay for itself.
int subtree_cost(const Node& node) {
  if (is_primitive(node.kind)) return evaluation_cost(node);
  int cost = 0;
  for (const Node& child : node.children) cost += subtree_cost(child);
  return node.kind == NodeKind::Displace ? cost + 6 : std::max(2, cost + 1);
}

/// Subtrees from this cost on are gated behind their bounding sphere inside unions and subtractions.
constexpr int kGateCost = 8;

class SdfEmitter;

/// The one union evaluated from its operand grid (grid_union), and what emitting it produced:
/// the functions of its operands' shapes, and the data they and kernels/operand_grid.cl read.
struct GridEmission {
  const Node* node = nullptr;
  bool emitted = false;
  std::string functions;
  std::shared_ptr<const std::vector<float>> data;

  void emit(const Node& union_node, int first_id, const Material& color, const glm::dvec3& offset, bool gate_subtrees,
            const MaterialLayout& materials, Literals& lit);
};

/// The functions that blend an operator's operands' materials: select(second, first, mask), or
/// mix(second, first, weight) for the smooth operators.
struct BlendFunctions {
  const char* select;
  const char* mix;
};
inline constexpr BlendFunctions kColorBlend{"v3_select", "v3_mix"};
/// Numbers are not blended: a smooth operator's id is its heavier operand's (kernels/operators.cl).
inline constexpr BlendFunctions kIdBlend{"select", "id_mix"};

/// The primitive number (the id channel's) of each child's first primitive, children of a node
/// whose first is first.
std::vector<int> child_first_ids(const Node& node, int first) {
  std::vector<int> firsts;
  firsts.reserve(node.children.size());
  for (const Node& child : node.children) {
    firsts.push_back(first);
    first += primitive_count(child);
  }
  return firsts;
}

/// How an emitter numbers primitives for the id channel: not at all, or from a base, the number
/// of the first primitive of the tree it emits (empty: 0; an operand grid's record holds its own).
struct IdNumbering {
  bool on = false;
  std::string base;
};

/// Emits the statements of one function body; with_color also tracks the material (albedo or its
/// pattern, the surface vector of MaterialLayout, and the emission where the scene has any),
/// blended by the same rules as the albedo, and with ids the number of the primitive the material
/// is of.
class SdfEmitter {
 public:
  SdfEmitter(bool with_color, SubtreeGates gates, Literals& literals, GridEmission* grid = nullptr,
             IdNumbering ids = {}, MaterialLayout materials = {})
      : with_color_(with_color),
        gate_subtrees_(gates != SubtreeGates::None),
        group_places_(gates == SubtreeGates::SubtreesAndPlaces && !with_color),
        lit_(literals),
        grid_(grid),
        ids_(std::move(ids)),
        materials_(materials) {}

  struct Value {
    std::string distance;
    std::string color;     // empty without color
    std::string surface;   // empty without color
    std::string id;        // empty without ids
    std::string emission;  // empty without color or without the scene's emission
  };

  /// The node's value at the point p + offset (offset: a constant the generator folds into the
  /// node's positions in double).
  Value emit(const Node& node, const std::string& p, const Material& inherited, const glm::dvec3& offset) {
    // The node's first primitive number, which its operators' children change while they emit.
    const int first_id = first_id_;
    const Material color = node.material_over(inherited);
    const auto [local_p, local_offset] = emit_transform(node, p, offset);
    // A pattern is a function of the point in the frame of the node that sets it.
    const std::string outer_pattern_frame = pattern_frame_;
    if (with_color_ && node.color_pattern) set_pattern_frame(local_p, local_offset);
    Value value = is_primitive(node.kind) ? emit_primitive(node, local_p, color, local_offset)
                                          : emit_operator(node, local_p, color, local_offset);
    pattern_frame_ = outer_pattern_frame;
    if (node.transform.scale != 1.0) {
      // p was divided by the scale, so distances in the local frame are scaled back.
      const std::string scaled = fresh("d");
      line(fmt::format("vfloat {} = {} * {};", scaled, value.distance, lit_.f(node.transform.scale)));
      value.distance = scaled;
    }
    if (node.step_factor != 1.0) {
      // Shorter steps for fields steeper than 1 (terrain, fractals, deep smooth unions).
      const std::string bounded = fresh("d");
      line(fmt::format("vfloat {} = {} * {};  /* step_factor */", bounded, value.distance, lit_.f(node.step_factor)));
      value.distance = bounded;
    }
    first_id_ = first_id;
    return value;
  }

  std::string body() const { return body_; }

  /// Makes p + offset the point the patterns of the nodes below are evaluated at.
  void set_pattern_frame(const std::string& p, const glm::dvec3& offset) {
    if (offset == glm::dvec3(0.0)) {
      pattern_frame_ = p;
      return;
    }
    pattern_frame_ = fresh("q");
    line(fmt::format("vec3v {} = v3_add({}, v3_from({}));  /* the pattern's frame */", pattern_frame_, p,
                     lit_.f4(offset)));
  }

  /// The blend of the material of an operator's operands, as combine() writes it: {0} and {1} are
  /// the first and second operand's colors, a and b their distances, k the blend radius's mark (a
  /// blend's arguments, operator_arguments).
  static std::string blend_rule(NodeKind kind, const std::string& a, const std::string& b, const std::string& k,
                                const BlendFunctions& f = kColorBlend) {
    switch (kind) {
      case NodeKind::Union:
        return fmt::format("{}({}, {}, MASK({} <= {}))", f.select, "{1}", "{0}", a, b);
      case NodeKind::Intersection:
        return fmt::format("{}({}, {}, MASK({} >= {}))", f.select, "{1}", "{0}", a, b);
      case NodeKind::Subtraction:
        return fmt::format("{}({}, {}, MASK({} >= -{}))", f.select, "{1}", "{0}", a, b);
      case NodeKind::SmoothUnion:
        return fmt::format("{}({}, {}, smooth_union_blend({}, {}, {}))", f.mix, "{1}", "{0}", a, b, k);
      case NodeKind::SmoothIntersection:
        return fmt::format("{}({}, {}, smooth_intersection_blend({}, {}, {}))", f.mix, "{1}", "{0}", a, b, k);
      case NodeKind::SmoothSubtraction:
        return fmt::format("{}({}, {}, smooth_subtraction_blend({}, {}, {}))", f.mix, "{0}", "{1}", a, b, k);
#define CLMARCH_BLEND(Kind, name, min_children, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
        return fmt::format("{}({}, {}, MASK({}))", f.select, "{1}", "{0}", blend_first_wins(kind, a, b, k));
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_MODIFIER(Kind, name, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
        break;
    }
    throw std::logic_error("blend_rule() called on a primitive or a modifier");
  }

  /// The distance of an operator's operands a and b, as combine() writes it.
  static std::string combine_rule(NodeKind kind, const std::string& a, const std::string& b, const std::string& k) {
    switch (kind) {
      case NodeKind::Union:
        return fmt::format("op_union({}, {})", a, b);
      case NodeKind::Intersection:
        return fmt::format("op_intersection({}, {})", a, b);
      case NodeKind::Subtraction:
        return fmt::format("op_subtraction({}, {})", a, b);
      case NodeKind::SmoothUnion:
        return fmt::format("op_smooth_union({}, {}, {})", a, b, k);
      case NodeKind::SmoothIntersection:
        return fmt::format("op_smooth_intersection({}, {}, {})", a, b, k);
      case NodeKind::SmoothSubtraction:
        return fmt::format("op_smooth_subtraction({}, {}, {})", a, b, k);
#define CLMARCH_BLEND(Kind, name, min_children, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
        return blend_distance_code(kind, a, b, k);
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_MODIFIER(Kind, name, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
        break;
    }
    throw std::logic_error("combine_rule() called on a primitive or a modifier");
  }

 private:
  std::string fresh(const char* prefix) { return fmt::format("{}{}", prefix, counter_++); }
  /// The literal of a smooth operator's blend radius; nothing for the others.
  std::string blend_radius(const Node& node) {
    return is_smooth_operator(node.kind) ? lit_.f(smooth_k(node)) : std::string();
  }
  /// The operator's arguments after a and b: a smooth one's blend radius, a blend's parameters.
  std::string operator_arguments(const Node& node) {
    if (!is_blend_operator(node.kind)) return blend_radius(node);
    std::string joined;
    for (const std::string& arg : blend_arguments(node, lit_)) joined += (joined.empty() ? "" : ", ") + arg;
    return joined;
  }
  void line(const std::string& text) { body_ += "  " + indent_ + text + "\n"; }

  /// The node's frame: the point and offset its subtree sees. The subtree's points are measured
  /// from a pivot of its own frame, its bound's centre: with C = translate + s R pivot that centre
  /// in the parent frame, p_local - pivot = L (p + offset - C). C - offset and pivot are formed here
  /// in double, so the kernel's point stays as small as the subtree, and a model authored far from
  /// the origin and translated home keeps the precision of one authored at home (issue 26).
  std::pair<std::string, glm::dvec3> emit_transform(const Node& node, const std::string& p, const glm::dvec3& offset) {
    const Transform& transform = node.transform;
    if (transform.is_identity()) return {p, offset};
    // localFromWorld = S^-1 R^T (p - translate)
    const glm::dmat3 local_from_world = glm::transpose(transform.world_from_local_rotation()) / transform.scale;
    const glm::dvec3 r0 = glm::row(local_from_world, 0), r1 = glm::row(local_from_world, 1),
                     r2 = glm::row(local_from_world, 2);
    const std::optional<BoundingSphere> bound = local_bounds(node);
    const glm::dvec3 centre = transform.translate + transform.world_from_local_rotation() *
                                                        (transform.scale * (bound ? bound->center : glm::dvec3(0.0)));
    // C - offset rounded to float, as the kernel holds it, and the pivot taken from that C: then the
    // kernel's subtraction is exact, and the rounding only moves the pivot, which the subtree's
    // positions, measured from it in double, follow.
    const glm::dvec3 kernel_centre = glm::dvec3(glm::vec3(centre - offset));
    const std::string q = fresh("p");
    line(fmt::format("vec3v {} = v3_transform(v3_sub({}, v3_from({})), {}, {}, {}, {}, {}, {}, {}, {}, {});", q, p,
                     lit_.f4(kernel_centre), lit_.f(r0.x), lit_.f(r0.y), lit_.f(r0.z), lit_.f(r1.x), lit_.f(r1.y),
                     lit_.f(r1.z), lit_.f(r2.x), lit_.f(r2.y), lit_.f(r2.z)));
    return {q, local_from_world * (kernel_centre + offset - transform.translate)};
  }

  /// p + offset as a point of the kernel: the absolute point for terrain noise (which hashes absolute
  /// lattice coordinates), the point relative to its axis for the polar repetition.
  std::string absolute_point(const std::string& p, const glm::dvec3& offset) {
    if (offset == glm::dvec3(0.0)) return p;
    std::string q = fresh("p");
    line(fmt::format("vec3v {} = v3_add({}, v3_from({}));", q, p, lit_.f4(offset)));
    return q;
  }

  /// The terrain at the point p + offset. Its noise hashes absolute lattice coordinates, so the
  /// offset cannot fold into positions: each octave's lattice point of it, M^i f (offset.x,
  /// offset.z) with M the octave step of kernels/noise.cl (noise_next_octave), is split here in
  /// double into whole cells and a fraction, which sd_terrain_<noise>_phased adds to the octave's
  /// small point (issue 26: at 10^4 float's spacing of the absolute point had turned the normals
  /// by 31 degrees). Where the cells outgrow float's integers (2^24), the absolute point is formed
  /// in float as before.
  std::string terrain_call(const Node& node, const std::string& p, const glm::dvec3& offset) {
    if (offset == glm::dvec3(0.0)) return primitive_call(node, p, offset, lit_);
    const Terrain& terrain = params_of<Terrain>(node);
    const double lacunarity = terrain_lacunarity(terrain);
    glm::dvec2 lattice = terrain.frequency * glm::dvec2(offset.x, offset.z);
    std::string phases;
    for (int octave = 0; octave < terrain.octaves; ++octave) {
      const glm::dvec2 cells = glm::floor(lattice), fraction = lattice - cells;
      if (std::abs(cells.x) >= 0x1p24 || std::abs(cells.y) >= 0x1p24) {
        return primitive_call(node, absolute_point(p, offset), glm::dvec3(0.0), lit_);
      }
      phases += fmt::format("{}(float4)({}, {}, {}, {})", octave ? ", " : "", lit_.f(fraction.x), lit_.f(fraction.y),
                            lit_.f(cells.x), lit_.f(cells.y));
      lattice = lacunarity * glm::dvec2(0.8 * lattice.x + 0.6 * lattice.y, -0.6 * lattice.x + 0.8 * lattice.y);
    }
    const std::string table = fresh("phases");
    line(fmt::format("const float4 {}[] = {{{}}};", table, phases));
    // The declared call, renamed to its phased form and given the table.
    std::string call = primitive_call(node, p, glm::dvec3(0.0), lit_);
    call.insert(call.find('('), "_phased");
    call.insert(call.size() - 1, ", " + table);
    return call;
  }

  /// A glsl node's call of its translated code (glsl_code.hpp), at its local point, with the time
  /// a literal so that frames of an animation share the program.
  std::string glsl_call(const Node& node, const std::string& p, const glm::dvec3& offset, const char* function) {
    const Glsl& glsl = params_of<Glsl>(node);
    return fmt::format("{}_{}_lanes({}, {})", glsl.program->name, function, absolute_point(p, offset),
                       lit_.f(glsl.program->time));
  }

  Value emit_primitive(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    Value value{fresh("d"), "", "", "", ""};
    std::string call;
    if (node.kind == NodeKind::Terrain) {
      call = terrain_call(node, p, offset);
    } else if (node.kind == NodeKind::Glsl) {
      call =
          fmt::format("{} * {}", glsl_call(node, p, offset, "distance"), lit_.f(1.0 / params_of<Glsl>(node).lipschitz));
    } else {
      call = primitive_call(node, p, offset, lit_);
    }
    line(fmt::format("vfloat {} = {};  /* {} */", value.distance, call, node_kind_name(node.kind)));
    if (with_color_) {
      value.color = fresh("c");
      if (node.kind == NodeKind::Glsl && params_of<Glsl>(node).program->module.color_function >= 0) {
        line(fmt::format("vec3v {} = {};  /* the code's colour */", value.color, glsl_call(node, p, offset, "color")));
      } else if (color.pattern) {
        line(fmt::format("vec3v {} = {};  /* color pattern */", value.color,
                         pattern_color_code(*color.pattern, pattern_frame_, lit_)));
      } else {
        line(fmt::format("vec3v {} = v3_from({});", value.color, lit_.f4(color.albedo)));
      }
      value.surface = fresh("s");
      line(fmt::format("vec3v {} = v3_from({});", value.surface, lit_.f4(surface_vector(color, materials_.model))));
      if (materials_.emission) {
        value.emission = fresh("e");
        line(fmt::format("vec3v {} = v3_from({});", value.emission, lit_.f4(color.emission)));
      }
    }
    if (with_color_ && ids_.on) {
      // Spelled, not a literal: numbers never vary between frames, and literals keep their indices.
      value.id = fresh("i");
      const std::string number = fmt::format("{}.0f", first_id_);
      line(fmt::format("vfloat {} = (vfloat)({});", value.id, ids_.base.empty() ? number : ids_.base + " + " + number));
    }
    return value;
  }

  Value emit_operator(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    if (grid_ && &node == grid_->node) return emit_grid(node, p, color, offset);
    if (node.kind == NodeKind::Repeat) return emit_repeat(node, p, color, offset);
    if (node.kind == NodeKind::Displace) return emit_displace(node, p, color, offset);
    if (node.kind == NodeKind::Elongate) return emit_elongate(node, p, color, offset);
    if (node.kind == NodeKind::Onion) return emit_onion(node, p, color, offset);
    if (node.kind == NodeKind::Round) return emit_round(node, p, color, offset);
    if (node.kind == NodeKind::Mirror) return emit_mirror(node, p, color, offset);
    if (node.kind == NodeKind::RepeatPolar) return emit_repeat_polar(node, p, color, offset);
    if (node.kind == NodeKind::RepeatLimited) return emit_repeat_limited(node, p, color, offset);
    if (node.kind == NodeKind::Revolve) return emit_revolve(node, p, color, offset);
    if (node.kind == NodeKind::Extrude) return emit_extrude(node, p, color, offset);
    if (node.kind == NodeKind::Twist || node.kind == NodeKind::Bend) return emit_turn(node, p, color, offset);
    if (node.kind == NodeKind::NonuniformScale) return emit_nonuniform_scale(node, p, color, offset);
    if (node.kind == NodeKind::Union) return emit_union(node, p, color, offset);
    const std::vector<int> firsts = child_first_ids(node, first_id_);
    Value acc = emit(node.children.front(), p, color, offset);
    for (std::size_t i = 1; i < node.children.size(); ++i) {
      const Node& child = node.children[i];
      first_id_ = firsts[i];
      const std::optional<std::string> skip_limit = sequential_skip_limit(node, acc.distance);
      const Value next = skip_limit ? emit_gated(child, p, color, offset, *skip_limit) : emit(child, p, color, offset);
      acc = combine(node, acc, next);
    }
    return acc;
  }

  /// Above what bound of a later child the operator returns acc unchanged: smooth union acc + k
  /// (its blend weight is 1 there), subtraction -acc, smooth subtraction k - acc (weight 0), the
  /// blends' limits (codegen/blend_code.cpp). Nothing for intersections, whose result is the
  /// largest operand.
  std::optional<std::string> sequential_skip_limit(const Node& node, const std::string& acc) {
    const std::string k = blend_radius(node);
    switch (node.kind) {
      case NodeKind::SmoothUnion:
        return fmt::format("{} + {}", acc, k);
      case NodeKind::Subtraction:
        return fmt::format("-{}", acc);
      case NodeKind::SmoothSubtraction:
        return fmt::format("{} - {}", k, acc);
#define CLMARCH_BLEND(Kind, name, min_children, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
        return blend_skip_limit(node.kind, acc, blend_arguments(node, lit_));
      case NodeKind::Union:
      case NodeKind::Intersection:
      case NodeKind::SmoothIntersection:
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) case NodeKind::Kind:
#define CLMARCH_MODIFIER(Kind, name, params_list) case NodeKind::Kind:
#include "scene/node_kinds.def"
        return std::nullopt;
    }
    return std::nullopt;
  }

  /// A union's children in any order of evaluation (min is commutative, and the material follows
  /// the first child at the minimum whatever the order): children not worth a bound first, then
  /// the others gated by the least distance so far; combined in the scene's order. In map() (no
  /// material), where at least kMinGroupedOperands cheap children are bounded, those are evaluated
  /// by place instead (emit_grouped), after the unbounded ones; map_color() runs once per hit, where
  /// a gate saves nothing and costs PoCL's compile.
  Value emit_union(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    if (std::optional<OperandGroup> groups = grouped_operands(node))
      return emit_grouped(node, *groups, p, color, offset);
    const std::vector<int> firsts = child_first_ids(node, first_id_);
    std::vector<std::size_t> gated, plain;
    for (std::size_t i = 0; i < node.children.size(); ++i)
      (worth_a_bound(node.children[i]) ? gated : plain).push_back(i);
    std::vector<std::optional<Value>> values(node.children.size());
    std::string least;  // the least distance of the children evaluated so far, while a gate needs it
    const auto fold = [&](const std::string& distance) {
      if (least.empty()) {
        least = distance;
        return;
      }
      const std::string next = fresh("m");
      line(fmt::format("vfloat {} = fmin({}, {});", next, least, distance));
      least = next;
    };
    for (std::size_t i : plain) {
      first_id_ = firsts[i];
      values[i] = emit(node.children[i], p, color, offset);
      if (!gated.empty()) fold(values[i]->distance);
    }
    for (std::size_t i : gated) {
      first_id_ = firsts[i];
      values[i] = least.empty() ? emit(node.children[i], p, color, offset)
                                : emit_gated(node.children[i], p, color, offset, least);
      if (i != gated.back()) fold(values[i]->distance);
    }
    Value acc = *values.front();
    for (std::size_t i = 1; i < values.size(); ++i) acc = combine(node, acc, *values[i]);
    return acc;
  }

  /// Cheap bounded children of a union from which it pays to group them by place (fewer gain
  /// nothing from a bound the single children are not worth).
  static constexpr std::size_t kMinGroupedOperands = 4;

  /// The hierarchy of a union's cheap bounded children in map(), or nothing where the union is
  /// evaluated as emit_union does otherwise.
  std::optional<OperandGroup> grouped_operands(const Node& node) const {
    if (!group_places_) return std::nullopt;
    std::vector<GroupedOperand> groupable;
    bool unbounded = false;
    for (std::size_t i = 0; i < node.children.size(); ++i) {
      const Node& child = node.children[i];
      if (worth_a_bound(child)) continue;
      if (const std::optional<BoundingSphere> bounds = node_bounds(child)) {
        groupable.push_back({i, *bounds, subtree_cost(child)});
      } else {
        unbounded = true;
      }
    }
    if (groupable.size() < kMinGroupedOperands) return std::nullopt;
    OperandGroup groups = group_operands(std::move(groupable));
    // Without a group worth its bound (each costs about one sphere evaluation and a branch) the
    // children stay in the scene's order, ungated: a table of five boxes was 10-15 % slower
    // grouped (checker_floor, docs/performance.md).
    if (!has_gated_group(groups, unbounded)) return std::nullopt;
    return groups;
  }

  /// A union's distance, its children evaluated in this order: the unbounded ones, the groups
  /// (each beyond the first only where a lane's bound of it is at most the least distance so far),
  /// then the expensive children behind their own bounds. Every child lowers one running minimum,
  /// which is the union's value: a skipped group cannot lower it.
  Value emit_grouped(const Node& node, const OperandGroup& groups, const std::string& p, const Material& color,
                     const glm::dvec3& offset) {
    line(fmt::format("/* {} operands of the union by place, {} groups */", count_operands(groups),
                     count_groups(groups)));
    const std::string running = fresh("m");
    bool running_set = false;
    const auto lower = [&](const std::string& distance) {
      line(running_set ? fmt::format("{} = fmin({}, {});", running, running, distance)
                       : fmt::format("vfloat {} = {};", running, distance));
      running_set = true;
    };
    // A child's first primitive number still matters without ids: an operand grid below records it.
    const std::vector<int> firsts = child_first_ids(node, first_id_);
    std::vector<bool> grouped(node.children.size(), false);
    for_each_operand(groups, [&](const GroupedOperand& operand) { grouped[operand.index] = true; });
    for (std::size_t i = 0; i < node.children.size(); ++i) {
      first_id_ = firsts[i];
      if (!grouped[i] && !worth_a_bound(node.children[i])) lower(emit(node.children[i], p, color, offset).distance);
    }
    if (!running_set) line(fmt::format("vfloat {};", running));
    emit_group(node, groups, firsts, p, color, offset, running, running_set);
    for (std::size_t i = 0; i < node.children.size(); ++i) {
      first_id_ = firsts[i];
      if (worth_a_bound(node.children[i])) lower(emit_gated(node.children[i], p, color, offset, running).distance);
    }
    return {running, "", "", "", ""};
  }

  void emit_group(const Node& node, const OperandGroup& group, const std::vector<int>& firsts, const std::string& p,
                  const Material& color, const glm::dvec3& offset, const std::string& running, bool& running_set) {
    const auto contents = [&] {
      for (const OperandGroup& half : group.halves)
        emit_group(node, half, firsts, p, color, offset, running, running_set);
      for (const GroupedOperand& operand : group.operands) {
        first_id_ = firsts[operand.index];
        const std::string distance = emit(node.children[operand.index], p, color, offset).distance;
        line(running_set ? fmt::format("{} = fmin({}, {});", running, running, distance)
                         : fmt::format("{} = {};", running, distance));
        running_set = true;
      }
    };
    if (!running_set || group.cost < kGateCost) {
      contents();
      return;
    }
    const std::string bound = fresh("b");
    line(fmt::format("vfloat {} = sd_bound({}, {}, {}, {});  /* bound of {} operands */", bound, p,
                     lit_.f4(group.bounds.center - offset), lit_.f(group.bounds.radius),
                     lit_.f(1.0 / group.bounds.gain), count_operands(group)));
    // The group's gain is its largest, a bound only where the distance is not negative: below 0 a
    // child of smaller gain reaches lower, so a negative minimum compares with 0 (no child is
    // negative outside the group's sphere). A NaN so far (a user's glsl) skips nothing, as fmin would.
    line(fmt::format("if (LANE_ANY(MASK(({} <= fmax({}, (vfloat)(0.0f))) | isnan({})))) {{", bound, running, running));
    indent_ += "  ";
    contents();
    indent_.resize(indent_.size() - 2);
    line("}");
  }

  /// Whether emit_group gates a group of this hierarchy: one that costs at least kGateCost, with a
  /// distance to compare against (running_set: a child evaluated before it).
  static bool has_gated_group(const OperandGroup& group, bool running_set) {
    if (running_set && group.cost >= kGateCost) return true;
    for (const OperandGroup& half : group.halves) {
      if (has_gated_group(half, running_set)) return true;
      running_set = true;
    }
    return false;
  }

  static std::size_t count_operands(const OperandGroup& group) {
    std::size_t count = 0;
    for_each_operand(group, [&](const GroupedOperand&) { ++count; });
    return count;
  }
  static std::size_t count_groups(const OperandGroup& group) {
    std::size_t count = 1;
    for (const OperandGroup& half : group.halves) count += count_groups(half);
    return count;
  }

  /// Worth gating behind its bounding sphere: a bounded subtree that costs well more than the bound.
  bool worth_a_bound(const Node& node) const {
    return gate_subtrees_ && subtree_cost(node) >= kGateCost && node_bounds(node).has_value();
  }

  /// The child, evaluated only if a lane's bound of it is at most skip_limit (the operator's result
  /// does not depend on it above that); otherwise its value is the bound, and its material unset.
  Value emit_gated(const Node& child, const std::string& p, const Material& color, const glm::dvec3& offset,
                   const std::string& skip_limit) {
    if (!worth_a_bound(child)) return emit(child, p, color, offset);
    const BoundingSphere sphere = *node_bounds(child);
    Value out{fresh("d"), "", "", "", ""};
    line(fmt::format("vfloat {} = sd_bound({}, {}, {}, {});  /* bound of {} */", out.distance, p,
                     lit_.f4(sphere.center - offset), lit_.f(sphere.radius), lit_.f(1.0 / sphere.gain),
                     node_kind_name(child.kind)));
    if (with_color_) {
      out.color = fresh("c");
      out.surface = fresh("s");
      line(fmt::format("vec3v {} = v3_splat(0.0f), {} = v3_splat(0.0f);", out.color, out.surface));
      if (materials_.emission) {
        out.emission = fresh("e");
        line(fmt::format("vec3v {} = v3_splat(0.0f);", out.emission));
      }
    }
    if (with_color_ && ids_.on) {
      out.id = fresh("i");
      line(fmt::format("vfloat {} = (vfloat)(-1.0f);", out.id));
    }
    line(fmt::format("if (LANE_ANY(MASK({} <= {}))) {{", out.distance, skip_limit));
    indent_ += "  ";
    const Value inside = emit(child, p, color, offset);
    line(fmt::format("{} = {};", out.distance, inside.distance));
    if (with_color_) line(fmt::format("{} = {}; {} = {};", out.color, inside.color, out.surface, inside.surface));
    if (!out.emission.empty()) line(fmt::format("{} = {};", out.emission, inside.emission));
    if (!out.id.empty()) line(fmt::format("{} = {};", out.id, inside.id));
    indent_.resize(indent_.size() - 2);
    line("}");
    return out;
  }

  Value emit_repeat(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const glm::dvec3& period = params_of<Repeat>(node).period;
    glm::dvec3 child_offset = offset;
    const auto axis = [&](const char* c, int i) {
      if (!(period[i] > 0.0)) return fmt::format("{}.{}", p, c);
      // Repetition forgets whole periods, so only the offset's remainder matters (floor-based).
      const double remainder = floor_mod(offset[i], period[i]);
      child_offset[i] = 0.0;
      const std::string x =
          remainder == 0.0 ? fmt::format("{}.{}", p, c) : fmt::format("{}.{} + {}", p, c, lit_.f(remainder));
      return fmt::format("op_repeat_axis({}, {})", x, lit_.f(period[i]));
    };
    const std::string q = fresh("p");
    line(fmt::format("vec3v {} = v3({}, {}, {});  /* repeat */", q, axis("x", 0), axis("y", 1), axis("z", 2)));
    return emit(node.children.front(), q, color, child_offset);
  }

  Value emit_displace(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const Value child = emit(node.children.front(), p, color, offset);
    const Displace& displace = params_of<Displace>(node);
    // The texture of the absolute point p + offset: f (p + offset) = f p + phase, the phase reduced
    // mod 2 pi here in double, so the kernel's sines take only the small p in float.
    glm::dvec3 phase;
    for (int axis = 0; axis < 3; ++axis)
      phase[axis] = std::fmod(displace.frequency * offset[axis], 2.0 * std::numbers::pi);
    Value out{fresh("d"), child.color, child.surface, child.id, child.emission};
    line(fmt::format("vfloat {} = ({} + displacement({}, {}, {}, {})) * {};  /* displace */", out.distance,
                     child.distance, p, lit_.f4(phase), lit_.f(displace.amplitude), lit_.f(displace.frequency),
                     lit_.f(1.0 / displacement_lipschitz(node))));
    return out;
  }

  /// The child at q = p_local - clamp(p_local, -h, h) with p_local = p + offset, written as
  /// p - clamp(p, -h - offset, h - offset) so that the bounds carry the offset in double and q
  /// (small near the shape) is the child's local point: its offset ends here.
  Value emit_elongate(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const glm::dvec3& h = params_of<Elongate>(node).h;
    const glm::dvec3 low = -h - offset, high = h - offset;
    const std::string q = fresh("p");
    const auto axis = [&](const char* c, int i) {
      return fmt::format("{0}.{1} - clamp({0}.{1}, {2}, {3})", p, c, lit_.f(low[i]), lit_.f(high[i]));
    };
    line(fmt::format("vec3v {} = v3({}, {}, {});  /* elongate */", q, axis("x", 0), axis("y", 1), axis("z", 2)));
    return emit(node.children.front(), q, color, glm::dvec3(0.0));
  }

  /// The child's distance d made d' by a formula of d (onion, round); material unchanged.
  Value emit_distance_map(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset,
                          const char* format, double amount) {
    const Value child = emit(node.children.front(), p, color, offset);
    Value out{fresh("d"), child.color, child.surface, child.id, child.emission};
    line(fmt::format("vfloat {} = {};  /* {} */", out.distance,
                     fmt::format(fmt::runtime(format), child.distance, lit_.f(amount)), node_kind_name(node.kind)));
    return out;
  }

  Value emit_onion(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    return emit_distance_map(node, p, color, offset, "fabs({}) - {}", params_of<Onion>(node).thickness);
  }

  Value emit_round(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    return emit_distance_map(node, p, color, offset, "{} - {}", params_of<Round>(node).radius);
  }

  /// |p_local| on the mirrored axes, which leave the offset there.
  Value emit_mirror(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const glm::bvec3& axes = params_of<Mirror>(node).axes;
    glm::dvec3 child_offset = offset;
    const auto axis = [&](const char* c, int i) {
      if (!axes[i]) return fmt::format("{}.{}", p, c);
      child_offset[i] = 0.0;
      return offset[i] == 0.0 ? fmt::format("fabs({}.{})", p, c)
                              : fmt::format("fabs({}.{} + {})", p, c, lit_.f(offset[i]));
    };
    const std::string q = fresh("p");
    line(fmt::format("vec3v {} = v3({}, {}, {});  /* mirror */", q, axis("x", 0), axis("y", 1), axis("z", 2)));
    return emit(node.children.front(), q, color, child_offset);
  }

  /// The point turned back into the sector of the copy k = 0, about the local y axis (whose x and
  /// z need the absolute point).
  Value emit_repeat_polar(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const int count = params_of<RepeatPolar>(node).count;
    const std::string at = absolute_point(p, glm::dvec3(offset.x, 0.0, offset.z));
    const std::string q = fresh("p");
    line(fmt::format("vec3v {} = op_repeat_polar({}, {});  /* repeat_polar of {} */", q, at,
                     lit_.f(2.0 * std::numbers::pi / count), count));
    return emit(node.children.front(), q, color, glm::dvec3(0.0, offset.y, 0.0));
  }

  /// Limited repetition per repeated axis, on the absolute coordinate there.
  Value emit_repeat_limited(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const RepeatLimited& repeat = params_of<RepeatLimited>(node);
    glm::dvec3 child_offset = offset;
    const auto axis = [&](const char* c, int i) {
      if (!(repeat.period[i] > 0.0)) return fmt::format("{}.{}", p, c);
      child_offset[i] = 0.0;
      const std::string x =
          offset[i] == 0.0 ? fmt::format("{}.{}", p, c) : fmt::format("{}.{} + {}", p, c, lit_.f(offset[i]));
      return fmt::format("op_repeat_limited_axis({}, {}, {}.0f, {}.0f)", x, lit_.f(repeat.period[i]), repeat.min[i],
                         repeat.max[i]);
    };
    const std::string q = fresh("p");
    line(fmt::format("vec3v {} = v3({}, {}, {});  /* repeat_limited */", q, axis("x", 0), axis("y", 1), axis("z", 2)));
    return emit(node.children.front(), q, color, child_offset);
  }

  /// The child's section at z = 0 at (length(p_local.xz) - offset, p_local.y): the radius needs
  /// the absolute x and z; y keeps its offset.
  Value emit_revolve(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const std::string at = absolute_point(p, glm::dvec3(offset.x, 0.0, offset.z));
    const std::string q = fresh("p");
    line(
        fmt::format("vec3v {0} = v3(vsqrt({1}.x * {1}.x + {1}.z * {1}.z) - {2}, {1}.y, (vfloat)(0.0f));  /* revolve */",
                    q, at, lit_.f(params_of<Revolve>(node).offset)));
    return emit(node.children.front(), q, color, glm::dvec3(0.0, offset.y, 0.0));
  }

  /// The child's section at z = 0 extruded along the absolute z.
  Value emit_extrude(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const std::string q = fresh("p");
    line(fmt::format("vec3v {0} = v3({1}.x, {1}.y, (vfloat)(0.0f));  /* extrude */", q, p));
    const Value section = emit(node.children.front(), q, color, glm::dvec3(offset.x, offset.y, 0.0));
    const std::string z = offset.z == 0.0 ? fmt::format("{}.z", p) : fmt::format("{}.z + {}", p, lit_.f(offset.z));
    Value out{fresh("d"), section.color, section.surface, section.id, section.emission};
    line(fmt::format("vfloat {} = op_extrude({}, {}, {});", out.distance, section.distance, z,
                     lit_.f(params_of<Extrude>(node).half_length)));
    return out;
  }

  /// Twist (about y) and bend (about z): the child at the turned absolute point, its distance
  /// divided by the turn's Lipschitz factor there, and never below the distance to the sphere
  /// holding the turned child (scene_bounds' turned_bounds).
  Value emit_turn(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const bool twist = node.kind == NodeKind::Twist;
    const int axis = twist ? 1 : 2;
    const double rate = (twist ? params_of<Twist>(node).rate : params_of<Bend>(node).rate) * std::numbers::pi / 180.0;
    const BoundingSphere child_bounds = *node_bounds(node.children.front());
    const BoundingSphere ball = turned_bounds(child_bounds, axis);
    const std::string at = absolute_point(p, offset);
    const std::string q = fresh("p");
    line(fmt::format("vec3v {} = op_{}({}, {});  /* {} */", q, twist ? "twist" : "bend", at, lit_.f(rate),
                     node_kind_name(node.kind)));
    const Value child = emit(node.children.front(), q, color, glm::dvec3(0.0));
    const std::string across = twist ? fmt::format("vsqrt({0}.x * {0}.x + {0}.z * {0}.z)", at)
                                     : fmt::format("vsqrt({0}.x * {0}.x + {0}.y * {0}.y)", at);
    Value out{fresh("d"), child.color, child.surface, child.id, child.emission};
    line(fmt::format("vfloat {} = fmax({} / op_{}_lipschitz({}, {}, {}), sd_bound({}, {}, {}, 1.0f));", out.distance,
                     child.distance, twist ? "twist" : "bend", across, lit_.f(rate),
                     lit_.f(turn_reach(child_bounds, axis)), p, lit_.f4(ball.center - offset), lit_.f(ball.radius)));
    return out;
  }

  /// The child at p_local / factors (its offset divided too), its distance times the smallest factor.
  Value emit_nonuniform_scale(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    const glm::dvec3& f = params_of<NonuniformScale>(node).factors;
    const std::string q = fresh("p");
    line(fmt::format("vec3v {0} = v3({1}.x * {2}, {1}.y * {3}, {1}.z * {4});  /* nonuniform_scale */", q, p,
                     lit_.f(1.0 / f.x), lit_.f(1.0 / f.y), lit_.f(1.0 / f.z)));
    const Value child = emit(node.children.front(), q, color, offset / f);
    Value out{fresh("d"), child.color, child.surface, child.id, child.emission};
    line(fmt::format("vfloat {} = {} * {};", out.distance, child.distance, lit_.f(std::min({f.x, f.y, f.z}))));
    return out;
  }

  Value combine(const Node& node, const Value& a, const Value& b) {
    Value out{fresh("d"), "", "", "", ""};
    const std::string k = operator_arguments(node);
    if (with_color_) {
      const std::string blend = blend_rule(node.kind, a.distance, b.distance, k);
      out.color = fresh("c");
      line(fmt::format("vec3v {} = {};", out.color, fmt::format(fmt::runtime(blend), a.color, b.color)));
      out.surface = fresh("s");
      line(fmt::format("vec3v {} = {};", out.surface, fmt::format(fmt::runtime(blend), a.surface, b.surface)));
      if (materials_.emission) {
        out.emission = fresh("e");
        line(fmt::format("vec3v {} = {};", out.emission, fmt::format(fmt::runtime(blend), a.emission, b.emission)));
      }
    }
    if (with_color_ && ids_.on) {
      out.id = fresh("i");
      const std::string rule = blend_rule(node.kind, a.distance, b.distance, k, kIdBlend);
      line(fmt::format("vfloat {} = {};", out.id, fmt::format(fmt::runtime(rule), a.id, b.id)));
    }
    line(fmt::format("vfloat {} = {};", out.distance, combine_rule(node.kind, a.distance, b.distance, k)));
    return out;
  }

  /// The union of many operands, read from its operand grid (kernels/operand_grid.cl).
  Value emit_grid(const Node& node, const std::string& p, const Material& color, const glm::dvec3& offset) {
    if (color.pattern && !node.color_pattern) {
      // Its operands' code sees the union's point only.
      throw InputError(
          fmt::format("a color pattern set above a {} of {} operands evaluated from an operand grid: set it on the {} "
                      "or on its operands, or render.pruning: none",
                      node_kind_name(node.kind), node.children.size(), node_kind_name(node.kind)));
    }
    if (!grid_->emitted) grid_->emit(node, first_id_, color, offset, gate_subtrees_, materials_, lit_);
    Value out{fresh("d"), "", "", "", ""};
    const std::string what =
        fmt::format("{} of {} operands, from its operand grid", node_kind_name(node.kind), node.children.size());
    if (with_color_) {
      out.color = fresh("c");
      out.surface = fresh("s");
      // The grid's operands always number their primitives; programs without ids drop the number.
      const std::string id = fresh("i");
      // Scenes without emission give the grid a vector it fills with 0, which the compiler drops.
      const std::string emission = fresh("e");
      line(fmt::format("vec3v {}, {}, {};", out.color, out.surface, emission));
      line(fmt::format("vfloat {};", id));
      line(fmt::format("vfloat {} = grid_distance_color(values, {}, &{}, &{}, &{}, &{});  /* {} */", out.distance, p,
                       out.color, out.surface, emission, id, what));
      if (materials_.emission) out.emission = emission;
      if (ids_.on) out.id = id;
    } else {
      line(fmt::format("vfloat {} = grid_distance(values, {});  /* {} */", out.distance, p, what));
    }
    return out;
  }

  bool with_color_;
  bool gate_subtrees_;
  bool group_places_;  ///< map() only: the colour function runs once per hit, where a gate saves nothing
  Literals& lit_;
  GridEmission* grid_;
  IdNumbering ids_;
  MaterialLayout materials_;
  /// The point the current pattern is evaluated at (set_pattern_frame).
  std::string pattern_frame_;
  /// The number of the first primitive of the node being emitted, from the emitter's base.
  int first_id_ = 0;
  int counter_ = 0;
  std::string body_;
  std::string indent_;
};

/// A float word holding an int's bits (the kernel reads it with as_int).
float int_word(std::uint32_t value) { return std::bit_cast<float>(value); }

/// The body of an operand's code with its literal marks read from the operand's record instead.
std::string read_literals_from_record(const std::string& body) {
  std::string out;
  std::size_t at = 0;
  for (std::size_t mark = body.find('@'); mark != std::string::npos; mark = body.find('@', at)) {
    const std::size_t end = body.find('@', mark + 1);
    out += body.substr(at, mark - at);
    out += fmt::format("SCENE_DATA[literals + {}]", body.substr(mark + 1, end - mark - 1));
    at = end + 1;
  }
  return out + body.substr(at);
}

/// One function over the shapes of the operands: a switch on the shape word of the record, the
/// last shape as its default so that every path returns.
std::string shape_function(const std::string& signature, const std::string& literals_at, const std::string& shape_word,
                           const std::vector<std::string>& shapes) {
  std::string out = signature + " {\n" + fmt::format("  const int literals = {};\n", literals_at);
  if (shapes.size() == 1) return out + read_literals_from_record(shapes.front()) + "}\n";
  out += fmt::format("  switch (as_int({})) {{\n", shape_word);
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    out += i + 1 < shapes.size() ? fmt::format("    case {}: {{\n", i) : std::string("    default: {\n");
    out += read_literals_from_record(shapes[i]) + "    }\n";
  }
  return out + "  }\n}\n";
}

/// FNV-1a over bytes, continuing from hash.
std::uint64_t fnv1a(std::uint64_t hash, const void* bytes, std::size_t size) {
  const auto* at = static_cast<const unsigned char*>(bytes);
  for (std::size_t i = 0; i < size; ++i) hash = (hash ^ at[i]) * 0x100000001b3ULL;
  return hash;
}

/// An operand grid packed into the words kernels/operand_grid.cl reads (header, cell starts, lists
/// of record offsets, records), and the figures the generated code's comment gives.
struct PackedGrid {
  std::shared_ptr<const std::vector<float>> data;
  glm::ivec3 dims{1};
  long long cells = 1;
  std::size_t listed = 0;
};

PackedGrid pack_grid(const OperandGrid& grid, const std::vector<float>& records,
                     const std::vector<std::uint32_t>& record_at) {
  const long long cells = grid.cell_count();
  const std::size_t cells_at = CLMARCH_GRID_HEADER_WORDS;
  const std::size_t list_at = cells_at + static_cast<std::size_t>(cells) + 1;
  const std::size_t records_at = list_at + grid.operands.size();
  auto data = std::make_shared<std::vector<float>>(CLMARCH_GRID_HEADER_WORDS, 0.0f);
  std::vector<float>& words = *data;
  for (int axis = 0; axis < 3; ++axis) {
    words[CLMARCH_GRID_ORIGIN + axis] = static_cast<float>(grid.lower[axis]);
    words[CLMARCH_GRID_DIMS + axis] = static_cast<float>(grid.dims[axis]);
    words[CLMARCH_GRID_UPPER + axis] = static_cast<float>(grid.upper[axis]);
  }
  words[CLMARCH_GRID_INVERSE_CELL] = static_cast<float>(1.0 / grid.cell_size);
  words[CLMARCH_GRID_OUTSIDE + 0] = static_cast<float>(grid.outside_margin);
  words[CLMARCH_GRID_OUTSIDE + 1] = static_cast<float>(grid.outside_inverse_gain);
  words[CLMARCH_GRID_OUTSIDE + 2] = static_cast<float>(grid.outside_undershoot);
  words[CLMARCH_GRID_CELLS_AT] = int_word(static_cast<std::uint32_t>(cells_at));
  words[CLMARCH_GRID_LIST_AT] = int_word(static_cast<std::uint32_t>(list_at));
  words.reserve(records_at + records.size());
  for (std::uint32_t start : grid.cell_start) words.push_back(int_word(start));
  for (std::uint32_t operand : grid.operands)
    words.push_back(int_word(static_cast<std::uint32_t>(records_at + record_at[operand])));
  words.insert(words.end(), records.begin(), records.end());
  return {std::move(data), grid.dims, cells, grid.operands.size()};
}

/// The packed grid of union_node, built once for the operands it was built for: a program's
/// source and its values are generated apart (generate_kernel_source, scene_values) from the same
/// scene, and a large union's grid takes seconds. key identifies the operands by their code and
/// numbers, records included. Only the packed words are kept, the grid itself freed once packed,
/// so that a large grid is held once in host memory besides the device's copy.
PackedGrid packed_grid_for(const Node& union_node, const glm::dvec3& offset, std::uint64_t key,
                           const std::vector<float>& records, const std::vector<std::uint32_t>& record_at) {
  static std::mutex mutex;
  static std::uint64_t last_key = 0;
  static PackedGrid last;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (last.data && last_key == key) return last;
  }
  // A program's code is generated once its device is selected (prepare_program): only the build's
  // address space is still to come.
  const std::optional<AvailableMemory> memory = available_host_memory(kOpenClBuildAddressSpace);
  const OperandGrid grid = build_operand_grid(union_node, offset, memory);
  const std::uint64_t packed_bytes =
      sizeof(float) * (CLMARCH_GRID_HEADER_WORDS + grid.cell_start.size() + grid.operands.size() + records.size());
  // Measured again: the grid is held now, and the packed words are allocated beside it.
  if (const std::optional<AvailableMemory> left = available_host_memory(kOpenClBuildAddressSpace)) {
    const std::string shortfall = memory_shortfall(packed_bytes, *left);
    if (!shortfall.empty()) {
      throw InputError(fmt::format(
          "the operand grid (render.pruning) of the {} of {} operands packs into {} of host memory, {}",
          node_kind_name(union_node.kind), union_node.children.size(), bytes_and_gibibytes(packed_bytes), shortfall));
    }
  }
  PackedGrid packed = pack_grid(grid, records, record_at);
  const std::lock_guard<std::mutex> lock(mutex);
  last_key = key;
  last = packed;
  return packed;
}

void GridEmission::emit(const Node& union_node, int first_id, const Material& color, const glm::dvec3& offset,
                        bool gate_subtrees, const MaterialLayout& materials, Literals& lit) {
  // Each operand's code, its literals left open: operands whose code reads alike share a shape.
  std::map<std::string, std::uint32_t> distance_ids, color_ids;
  std::vector<std::string> distance_shapes, color_shapes;
  const auto shape_of = [](std::map<std::string, std::uint32_t>& ids, std::vector<std::string>& shapes,
                           std::string code) {
    const auto [it, added] = ids.emplace(std::move(code), static_cast<std::uint32_t>(shapes.size()));
    if (added) shapes.push_back(it->first);
    return it->second;
  };
  std::vector<float> records;
  std::vector<std::uint32_t> record_at;
  record_at.reserve(union_node.children.size());
  const std::vector<int> firsts = child_first_ids(union_node, first_id);
  const IdNumbering record_ids{true, "(float)as_int(SCENE_DATA[at + CLMARCH_GRID_RECORD_ID])"};
  for (std::size_t i = 0; i < union_node.children.size(); ++i) {
    const Node& operand = union_node.children[i];
    Literals distance_literals, color_literals;
    // An operand's code is one function for all its copies in the grid, so no groups by place.
    const SubtreeGates gates = gate_subtrees ? SubtreeGates::Subtrees : SubtreeGates::None;
    SdfEmitter distance(false, gates, distance_literals);
    const SdfEmitter::Value d = distance.emit(operand, "p", color, offset);
    SdfEmitter colored(true, gates, color_literals, nullptr, record_ids, materials);
    if (color.pattern) colored.set_pattern_frame("p", offset);
    const SdfEmitter::Value c = colored.emit(operand, "p", color, offset);
    const std::uint32_t distance_shape =
        shape_of(distance_ids, distance_shapes, distance.body() + fmt::format("  return {};\n", d.distance));
    const std::uint32_t color_shape = shape_of(
        color_ids, color_shapes,
        colored.body() +
            fmt::format("  *albedo = {};\n  *surface = {};\n  *emission = {};\n  *id = {};\n  return {};\n", c.color,
                        c.surface, c.emission.empty() ? "v3_splat(0.0f)" : c.emission, c.id, c.distance));
    const std::vector<float> distance_values = distance_literals.take(), color_values = color_literals.take();
    record_at.push_back(static_cast<std::uint32_t>(records.size()));
    records.push_back(int_word(distance_shape));
    records.push_back(int_word(color_shape));
    records.push_back(int_word(static_cast<std::uint32_t>(CLMARCH_GRID_RECORD_WORDS + distance_values.size())));
    records.push_back(int_word(static_cast<std::uint32_t>(firsts[i])));
    records.insert(records.end(), distance_values.begin(), distance_values.end());
    records.insert(records.end(), color_values.begin(), color_values.end());
  }
  std::uint64_t key = 0xcbf29ce484222325ULL;
  key = fnv1a(key, records.data(), records.size() * sizeof(float));
  for (const std::string& shape : distance_shapes) key = fnv1a(key, shape.data(), shape.size());
  const double k_value = is_smooth_operator(union_node.kind) ? smooth_k(union_node) : 0.0;
  const double numbers[] = {static_cast<double>(union_node.kind), k_value, offset.x, offset.y, offset.z};
  key = fnv1a(key, numbers, sizeof(numbers));
  const PackedGrid grid = packed_grid_for(union_node, offset, key, records, record_at);
  data = grid.data;

  const std::string k = lit.f(k_value);
  functions = fmt::format(
      "/* The {} of {} operands evaluated from its operand grid ({} x {} x {} cells, {:.1f} operands a cell on\n"
      " * average; host/prune/operand_grid.hpp). Each operand's numbers are in its record, read by its\n"
      " * shape's code ({} shapes). */\n",
      node_kind_name(union_node.kind), union_node.children.size(), grid.dims.x, grid.dims.y, grid.dims.z,
      static_cast<double>(grid.listed) / static_cast<double>(grid.cells), distance_shapes.size());
  functions +=
      fmt::format("#define GRID_COMBINE(a, b) {}\n", SdfEmitter::combine_rule(union_node.kind, "(a)", "(b)", k));
  functions += fmt::format(
      "#define GRID_BLEND(first, second, a, b) {}\n",
      fmt::format(fmt::runtime(SdfEmitter::blend_rule(union_node.kind, "(a)", "(b)", k)), "(first)", "(second)"));
  functions += fmt::format("#define GRID_ID_BLEND(first, second, a, b) {}\n",
                           fmt::format(fmt::runtime(SdfEmitter::blend_rule(union_node.kind, "(a)", "(b)", k, kIdBlend)),
                                       "(first)", "(second)"));
  functions += shape_function("SDF_INLINE vfloat grid_operand_distance(SceneValues values, int at, vec3v p)",
                              "at + CLMARCH_GRID_RECORD_WORDS", "SCENE_DATA[at]", distance_shapes);
  functions += shape_function(
      "SDF_INLINE vfloat grid_operand_color(SceneValues values, int at, vec3v p, vec3v* albedo, vec3v* surface, vec3v* "
      "emission,\n"
      "                                     vfloat* id)",
      "at + as_int(SCENE_DATA[at + 2])", "SCENE_DATA[at + 1]", color_shapes);
  functions += kernel_file("operand_grid.cl");
  functions += "#line 1 \"generated scene\"\n";
  emitted = true;
}

}  // namespace

std::string code_shape(const std::string& source) {
  std::string shape;
  shape.reserve(source.size());
  for (std::size_t at = 0; at < source.size();) {
    if (source.compare(at, 2, "/*") == 0) {
      const std::size_t end = source.find("*/", at + 2);
      at = end == std::string::npos ? source.size() : end + 2;
      continue;
    }
    shape.push_back(source[at++]);
  }
  return shape;
}

std::string Literals::f(double value) {
  // Each value of the file is a float, but numbers made from them (a position relative to the
  // camera's map frame) can pass float's range; OpenCL C would see "inff".
  if (!std::isfinite(static_cast<float>(value))) {
    throw InputError(
        fmt::format("the scene needs the number {:g} in its OpenCL program, beyond float's range (+-{:g}): "
                    "positions too far apart; the CPU reference renders it (--backend reference)",
                    value, std::numeric_limits<float>::max()));
  }
  values_.push_back(static_cast<float>(value));
  rounding_ = std::max(rounding_, std::abs(static_cast<double>(values_.back()) - value));
  return fmt::format("@{}@", values_.size() - 1);
}

std::string Literals::f4(const glm::dvec3& v) {
  // Numbered x, y, z whatever the compiler (it evaluates function arguments in no fixed order).
  const std::string x = f(v.x), y = f(v.y), z = f(v.z);
  return cl_float4_of(x, y, z);
}

std::string Literals::f4(const glm::dvec4& v) {
  const std::string x = f(v.x), y = f(v.y), z = f(v.z), w = f(v.w);
  return cl_float4_of(x, y, z, w);
}

std::string sdf_functions(const Node& root, const glm::dvec3& frame_origin, SubtreeGates gates, Literals& literals,
                          const Node* grid_node, std::shared_ptr<const std::vector<float>>& data, bool with_ids,
                          const MaterialLayout& materials) {
  GridEmission grid;
  grid.node = grid_node;
  // Both walks know the materials: the first to reach the operand grid writes its records.
  SdfEmitter distance_only(false, gates, literals, &grid, {}, materials);
  const SdfEmitter::Value d = distance_only.emit(root, "p", materials.root, frame_origin);
  literals.end_distance();
  SdfEmitter with_color(true, gates, literals, &grid, IdNumbering{with_ids, ""}, materials);
  const SdfEmitter::Value dc = with_color.emit(root, "p", materials.root, frame_origin);
  data = std::move(grid.data);
  const std::string frame =
      frame_origin == glm::dvec3(0.0)
          ? std::string()
          : fmt::format("/* p is relative to the world point ({}, {}, {}) (map_frame_origin). */\n", frame_origin.x,
                        frame_origin.y, frame_origin.z);
  // The operand grid's data can pass the 64 KiB of constant memory that every device has.
  const std::string values_type =
      grid.emitted
          ? "/* Literals of the scene read from the kernel's values buffer (values[j]) instead of spelled\n"
            " * (render.literals, or those an animation changes) let scenes that differ in them share this\n"
            " * program; the operand grid's data follows them (SCENE_DATA), in global memory for its size. */\n"
            "typedef __global const float* SceneValues;\n\n"
          : "/* Literals of the scene read from the kernel's values buffer (values[j]) instead of spelled\n"
            " * (render.literals, or those an animation changes) let scenes that differ in them share this\n"
            " * program. */\n"
            "typedef __constant const float* SceneValues;\n\n";
  return frame + values_type + glsl_functions(root) + grid.functions +
         fmt::format(
             "/* Distance to the scene. */\n"
             "SDF_INLINE vfloat map(SceneValues values, vec3v p) {{\n{}  return {};\n}}\n\n"
             "/* Distance to the scene and the material there: albedo, surface = ({}, reflectivity), the\n"
             " * light it emits{}. */\n"
             "SDF_STAGE vfloat map_color(SceneValues values, vec3v p, vec3v* albedo, vec3v* surface, vec3v* "
             "emission{}) {{\n{}"
             "  *albedo = {};\n  *surface = {};\n  *emission = {};\n{}  return {};\n}}\n",
             distance_only.body(), d.distance,
             materials.model == ShadingModel::Pbr ? "metallic, roughness" : "specular, shininess",
             with_ids ? ", and id, the number of the primitive it is of" : "", with_ids ? ", vfloat* id" : "",
             with_color.body(), dc.color, dc.surface, dc.emission.empty() ? "v3_splat(0.0f)" : dc.emission,
             with_ids ? fmt::format("  *id = {};\n", dc.id) : std::string(), dc.distance);
}

bool takes_absolute_points(const Node& root, const glm::dvec3& frame_origin) {
  if (root.kind == NodeKind::Terrain) {
    // terrain_call's test, on the largest octave's lattice point of the frame origin.
    const Terrain& terrain = params_of<Terrain>(root);
    if (terrain.frequency * glm::length(frame_origin) * std::pow(terrain_lacunarity(terrain), terrain.octaves - 1) >=
        0x1p24) {
      return true;
    }
  }
  return std::any_of(root.children.begin(), root.children.end(),
                     [&](const Node& child) { return takes_absolute_points(child, frame_origin); });
}

SdfCode generate_sdf_code(const Node& root, const glm::dvec3& frame_origin, SubtreeGates gates, const Node* grid_node,
                          bool with_ids, const MaterialLayout& materials) {
  Literals literals;
  SdfCode code;
  code.source = sdf_functions(root, frame_origin, gates, literals, grid_node, code.data, with_ids, materials);
  code.literal_rounding = literals.distance_rounding();
  code.literals = literals.take();
  return code;
}

namespace {

/// Calls visit(text, k) for each run of plain text and each literal mark k of the source, in order.
template <typename Visit>
void for_each_mark(const std::string& source, Visit&& visit) {
  std::size_t at = 0;
  for (std::size_t mark = source.find('@'); mark != std::string::npos; mark = source.find('@', at)) {
    const std::size_t end = source.find('@', mark + 1);
    visit(std::string_view(source).substr(at, mark - at), std::stoul(source.substr(mark + 1, end - mark - 1)));
    at = end + 1;
  }
  visit(std::string_view(source).substr(at), std::string::npos);
}

/// The slots' literals in the order the source first reads them: the program's values[j] is the
/// j-th, so that the dumped source numbers them as it is read.
std::vector<std::size_t> slots_in_reading_order(const SdfCode& code, const ValueSlots& slots) {
  std::vector<bool> is_slot(code.literals.size(), false);
  for (int k : slots) {
    if (k < 0 || static_cast<std::size_t>(k) >= code.literals.size()) {
      throw std::invalid_argument(fmt::format("value slot {} is not a literal of the scene's code", k));
    }
    is_slot[static_cast<std::size_t>(k)] = true;
  }
  std::vector<std::size_t> order;
  for_each_mark(code.source, [&](std::string_view, std::size_t k) {
    if (k != std::string::npos && is_slot[k]) {
      is_slot[k] = false;
      order.push_back(k);
    }
  });
  return order;
}

}  // namespace

std::string spell_sdf_code(const SdfCode& code, const ValueSlots& slots) {
  const std::vector<std::size_t> order = slots_in_reading_order(code, slots);
  std::vector<int> slot_of(code.literals.size(), -1);
  for (std::size_t j = 0; j < order.size(); ++j) slot_of[order[j]] = static_cast<int>(j);
  std::string out;
  if (!order.empty()) {
    out += fmt::format("/* values[0 .. {}]: the literals read from the values buffer. */\n", order.size() - 1);
  }
  if (code.data) out += fmt::format("#define SCENE_DATA (values + {})\n", order.size());
  for_each_mark(code.source, [&](std::string_view text, std::size_t k) {
    out += text;
    if (k == std::string::npos) return;
    out += slot_of[k] >= 0 ? fmt::format("values[{}]", slot_of[k]) : cl_float(code.literals[k]);
  });
  return out;
}

std::vector<float> ProgramValues::joined() const {
  std::vector<float> values = slots;
  if (data) values.insert(values.end(), data->begin(), data->end());
  return values;
}

ProgramValues slot_values(const SdfCode& code, const ValueSlots& slots) {
  ProgramValues values;
  for (std::size_t k : slots_in_reading_order(code, slots)) values.slots.push_back(code.literals[k]);
  values.data = code.data;
  return values;
}

}  // namespace clmarch
