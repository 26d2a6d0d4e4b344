// The scene IR: a validated scene file. The one definition shared by the code generator, the
// OpenCL renderer and the CPU reference; each interprets it on its own.
#pragma once

#include "scene/node_params.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace clmarch {

/// Kinds of SDF nodes, from node_kinds.def.
enum class NodeKind {
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) Kind,
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) Kind,
#include "scene/node_kinds.def"
};

/// Every node kind, in list order (for tests and lookups).
inline constexpr NodeKind kAllNodeKinds[] = {
#define CLMARCH_PRIMITIVE(Kind, name, quality, cost, params_list) NodeKind::Kind,
#define CLMARCH_OPERATOR(Kind, name, min_children, max_children, params_list) NodeKind::Kind,
#include "scene/node_kinds.def"
};

/// The scene-file name of a kind ("smooth_union").
std::string_view node_kind_name(NodeKind kind);
/// The kind with a scene-file name, if any.
std::optional<NodeKind> node_kind_from_name(std::string_view name);
/// True for leaves (primitives), false for operators.
bool is_primitive(NodeKind kind);
/// True for the 2D primitives (profiles in the xy plane, for revolve and extrude).
bool is_profile(NodeKind kind);
/// True for the smooth operators, which take a blend radius k.
bool is_smooth_operator(NodeKind kind);
/// Whether kind is one of node_kinds.def's blends (CLMARCH_BLEND: chamfer, round, stairs, ...).
bool is_blend_operator(NodeKind kind);

/// Radius of a ball about the centre that holds the whole power-n Mandelbulb: 2^(1/(n-1)). Its
/// estimator is never below the distance to this ball (kernels/fractals.cl, the reference).
double mandelbulb_radius(double power);

/// Half the side of the cube centred on the Mandelbox that holds it (fold limit 1): 2 for scales
/// below -1, 2 (scale + 1) / (scale - 1) above 1 (knighty's sizes; tests sample orbits past it).
double mandelbox_half_size(double scale);

/// Radius of a ball about the centre that holds the quaternion Julia set of c: the root R of
/// R^2 - R = |c|, beyond which |z^2 + c| >= |z|^2 - |c| > |z| and every orbit escapes.
double julia_radius(const glm::dvec4& c);

/// The fewest and most children an operator takes (0: no limit), from its declaration.
int min_children(NodeKind kind);
int max_children(NodeKind kind);

/// Placement of a node: p_world = translate + R(rotate) * (scale * p_local).
struct Transform {
  glm::dvec3 translate{0.0};
  /// Euler angles in degrees, applied about x, then y, then z.
  glm::dvec3 rotate_degrees{0.0};
  /// Uniform scale; the distance is multiplied by it (distances stay exact).
  double scale = 1.0;

  bool is_identity() const;
  /// worldFromLocal rotation matrix R.
  glm::dmat3 world_from_local_rotation() const;
};

/// A color that varies over the surface: a function of the point (x, y, z) in the local frame of
/// the node that sets it, so that it moves with the node.
struct ColorPattern {
  enum class Kind { Checker, Stripes, Grid, Expression };
  Kind kind = Kind::Checker;
  /// Checker, stripes, grid: the side of a cell (the period).
  double size = 1.0;
  /// Checker: a where floor(x/size) + floor(y/size) + floor(z/size) is even, b where odd. Stripes:
  /// a where floor(coordinate/size) is even. Grid: the fill, then the lines.
  glm::dvec3 colors[2] = {glm::dvec3(1.0), glm::dvec3(0.0)};
  /// Stripes: the axis across the stripes (0 x, 1 y, 2 z).
  int axis = 0;
  /// Grid: the axes whose multiples of size draw lines (a floor's: x and z), and the lines' width.
  bool grid_axes[3] = {true, false, true};
  double line_width = 0.05;
  /// Expression: r, g and b as expressions of x, y, z and t (muparser syntax, GLSL's functions),
  /// and the t they are evaluated at.
  std::string expressions[3];
  double time = 0.0;
};

/// Material of a surface point: albedo, the PBR parameters, the Phong and Blinn-Phong ones, the
/// mirror's share and the light it emits.
struct Material {
  glm::dvec3 albedo{1.0};
  /// A pattern in place of the albedo, from the node that sets it (a node of the tree, which
  /// outlives the material); null: the albedo.
  const ColorPattern* pattern = nullptr;
  double metallic = 0.0;
  double roughness = 0.5;
  double reflectivity = 0.0;
  /// Phong and Blinn-Phong: the specular weight and exponent (the scene's shading.specular and
  /// shading.shininess where no node sets them: root_material).
  double specular = 0.0;
  double shininess = 32.0;
  /// Light the surface adds whatever lights it (unlit), linear RGB.
  glm::dvec3 emission{0.0};
};

/// One node of the SDF tree.
struct Node {
  NodeKind kind = NodeKind::Sphere;
  /// The parameters of its kind (the alternative at the index of kind).
  NodeParams params;
  /// Operands of an operator, folded left: union(a, b, c) = union(union(a, b), c).
  std::vector<Node> children;
  Transform transform;
  /// Multiplies the node's distance (after its scale), in (0, 1]: makes a field that is not
  /// 1-Lipschitz (terrain, mandelbulb, deep smooth unions) a bound the march cannot overshoot.
  double step_factor = 1.0;
  /// Albedo of this subtree, unless a descendant sets its own: a color, or a pattern of the point.
  std::optional<glm::dvec3> color;
  std::optional<ColorPattern> color_pattern;
  /// PBR metalness in [0, 1] of this subtree (inherited like color; default 0).
  std::optional<double> metallic;
  /// PBR roughness in [0.02, 1] (inherited; default 0.5).
  std::optional<double> roughness;
  /// Share of the mirror bounce added to the color, in [0, 1] (inherited; default 0).
  std::optional<double> reflectivity;
  /// Phong and Blinn-Phong specular weight and exponent (inherited; default the scene's shading's).
  std::optional<double> specular;
  std::optional<double> shininess;
  /// Light emitted, added unlit (inherited; default none).
  std::optional<glm::dvec3> emission;

  /// This node's material: its own settings over the inherited ones.
  Material material_over(const Material& inherited) const;
};

/// The parameters of a node of kind T; throws std::logic_error if the node is of another kind.
template <class T>
const T& params_of(const Node& node) {
  if (const T* p = std::get_if<T>(&node.params)) return *p;
  throw std::logic_error("a node's parameters are not those of its kind");
}
/// The primitives of the subtree: the numbers of the id channel it takes. Primitives are numbered
/// from 0 depth-first in the order of the scene file (an instance file's where it is instanced);
/// operators and modifiers take none, and every copy a repeat makes shares its primitive's number.
int primitive_count(const Node& node);
/// The id channel's value where a ray meets nothing.
inline constexpr float kMissId = -1.0f;
/// The node of a kind with that kind's default parameters (and no children).
Node node_of_kind(NodeKind kind);
/// The parameter table of a kind, in the order of its declaration.
std::vector<ParamSpec> param_table(NodeKind kind);
/// What one evaluation of a primitive costs, in sphere evaluations (its declaration's cost).
int evaluation_cost(const Node& primitive);
/// How a primitive's field relates to the true distance (its declaration's quality).
FieldQuality field_quality(NodeKind primitive);
/// The blend radius k of a smooth operator.
double smooth_k(const Node& node);
/// How much steeper than the distance an operator's result can be, its operands being 1-Lipschitz:
/// sqrt(n) over n children for the blends exact in the plane of the operands' distances (chamfer,
/// round, columns, pipe, engrave: docs/scene-format.md "Blends"), 1 for every other operator.
double operator_lipschitz(const Node& node);

/// Lipschitz constant of a displace node's field, 1 + amplitude * frequency * sqrt(3): its distance
/// is divided by it so the march never steps past the displaced surface.
double displacement_lipschitz(const Node& displace);

/// Camera of the contract in docs/scene-format.md (fov is vertical, in degrees).
struct Camera {
  glm::dvec3 position{-2.0, 4.0, 4.0};
  glm::dvec3 look_at{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fov_degrees = 45.0;
};

/// How surface normals are estimated from the distance field: central differences (6 taps), the
/// tetrahedron (4 taps) or forward differences f(p + h e_i) - f(p) (4 taps).
enum class NormalMethod { Central, Tetrahedral, Forward };
inline constexpr const char* kNormalMethodNames[] = {"central", "tetrahedral", "forward"};

/// When a ray counts as arrived: below epsilon, or below a threshold that grows with depth so it
/// stays a fixed share of a pixel's footprint (the pixel cone).
enum class HitThreshold { Fixed, PixelCone };
inline constexpr const char* kHitThresholdNames[] = {"fixed", "pixel_cone"};

/// Whether the generated map() skips subtrees by their bounding spheres (host/scene/scene_bounds.hpp).
enum class SceneBounds { None, Sphere };
inline constexpr const char* kSceneBoundsNames[] = {"none", "sphere"};
/// What rays are clipped to (render.bounds): nothing, the scene's bounding sphere, or the sphere and
/// the scene's bounding box (host/scene/scene_bounds.hpp, scene_box.hpp).
enum class RayBounds { None, Sphere, Box };
inline constexpr const char* kRayBoundsNames[] = {"none", "sphere", "box"};

/// A coarse pass before the camera rays' march: none, or a cone per block of pixels
/// (CLMARCH_COARSE_BLOCK in kernels/device_types.h) that gives the block's rays a safe start;
/// auto: the cone where the time-against-error sweeps found it pays (uses_cone_pass).
enum class CoarsePass { None, Cone, Auto };
inline constexpr const char* kCoarsePassNames[] = {"none", "cone", "auto"};

/// How a union of many operands is evaluated: from generated code, or from a grid whose cells list
/// only the operands that can change the union there (host/prune/operand_grid.hpp); auto: the grid
/// for the largest union of at least kAutoGridOperands bounded operands.
enum class Pruning { Auto, None, Grid };
inline constexpr const char* kPruningNames[] = {"auto", "none", "grid"};

/// The arithmetic of the march, the distance function and the shading on the device: float, or
/// double (render.precision; cl_khr_fp64), for views finer than float's spacing (deep zooms).
/// Buffers stay float either way.
enum class Precision { Float, Double };
inline constexpr const char* kPrecisionNames[] = {"float", "double"};

/// Where the numbers of the scene's tree (positions, sizes, angles, blend radii, colours, materials)
/// live in its program: spelled into the source (inline: a changed number is a new program), or read
/// from the program's values buffer (buffer: programs are keyed by the tree's shape, so an edited
/// number re-renders from the program built before, in this process or from the driver's cache in
/// the next). auto spells them, measured faster warm (render/prepared_program.hpp).
enum class LiteralPlacement { Auto, Inline, Buffer };
inline constexpr const char* kLiteralPlacementNames[] = {"auto", "inline", "buffer"};

/// Whether the kernels' stages (a march loop, a normal, a shadow ray, a hit's shading and material)
/// are functions called or inlined into the kernel (kernels/lanes.cl): called, a large scene's
/// program compiles in a fraction of the time; inlined, a small one marches faster. auto calls them
/// for scenes whose code is large (codegen/kernel_source.hpp, calls_stages), measured.
enum class KernelStages { Auto, Inline, Called };
inline constexpr const char* kKernelStagesNames[] = {"auto", "inline", "called"};

/// The most samples per pixel render.samples allows.
inline constexpr int kMaxSamples = 1024;

/// Settings of the march itself.
struct RenderSettings {
  int width = 640;
  int height = 360;
  int max_steps = 255;
  /// A ray hits when the distance falls below epsilon.
  double epsilon = 1e-4;
  double max_distance = 100.0;
  NormalMethod normal_method = NormalMethod::Central;
  /// Finite-difference step of the normal estimate.
  double normal_epsilon = 1e-3;
  /// Keinert et al.'s over-relaxation factor omega of camera rays, in [1, 2); 1 = plain sphere
  /// tracing. Empty: auto (the default), omega chosen per scene by camera_over_relaxation.
  std::optional<double> over_relaxation;
  HitThreshold hit_threshold = HitThreshold::Fixed;
  /// pixel_cone: the threshold is max(epsilon, cone_factor * t * pixel angle).
  double cone_factor = 1.0;
  /// sphere: camera, shadow and mirror rays march only inside the bounding sphere of a bounded
  /// scene; box (the default): inside its bounding box too.
  RayBounds bounds = RayBounds::Box;
  /// sphere: unions and subtractions skip an expensive bounded subtree wherever its bounding sphere
  /// shows it cannot change the result (host/codegen/sdf_codegen.cpp).
  SceneBounds subtree_bounds = SceneBounds::Sphere;
  /// cone: camera rays start where their block's cone march stopped (docs/scene-format.md); auto
  /// (the default): the cone for scenes without a bounding sphere or step-count occlusion.
  CoarsePass coarse_pass = CoarsePass::Auto;
  Pruning pruning = Pruning::Auto;
  /// Anti-aliasing: a pixel's color is the mean of up to samples rays at stratified points of its
  /// area (a box filter; host/frame/antialias.hpp); 1 = the centre ray alone.
  int samples = 1;
  /// With samples > 1: only pixels whose neighbourhood shows an edge get more than the centre ray.
  bool adaptive = true;
  Precision precision = Precision::Float;
  LiteralPlacement literals = LiteralPlacement::Auto;
  KernelStages stages = KernelStages::Auto;

  bool operator==(const RenderSettings&) const = default;
};

enum class LightKind { Point, Directional, Spot };

/// How a point or spot light's radiance falls with the distance d: not at all, or as 1 / d^2.
enum class Falloff { None, InverseSquare };
inline constexpr const char* kFalloffNames[] = {"none", "inverse_square"};

struct Light {
  LightKind kind = LightKind::Point;
  /// Point and spot lights: where the light is.
  glm::dvec3 position{0.0};
  /// Directional lights: unit vector from the surface towards the light.
  glm::dvec3 direction{0.0, 1.0, 0.0};
  /// Spot lights: unit vector the light points along (from the light into the scene).
  glm::dvec3 axis{0.0, -1.0, 0.0};
  /// Spot lights: degrees from the axis to the edge of the full light (inner) and of any light
  /// (outer), 0 <= inner <= outer < 180; smoothstep between (reference/reference_shading.hpp, light_reach).
  double inner_angle = 20.0;
  double outer_angle = 30.0;
  glm::dvec3 color{1.0};
  double intensity = 1.0;
  Falloff falloff = Falloff::None;
  /// Point and spot lights: the distance where the light ends, windowed smoothly (Karis:
  /// clamp(1 - (d / range)^4, 0, 1)^2); none: it reaches everywhere.
  std::optional<double> range;
  /// Whether the light casts shadows (the scene's shading.shadows then marches towards it).
  bool shadows = true;

  /// Whether its radiance depends on where the surface is (falloff, range or a spot's cone).
  bool shaped() const { return kind == LightKind::Spot || falloff != Falloff::None || range.has_value(); }
};

enum class ShadingModel { Lambert, Phong, BlinnPhong, Pbr };
inline constexpr const char* kShadingModelNames[] = {"lambert", "phong", "blinn_phong", "pbr"};

enum class ShadowMode { Hard, Soft, SoftImproved };
inline constexpr const char* kShadowModeNames[] = {"hard", "soft", "soft_improved"};

/// Shadows by marching from the surface towards each light (Inigo Quilez's soft shadows).
struct Shadows {
  ShadowMode mode = ShadowMode::Soft;
  /// Penumbra sharpness k of the soft modes.
  double k = 16.0;
  /// The shadow ray starts min_t from the surface and, for directional lights, ends at max_t.
  double min_t = 0.01;
  double max_t = 20.0;
  int max_steps = 64;
};

/// Ambient occlusion by marching along the normal (the PBR course): 1 - sum (i step - sdf)^2 / i,
/// raised to power.
struct NormalOcclusion {
  int samples = 5;
  double step = 0.05;
  double power = 1.0;
};

/// A sky gradient for misses, from horizon (ray level or below) to zenith (straight up).
struct Sky {
  glm::dvec3 horizon{0.7, 0.8, 1.0};
  glm::dvec3 zenith{0.2, 0.4, 0.8};
};

/// Crum's glow of misses: color * (1 - closest / radius)^2 where the ray passed within radius.
struct Glow {
  glm::dvec3 color{1.0};
  double radius = 0.1;
};

/// Inigo Quilez's height fog, denser near the ground and tinted towards the sun.
struct HeightFog {
  double density = 0.1;
  double falloff = 0.5;
  glm::dvec3 color{0.5, 0.6, 0.7};
  glm::dvec3 sun_color{1.0, 0.9, 0.7};
  /// Unit vector towards the sun.
  glm::dvec3 sun_direction{0.0, 1.0, 0.0};
  double sun_power = 8.0;
};

/// A scattering glow of the sky at the horizon and towards the sun (the Martian landscape).
struct PlanetaryGlow {
  glm::dvec3 color{1.0, 0.5, 0.3};
  double sharpness = 8.0;
  /// Unit vector towards the sun.
  glm::dvec3 sun_direction{0.0, 1.0, 0.0};
};

enum class ToneMap { None, Reinhard };
inline constexpr const char* kToneMapNames[] = {"none", "reinhard"};

/// What the color image shows: the lit scene or one of the debug views.
enum class View { Shaded, Normals, Depth, Steps, Samples, Status };
inline constexpr const char* kViewNames[] = {"shaded", "normals", "depth", "steps", "samples", "status"};

/// Beer-Lambert fog on hits: color = mix(fog color, color, exp(-density * depth)).
struct Fog {
  glm::dvec3 color{1.0};
  double density = 0.1;
};

/// Lighting model and the look of misses.
struct Shading {
  ShadingModel model = ShadingModel::Lambert;
  glm::dvec3 ambient{0.1};
  double diffuse = 1.0;
  double specular = 0.0;
  double shininess = 32.0;
  /// Step-count ambient occlusion (Crum): subtracts steps^2 / step_ao from each channel; 0 = off.
  double step_ao = 0.0;
  glm::dvec3 background{0.0};
  std::optional<Fog> fog;
  std::optional<Shadows> shadows;
  std::optional<NormalOcclusion> ambient_occlusion;
  std::optional<Sky> sky;
  std::optional<Glow> glow;
  std::optional<HeightFog> height_fog;
  std::optional<PlanetaryGlow> planetary_glow;
  /// Mirror bounces for surfaces with reflectivity > 0; 0 = none.
  int reflection_bounces = 0;
  ToneMap tone_map = ToneMap::None;
  /// Display gamma applied after tone mapping (c^(1/gamma)); 1 = none. 8-bit outputs are
  /// sRGB-encoded on top of this.
  double gamma = 1.0;
  View view = View::Shaded;
};

enum class TilingMethod { Cells, Mod };
inline constexpr const char* kTilingMethodNames[] = {"cells", "mod"};

/// Infinite repetition of the whole tree, written in cell-local coordinates 0 <= p < cell.
struct Tiling {
  glm::dvec3 cell{1.0};
  /// cells: unit-cell traversal (march inside one cell, step to its wall, wrap); mod: the cheap
  /// modulo of the sample point.
  TilingMethod method = TilingMethod::Cells;
};

/// How far a mirror bounce starts off the surface along the normal: clear of the hit threshold and
/// of the normal estimate's step, so the reflected ray does not hit its own start.
double reflection_offset(const RenderSettings& render);

/// Growth of the camera rays' hit threshold per unit of depth: cone_factor * 2 tan(fov / 2) / height
/// (the angle one pixel subtends at the image centre) with the pixel cone, 0 with the fixed threshold.
double hit_cone_slope(const RenderSettings& render, const Camera& camera);

/// A whole scene file after loading and validation.
struct Scene {
  /// File name, for messages.
  std::string source_name;
  Camera camera;
  RenderSettings render;
  Node sdf;
  std::vector<Light> lights;
  Shading shading;
  /// Absent: the scene is not repeated.
  std::optional<Tiling> tiling;
  /// The time t (seconds) at which expressions in the file were evaluated.
  double time = 0.0;
  /// Whether a number of the scene is an expression that changes with t.
  bool animated = false;
  /// The instance files the scene read its rows from (paths as opened), besides the scene file.
  std::vector<std::string> instance_files;
  /// Where render.width/height were set ("file:line:col", "file (--set)"), for checks made after
  /// loading (host memory); empty when both are the defaults.
  std::string size_origin;
};

/// Whether camera rays walk the unit cells (tiling.method: cells) rather than a plain march.
inline bool uses_cells_tiling(const Scene& scene) {
  return scene.tiling && scene.tiling->method == TilingMethod::Cells;
}

/// The over-relaxation of render.over_relaxation: for auto, omega = kAutoOverRelaxation, except
/// plain sphere tracing (1) where it did not pay or would change the picture: scenes shaded by
/// step-count occlusion, whose step counts it shortens, and the cells tiling.
inline constexpr double kAutoOverRelaxation = 1.2;
double camera_over_relaxation(const Scene& scene);

/// The material the tree's root inherits: Material's defaults, with the scene's shading.specular
/// and shading.shininess.
Material root_material(const Scene& scene);
/// Whether a node of the tree emits light (emission set, and not black): the EMISSION feature.
bool uses_emission(const Node& node);
/// Whether a node of the tree sets a color pattern (kernels/patterns.cl).
bool uses_patterns(const Node& node);

}  // namespace clmarch
