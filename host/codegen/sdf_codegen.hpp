// Turns a scene's SDF tree into OpenCL C: map(values, p), the distance, and map_color(values, p,
// &albedo, &surface), the distance with the blended material, calling the functions of
// kernels/primitives.cl and operators.cl.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace clmarch {

/// Generated code with its float literals left open: the frames of an animation share one program
/// when their code differs only in values, which the program then reads from its values buffer
/// (SceneValues values) instead of spelling them.
struct SdfCode {
  /// The source, with "@k@" where literal k goes.
  std::string source;
  /// Every float literal of the code, rounded to float, by index.
  std::vector<float> literals;
  /// The largest |float(x) - x| of the distance function's literals: how far the program's
  /// geometry is from the scene's where it computes in double (render.precision; the literals stay
  /// float).
  double literal_rounding = 0.0;
  /// The operand grid's data, which the code reads after the values of its slots (SCENE_DATA);
  /// null without a grid. Shared with the grid's cache, not copied: a million operands' grid is
  /// half a gigabyte.
  std::shared_ptr<const std::vector<float>> data;
};

/// The source without its comments, which spell numbers for the reader (the map frame's origin, an
/// operand grid's cells) that change no program: what decides whether frames share one.
std::string code_shape(const std::string& source);

/// Writes float literals as their marks "@k@" and keeps their values, for SdfCode.
class Literals {
 public:
  /// The mark of a new literal: value rounded to float.
  std::string f(double value);
  /// A float4 of three new literals and w = 0.
  std::string f4(const glm::dvec3& v);
  /// A float4 of four new literals.
  std::string f4(const glm::dvec4& v);
  /// The values by index; leaves this empty.
  std::vector<float> take() { return std::move(values_); }
  /// Marks the values written so far as the distance function's (map(), which comes first).
  void end_distance() { distance_rounding_ = rounding_; }
  /// The largest |float(x) - x| of the distance function's values (end_distance).
  double distance_rounding() const { return distance_rounding_; }

 private:
  std::vector<float> values_;
  double rounding_ = 0.0;
  double distance_rounding_ = 0.0;
};

/// How map_color lays out the materials it returns: the root's (whose specular and shininess are
/// the scene's), the shading model, which picks the surface vector's two numbers (PBR: metallic,
/// roughness; the others: specular, shininess), and whether any node emits (EMISSION: else
/// map_color's emission is 0 and no node carries one).
struct MaterialLayout {
  Material root;
  ShadingModel model = ShadingModel::Lambert;
  bool emission = false;
};

/// What the generated map() skips behind bounding spheres (render.subtree_bounds, docs/scene-format.md
/// "Subtree bounds"): nothing; expensive subtrees; or also a union's cheap bounded children grouped by
/// place. The groups follow where the children are, so a moved child can change the code's shape:
/// only for numbers that are spelled (subtree_gates(), kernel_source.hpp).
enum class SubtreeGates { None, Subtrees, SubtreesAndPlaces };

/// map and map_color for this tree, their literals written to literals and the operand grid's data
/// to data (see generate_sdf_code).
std::string sdf_functions(const Node& root, const glm::dvec3& frame_origin, SubtreeGates gates, Literals& literals,
                          const Node* grid_node, std::shared_ptr<const std::vector<float>>& data, bool with_ids,
                          const MaterialLayout& materials);

/// Whether the generated map() of this tree, measured from frame_origin, takes absolute world points
/// somewhere (the point plus the frame origin, in float: a terrain whose octaves' lattice points
/// there pass float's integers), so that its accuracy is the world coordinates' rather than the
/// frame's.
bool takes_absolute_points(const Node& root, const glm::dvec3& frame_origin);

/// The code of map and map_color for this tree, taking points relative to the world point
/// frame_origin (its positions are baked relative to it, in double). With gates, unions and
/// subtractions evaluate an expensive bounded subtree only where its bounding sphere shows it can
/// change their result, and (SubtreesAndPlaces) map() groups a union's cheap children by place. grid_node, a union of
/// root's tree (grid_union), is evaluated from its operand grid rather than from code of every operand. With ids,
/// map_color also returns the number of the primitive whose material it gives (the id channel; scene/scene.hpp,
/// primitive_count), spelled in the code, so that literals keep their indices with and without.
SdfCode generate_sdf_code(const Node& root, const glm::dvec3& frame_origin = glm::dvec3(0.0),
                          SubtreeGates gates = SubtreeGates::SubtreesAndPlaces, const Node* grid_node = nullptr,
                          bool with_ids = false, const MaterialLayout& materials = {});

/// Indices into SdfCode::literals, ascending: the literals a program reads from its values
/// (values[j] is the j-th of them that the source reads, in the source's order).
using ValueSlots = std::vector<int>;

/// The source as it is built: each literal spelled exactly, except those of slots (values[j]).
/// Throws std::invalid_argument for a slot that is no literal of the code.
std::string spell_sdf_code(const SdfCode& code, const ValueSlots& slots = {});

/// What a program's values buffer holds: values[j] is its literals at slots, in the order the
/// source reads them, then the operand grid's data, kept apart so that it is never copied on the
/// host (written to the device from the grid's cache).
struct ProgramValues {
  std::vector<float> slots;
  std::shared_ptr<const std::vector<float>> data;

  std::size_t size() const { return slots.size() + (data ? data->size() : 0); }
  /// The slots then the data, as one vector.
  std::vector<float> joined() const;
};

/// The values of this code's program with these slots.
ProgramValues slot_values(const SdfCode& code, const ValueSlots& slots);

}  // namespace clmarch
