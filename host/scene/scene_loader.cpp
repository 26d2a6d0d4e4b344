// Scene files: schema, defaults and ranges (documented key by key in docs/scene-format.md).
#include "scene/scene_loader.hpp"

#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/nearest_name.hpp"
#include "scene/color_pattern_reader.hpp"
#include "scene/glsl_node_reader.hpp"
#include "scene/instance_file.hpp"
#include "scene/scene_bounds.hpp"
#include "scene/yaml_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <type_traits>
#include <unordered_set>
#include <variant>

namespace clmarch {
namespace {

/// Whether user code reads the time (iTime, iFrame): its scene is then an animation.
bool uses_time(const glsl::Module& module) {
  for (const glsl::Variable& variable : module.variables) {
    if (variable.uniform == glsl::UniformKind::Time || variable.uniform == glsl::UniformKind::Frame) return true;
  }
  return false;
}

constexpr int kMaxStepBudget = 1000000;

// Keys every SDF node accepts besides its own parameters.
#define CLMARCH_COMMON_NODE_KEYS                                                                                \
  "color", "metallic", "roughness", "reflectivity", "specular", "shininess", "emission", "translate", "rotate", \
      "scale", "step_factor"

class SceneReader {
 public:
  SceneReader(const std::string& source_name, double time) : yaml_(source_name, time), source_name_(source_name) {
    glsl_context_.scene_file = source_name;
  }

  Scene read(const YAML::Node& root, const std::string& source_name) {
    Scene scene;
    scene.source_name = source_name;
    yaml_.set_document(root);
    yaml_.expect_map(root, "the scene", {"description", "camera", "render", "sdf", "lights", "shading", "tiling"});
    if (const YAML::Node description = root["description"]) yaml_.text(description, "description");
    if (const YAML::Node camera = root["camera"]) scene.camera = read_camera(camera);
    if (const YAML::Node render = root["render"]) {
      scene.render = read_render(render);
      glsl_context_.width = scene.render.width;
      glsl_context_.height = scene.render.height;
      if (const YAML::Node side = render["width"] ? render["width"] : render["height"])
        scene.size_origin = yaml_.where(side);
    }
    scene.sdf = read_node(yaml_.required(root, "sdf", "sdf (the distance field tree)"), "sdf", 1);
    bool asks_for_shadows = false;
    if (const YAML::Node lights = root["lights"]) scene.lights = read_lights(lights, asks_for_shadows);
    if (const YAML::Node shading = root["shading"]) scene.shading = read_shading(shading);
    // A light's shadows: true switches shadows on with their defaults where shading has none.
    if (asks_for_shadows && !scene.shading.shadows) scene.shading.shadows = Shadows{};
    if (const YAML::Node tiling = root["tiling"]) {
      scene.tiling = read_tiling(tiling);
      if (uses_cells_tiling(scene) && scene.render.coarse_pass == CoarsePass::Cone) {
        yaml_.fail(root["render"]["coarse_pass"],
                   "render.coarse_pass: cone does not combine with tiling.method: cells (its march keeps to one cell "
                   "at a time); "
                   "use method: mod or coarse_pass: none");
      }
    }
    scene.animated = yaml_.read_time();
    scene.instance_files = instance_files_;
    return scene;
  }

 private:
  Camera read_camera(const YAML::Node& node) {
    Camera camera;
    yaml_.expect_map(node, "camera", {"position", "look_at", "up", "fov"});
    yaml_.optional_vec3(node, "position", "camera.position", camera.position);
    yaml_.optional_vec3(node, "look_at", "camera.look_at", camera.look_at);
    yaml_.optional_vec3(node, "up", "camera.up", camera.up);
    yaml_.optional_number(node, "fov", "camera.fov", camera.fov_degrees, Range::open(0.0, 180.0));
    const glm::dvec3 view = camera.look_at - camera.position;
    if (glm::length(view) == 0.0) yaml_.fail(node, "camera.look_at must differ from camera.position");
    const double sine =
        glm::length(glm::cross(glm::normalize(view), camera.up)) / std::max(glm::length(camera.up), 1e-300);
    if (glm::length(camera.up) == 0.0 || sine < 1e-9) {
      yaml_.fail(node, "camera.up must not be zero or parallel to the view direction (look_at - position)");
    }
    return camera;
  }

  RenderSettings read_render(const YAML::Node& node) {
    RenderSettings render;
    yaml_.expect_map(node, "render",
                     {"width", "height", "max_steps", "epsilon", "max_distance", "normal_method", "normal_epsilon",
                      "over_relaxation", "hit_threshold", "cone_factor", "bounds", "subtree_bounds", "coarse_pass",
                      "pruning", "samples", "adaptive", "precision", "literals", "stages"});
    const Range side = Range::closed(1, kMaxImageSide);
    if (node["width"]) render.width = yaml_.integer(node["width"], "render.width", side);
    if (node["height"]) render.height = yaml_.integer(node["height"], "render.height", side);
    if (node["max_steps"])
      render.max_steps = yaml_.integer(node["max_steps"], "render.max_steps", Range::closed(1, kMaxStepBudget));
    yaml_.optional_number(node, "epsilon", "render.epsilon", render.epsilon, Range::positive());
    yaml_.optional_number(node, "max_distance", "render.max_distance", render.max_distance, Range::positive());
    if (node["normal_method"]) {
      render.normal_method =
          static_cast<NormalMethod>(yaml_.choice(node["normal_method"], "render.normal_method", kNormalMethodNames));
    }
    yaml_.optional_number(node, "normal_epsilon", "render.normal_epsilon", render.normal_epsilon, Range::positive());
    read_march_acceleration(node, render);
    if (node["bounds"])
      render.bounds = static_cast<RayBounds>(yaml_.choice(node["bounds"], "render.bounds", kRayBoundsNames));
    if (node["subtree_bounds"]) {
      render.subtree_bounds =
          static_cast<SceneBounds>(yaml_.choice(node["subtree_bounds"], "render.subtree_bounds", kSceneBoundsNames));
    }
    if (node["pruning"])
      render.pruning = static_cast<Pruning>(yaml_.choice(node["pruning"], "render.pruning", kPruningNames));
    if (node["coarse_pass"]) {
      render.coarse_pass =
          static_cast<CoarsePass>(yaml_.choice(node["coarse_pass"], "render.coarse_pass", kCoarsePassNames));
    }
    if (node["samples"])
      render.samples = yaml_.integer(node["samples"], "render.samples", Range::closed(1, kMaxSamples));
    if (node["adaptive"]) render.adaptive = yaml_.boolean(node["adaptive"], "render.adaptive");
    if (node["precision"])
      render.precision = static_cast<Precision>(yaml_.choice(node["precision"], "render.precision", kPrecisionNames));
    if (node["literals"])
      render.literals =
          static_cast<LiteralPlacement>(yaml_.choice(node["literals"], "render.literals", kLiteralPlacementNames));
    if (node["stages"])
      render.stages = static_cast<KernelStages>(yaml_.choice(node["stages"], "render.stages", kKernelStagesNames));
    if (!image_size_fits(render.width, render.height)) {
      yaml_.fail(node,
                 fmt::format("render.width x render.height = {} x {} exceeds {} pixels (got {}, expected at most {})",
                             render.width, render.height, kMaxPixels,
                             static_cast<long long>(render.width) * render.height, kMaxPixels));
    }
    return render;
  }

  /// A number in [1, 2), or auto (empty). A bare word other than auto and the time t is a misspelt
  /// name rather than an expression, so its error names the choices.
  std::optional<double> read_over_relaxation(const YAML::Node& omega) const {
    const Range below_two{1.0, 2.0, false, true};
    if (!omega.IsScalar()) return yaml_.number(omega, "render.over_relaxation", below_two);
    const std::string& text = omega.Scalar();
    if (text == "auto") return std::nullopt;
    const auto letter = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
    const bool bare_word = !text.empty() && std::all_of(text.begin(), text.end(), letter);
    if (bare_word && text != "t") {
      yaml_.fail(omega, fmt::format("render.over_relaxation must be a number in [1, 2) or auto (got '{}')", text));
    }
    return yaml_.number(omega, "render.over_relaxation", below_two);
  }

  /// over_relaxation, hit_threshold and cone_factor; cone_factor without the pixel cone is unused,
  /// so an error like an unknown key.
  void read_march_acceleration(const YAML::Node& node, RenderSettings& render) {
    if (const YAML::Node omega = node["over_relaxation"]) render.over_relaxation = read_over_relaxation(omega);
    if (node["hit_threshold"]) {
      render.hit_threshold =
          static_cast<HitThreshold>(yaml_.choice(node["hit_threshold"], "render.hit_threshold", kHitThresholdNames));
    }
    yaml_.optional_number(node, "cone_factor", "render.cone_factor", render.cone_factor, Range::positive());
    if (node["cone_factor"] && render.hit_threshold != HitThreshold::PixelCone) {
      yaml_.fail(node["cone_factor"], "render.cone_factor applies only with render.hit_threshold: pixel_cone");
    }
  }

  /// The lights; asks_for_shadows is set when one says shadows: true.
  std::vector<Light> read_lights(const YAML::Node& node, bool& asks_for_shadows) {
    if (!node.IsSequence()) yaml_.fail(node, fmt::format("lights must be a list (got {})", describe_yaml(node)));
    if (node.size() > static_cast<std::size_t>(kMaxLights)) {
      yaml_.fail(node,
                 fmt::format("lights has too many entries (got {}, expected at most {})", node.size(), kMaxLights));
    }
    std::vector<Light> lights;
    for (std::size_t i = 0; i < node.size(); ++i) {
      const YAML::Node entry = node[i];
      const std::string what = fmt::format("lights[{}]", i);
      yaml_.expect_map(entry, what, {"point", "directional", "spot"});
      if (entry.size() != 1) yaml_.fail(entry, what + " must have exactly one key: point, directional or spot");
      Light light;
      const auto kind = entry.begin();
      const std::string kind_name = kind->first.Scalar();
      const YAML::Node params = kind->second;
      const std::string path = fmt::format("{}.{}", what, kind_name);
      if (kind_name == "directional") {
        light.kind = LightKind::Directional;
        yaml_.expect_map(params, path, {"direction", "color", "intensity", "shadows"});
        light.direction = unit_vector(yaml_.required(params, "direction", path + ".direction"), path + ".direction");
      } else {
        light.kind = kind_name == "point" ? LightKind::Point : LightKind::Spot;
        if (light.kind == LightKind::Point) {
          yaml_.expect_map(params, path, {"position", "color", "intensity", "falloff", "range", "shadows"});
        } else {
          yaml_.expect_map(params, path,
                           {"position", "direction", "inner_angle", "outer_angle", "color", "intensity", "falloff",
                            "range", "shadows"});
          read_spot_cone(params, path, light);
        }
        light.position = yaml_.vec3(yaml_.required(params, "position", path + ".position"), path + ".position");
        if (const YAML::Node falloff = params["falloff"])
          light.falloff = static_cast<Falloff>(yaml_.choice(falloff, path + ".falloff", kFalloffNames));
        if (const YAML::Node range = params["range"])
          light.range = yaml_.number(range, path + ".range", Range::positive());
      }
      if (params["color"]) light.color = yaml_.color(params["color"], path + ".color");
      yaml_.optional_number(params, "intensity", path + ".intensity", light.intensity, Range::non_negative());
      if (const YAML::Node shadows = params["shadows"]) {
        light.shadows = yaml_.boolean(shadows, path + ".shadows");
        asks_for_shadows = asks_for_shadows || light.shadows;
      }
      lights.push_back(light);
    }
    return lights;
  }

  /// A spot light's axis and cone: direction (where it points, required) and the angles from the
  /// axis to the cone's edges, in degrees.
  void read_spot_cone(const YAML::Node& params, const std::string& path, Light& light) {
    light.axis = unit_vector(yaml_.required(params, "direction", path + ".direction"), path + ".direction");
    yaml_.optional_number(params, "outer_angle", path + ".outer_angle", light.outer_angle, Range::open(0.0, 180.0));
    yaml_.optional_number(params, "inner_angle", path + ".inner_angle", light.inner_angle,
                          Range::closed(0.0, light.outer_angle));
    if (!params["inner_angle"] && light.inner_angle > light.outer_angle) light.inner_angle = light.outer_angle;
  }

  Tiling read_tiling(const YAML::Node& node) {
    Tiling tiling;
    yaml_.expect_map(node, "tiling", {"cell", "method"});
    yaml_.optional_vec3(node, "cell", "tiling.cell", tiling.cell, Range::positive());
    if (node["method"])
      tiling.method = static_cast<TilingMethod>(yaml_.choice(node["method"], "tiling.method", kTilingMethodNames));
    return tiling;
  }

  Fog read_fog(const YAML::Node& node) {
    Fog fog;
    yaml_.expect_map(node, "shading.fog", {"color", "density"});
    if (node["color"]) fog.color = yaml_.color(node["color"], "shading.fog.color");
    yaml_.optional_number(node, "density", "shading.fog.density", fog.density, Range::non_negative());
    return fog;
  }

  glm::dvec3 unit_vector(const YAML::Node& node, const std::string& what) {
    const glm::dvec3 v = yaml_.vec3(node, what);
    if (glm::length(v) == 0.0) yaml_.fail(node, what + " must not be zero");
    return glm::normalize(v);
  }

  Shadows read_shadows(const YAML::Node& node) {
    Shadows shadows;
    yaml_.expect_map(node, "shading.shadows", {"mode", "k", "min_t", "max_t", "max_steps"});
    if (node["mode"])
      shadows.mode = static_cast<ShadowMode>(yaml_.choice(node["mode"], "shading.shadows.mode", kShadowModeNames));
    yaml_.optional_number(node, "k", "shading.shadows.k", shadows.k, Range::positive());
    yaml_.optional_number(node, "min_t", "shading.shadows.min_t", shadows.min_t, Range::non_negative());
    yaml_.optional_number(node, "max_t", "shading.shadows.max_t", shadows.max_t, Range::positive());
    if (node["max_steps"])
      shadows.max_steps = yaml_.integer(node["max_steps"], "shading.shadows.max_steps", Range::closed(1, 10000));
    return shadows;
  }

  NormalOcclusion read_occlusion(const YAML::Node& node) {
    NormalOcclusion ao;
    yaml_.expect_map(node, "shading.ambient_occlusion", {"samples", "step", "power"});
    if (node["samples"])
      ao.samples = yaml_.integer(node["samples"], "shading.ambient_occlusion.samples", Range::closed(1, 64));
    yaml_.optional_number(node, "step", "shading.ambient_occlusion.step", ao.step, Range::positive());
    yaml_.optional_number(node, "power", "shading.ambient_occlusion.power", ao.power, Range::positive());
    return ao;
  }

  Sky read_sky(const YAML::Node& node) {
    Sky sky;
    yaml_.expect_map(node, "shading.sky", {"horizon", "zenith"});
    if (node["horizon"]) sky.horizon = yaml_.color(node["horizon"], "shading.sky.horizon");
    if (node["zenith"]) sky.zenith = yaml_.color(node["zenith"], "shading.sky.zenith");
    return sky;
  }

  Glow read_glow(const YAML::Node& node) {
    Glow glow;
    yaml_.expect_map(node, "shading.glow", {"color", "radius"});
    if (node["color"]) glow.color = yaml_.color(node["color"], "shading.glow.color");
    yaml_.optional_number(node, "radius", "shading.glow.radius", glow.radius, Range::positive());
    return glow;
  }

  HeightFog read_height_fog(const YAML::Node& node) {
    HeightFog fog;
    const std::string w = "shading.height_fog";
    yaml_.expect_map(node, w, {"density", "falloff", "color", "sun_color", "sun_direction", "sun_power"});
    yaml_.optional_number(node, "density", w + ".density", fog.density, Range::non_negative());
    yaml_.optional_number(node, "falloff", w + ".falloff", fog.falloff, Range::positive());
    if (node["color"]) fog.color = yaml_.color(node["color"], w + ".color");
    if (node["sun_color"]) fog.sun_color = yaml_.color(node["sun_color"], w + ".sun_color");
    if (node["sun_direction"]) fog.sun_direction = unit_vector(node["sun_direction"], w + ".sun_direction");
    yaml_.optional_number(node, "sun_power", w + ".sun_power", fog.sun_power, Range::positive());
    return fog;
  }

  PlanetaryGlow read_planetary_glow(const YAML::Node& node) {
    PlanetaryGlow glow;
    const std::string w = "shading.planetary_glow";
    yaml_.expect_map(node, w, {"color", "sharpness", "sun_direction"});
    if (node["color"]) glow.color = yaml_.color(node["color"], w + ".color");
    yaml_.optional_number(node, "sharpness", w + ".sharpness", glow.sharpness, Range::positive());
    if (node["sun_direction"]) glow.sun_direction = unit_vector(node["sun_direction"], w + ".sun_direction");
    return glow;
  }

  Shading read_shading(const YAML::Node& node) {
    Shading shading;
    yaml_.expect_map(node, "shading",
                     {"model", "ambient", "diffuse", "specular", "shininess", "step_ao", "background", "fog", "shadows",
                      "ambient_occlusion", "sky", "glow", "height_fog", "planetary_glow", "reflections", "tone_map",
                      "gamma", "view"});
    if (node["fog"]) shading.fog = read_fog(node["fog"]);
    if (node["shadows"]) shading.shadows = read_shadows(node["shadows"]);
    if (node["ambient_occlusion"]) shading.ambient_occlusion = read_occlusion(node["ambient_occlusion"]);
    if (node["sky"]) shading.sky = read_sky(node["sky"]);
    if (node["glow"]) shading.glow = read_glow(node["glow"]);
    if (node["height_fog"]) shading.height_fog = read_height_fog(node["height_fog"]);
    if (node["planetary_glow"]) shading.planetary_glow = read_planetary_glow(node["planetary_glow"]);
    if (node["reflections"])
      shading.reflection_bounces = yaml_.integer(node["reflections"], "shading.reflections", Range::closed(0, 8));
    if (node["tone_map"])
      shading.tone_map = static_cast<ToneMap>(yaml_.choice(node["tone_map"], "shading.tone_map", kToneMapNames));
    yaml_.optional_number(node, "gamma", "shading.gamma", shading.gamma, Range::closed(0.1, 10.0));
    if (node["model"])
      shading.model = static_cast<ShadingModel>(yaml_.choice(node["model"], "shading.model", kShadingModelNames));
    if (node["ambient"]) shading.ambient = yaml_.color(node["ambient"], "shading.ambient");
    yaml_.optional_number(node, "diffuse", "shading.diffuse", shading.diffuse, Range::non_negative());
    yaml_.optional_number(node, "specular", "shading.specular", shading.specular, Range::non_negative());
    yaml_.optional_number(node, "shininess", "shading.shininess", shading.shininess, Range::positive());
    yaml_.optional_number(node, "step_ao", "shading.step_ao", shading.step_ao, Range::non_negative());
    if (node["background"]) shading.background = yaml_.color(node["background"], "shading.background");
    if (node["view"]) shading.view = static_cast<View>(yaml_.choice(node["view"], "shading.view", kViewNames));
    return shading;
  }

  Node read_node(const YAML::Node& yaml, const std::string& path, int depth) {
    if (depth > kMaxTreeDepth) {
      yaml_.fail(yaml, fmt::format("{}: the tree is deeper than {} levels (got level {}, expected at most {}; an alias "
                                   "*name inside its own anchor &name makes an endless tree)",
                                   path, kMaxTreeDepth, depth, kMaxTreeDepth));
    }
    if (++node_count_ > kMaxTreeNodes) {
      yaml_.fail(yaml, fmt::format("{}: the tree has too many nodes (got node {} here, expected at most {})", path,
                                   node_count_, kMaxTreeNodes));
    }
    // Counted on the way in, so that an alias bomb stops after kMaxAliasedNodes nodes: yaml-cpp
    // shares an aliased subtree (one position in the file), and only this walk would expand it.
    if (!yaml.Mark().is_null() && !positions_read_.insert(yaml.Mark().pos).second &&
        ++aliased_nodes_ > kMaxAliasedNodes) {
      yaml_.fail(yaml,
                 fmt::format("{}: the tree has too many nodes through aliases (got aliased node {} here, expected "
                             "at most {}; an alias *name counts its nodes again at every use)",
                             path, aliased_nodes_, kMaxAliasedNodes));
    }
    if (!yaml.IsMap() || yaml.size() != 1) {
      // Blamed on a key that --set added, if any (--set sdf.sphere.radius=1 on a torus adds a kind).
      YAML::Node at = yaml;
      std::vector<std::string> keys;
      for (const auto& entry : yaml) {
        if (!yaml.IsMap()) break;
        keys.push_back(entry.first.Scalar());
        if (entry.first.Mark().is_null() && !yaml.Mark().is_null()) at.reset(entry.first);
      }
      yaml_.fail(
          at,
          fmt::format("{} must be a map with one key naming the node kind, e.g. sphere: {{radius: 1}} (got {})", path,
                      !yaml.IsMap()  ? describe_yaml(yaml)
                      : keys.empty() ? std::string("0 keys")
                                     : fmt::format("{} keys: {}", yaml.size(), fmt::join(keys, ", "))));
    }
    const auto entry = yaml.begin();
    const std::string name = entry->first.Scalar();
    const std::optional<NodeKind> kind = node_kind_from_name(name);
    if (!kind) {
      std::vector<std::string_view> names;
      for (NodeKind k : kAllNodeKinds) names.push_back(node_kind_name(k));
      // Every kind, however long the name before them: a list cut in the middle hides the one wanted.
      yaml_.fail(entry->first, fmt::format("{}: unknown node kind '{}'{}", path, name, did_you_mean(name, names)),
                 fmt::format(" (expected one of: {})", fmt::join(names, ", ")));
    }
    Node node = node_of_kind(*kind);
    const std::string node_path = path + "." + name;
    if (is_primitive(*kind)) {
      read_primitive(node, entry->second, node_path);
    } else {
      read_operator(node, entry->second, node_path, depth);
    }
    return node;
  }

  void read_common(Node& node, const YAML::Node& params, const std::string& path) {
    // A glsl node's color may name its code's colour function, which its program took.
    const bool color_is_code = node.kind == NodeKind::Glsl && params["color"] && names_glsl_function(params["color"]);
    if (params["color"] && !color_is_code) read_node_color(yaml_, params["color"], path + ".color", node);
    if (params["metallic"])
      node.metallic = yaml_.number(params["metallic"], path + ".metallic", Range::closed(0.0, 1.0));
    if (params["roughness"])
      node.roughness = yaml_.number(params["roughness"], path + ".roughness", Range::closed(0.02, 1.0));
    if (params["reflectivity"]) {
      node.reflectivity = yaml_.number(params["reflectivity"], path + ".reflectivity", Range::closed(0.0, 1.0));
    }
    if (params["specular"]) node.specular = yaml_.number(params["specular"], path + ".specular", Range::non_negative());
    if (params["shininess"]) node.shininess = yaml_.number(params["shininess"], path + ".shininess", Range::positive());
    if (params["emission"]) node.emission = yaml_.color(params["emission"], path + ".emission", false);
    yaml_.optional_vec3(params, "translate", path + ".translate", node.transform.translate);
    yaml_.optional_vec3(params, "rotate", path + ".rotate", node.transform.rotate_degrees);
    // The kernels divide by the scale in float: 1 / scale must be a float too.
    if (!has_param(node, "scale")) {
      yaml_.optional_number(params, "scale", path + ".scale", node.transform.scale,
                            Range::closed(1.0 / kMaxSceneNumber, kMaxSceneNumber));
    }
    yaml_.optional_number(params, "step_factor", path + ".step_factor", node.step_factor, Range{0.0, 1.0, true, false});
  }

  /// The keys of a node of this kind: its parameters' (from its declaration), children for an
  /// operator, and the common ones.
  static std::vector<std::string_view> node_keys(const Node& node) {
    std::vector<std::string_view> keys;
    for (const ParamSpec& spec : param_table(node.kind)) {
      // A program is read from several keys of its own.
      if (spec.type == ParamType::Program) {
        keys.insert(keys.end(), std::begin(kGlslNodeKeys), std::end(kGlslNodeKeys));
      } else {
        keys.emplace_back(spec.key);
      }
    }
    if (!is_primitive(node.kind)) keys.emplace_back("children");
    for (std::string_view common : {CLMARCH_COMMON_NODE_KEYS}) {
      if (!has_param(node, common)) keys.push_back(common);
    }
    return keys;
  }

  /// Whether the node's kind declares a parameter named key: a fractal's scale is its own (the
  /// IFS's), not the transform's.
  static bool has_param(const Node& node, std::string_view key) {
    for (const ParamSpec& spec : param_table(node.kind)) {
      if (spec.key == key) return true;
    }
    return false;
  }

  /// Reads the parameters of the node's kind from map, by its declaration's table: the keys
  /// given are read and range-checked, the others keep their defaults (a required one fails).
  void read_params(Node& node, const YAML::Node& map, const std::string& path) {
    std::visit(
        [&](auto& params) {
          for_each_param(params, [&](const ParamSpec& spec, auto& value) {
            if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::shared_ptr<const GlslProgram>>) {
              value = read_glsl_program(yaml_, map, path, glsl_context_, instance_files_);
              if (uses_time(value->module)) yaml_.note_time_read();
            } else {
              const std::string what = path + "." + spec.key;
              const YAML::Node given = map[spec.key];
              if (!given) {
                if (spec.required) yaml_.required(map, spec.key, what);
                return;
              }
              read_param(spec, given, what, value);
            }
          });
          check_params(params, map, path);
        },
        node.params);
  }

  void read_param(const ParamSpec& spec, const YAML::Node& given, const std::string& what, glm::dvec3& value) {
    value = yaml_.vec3(given, what, spec.range);
    if (spec.type == ParamType::Direction) {
      if (glm::length(value) == 0.0) yaml_.fail(given, what + " must not be zero");
      value = glm::normalize(value);
    }
  }
  void read_param(const ParamSpec& spec, const YAML::Node& given, const std::string& what, glm::dvec4& value) {
    if (!given.IsSequence() || given.size() != 4) {
      yaml_.fail(given, fmt::format("{} must be a list of 4 numbers [x, y, z, w] (got {})", what,
                                    given.IsSequence() ? fmt::format("{} items", given.size()) : describe_yaml(given)));
    }
    for (int i = 0; i < 4; ++i) value[i] = yaml_.number(given[i], fmt::format("{}[{}]", what, i), spec.range);
  }
  void read_param(const ParamSpec& spec, const YAML::Node& given, const std::string& what, double& value) {
    value = yaml_.number(given, what, spec.range);
  }
  template <class Integer>
  requires std::is_integral_v<Integer>
  void read_param(const ParamSpec& spec, const YAML::Node& given, const std::string& what, Integer& value) {
    value = static_cast<Integer>(yaml_.integer(given, what, spec.range));
  }
  template <class Enum>
  requires std::is_enum_v<Enum>
  void read_param(const ParamSpec& spec, const YAML::Node& given, const std::string& what, Enum& value) {
    value = static_cast<Enum>(yaml_.choice(given, what, spec.choices));
  }

  void read_param(const ParamSpec& spec, const YAML::Node& given, const std::string& what, glm::ivec3& value) {
    if (!given.IsSequence() || given.size() != 3) {
      yaml_.fail(given, fmt::format("{} must be a list of 3 integers (got {})", what, describe_yaml(given)));
    }
    for (int i = 0; i < 3; ++i) value[i] = yaml_.integer(given[i], fmt::format("{}[{}]", what, i), spec.range);
  }
  void read_param(const ParamSpec&, const YAML::Node& given, const std::string& what, glm::bvec3& value) {
    if (!given.IsSequence() || given.size() == 0) {
      yaml_.fail(given,
                 fmt::format("{} must be a non-empty list of the axes x, y, z (got {})", what, describe_yaml(given)));
    }
    for (std::size_t i = 0; i < given.size(); ++i) {
      const std::string axis = yaml_.text(given[i], fmt::format("{}[{}]", what, i));
      const int index = axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1;
      if (index < 0) yaml_.fail(given[i], fmt::format("{}[{}]: unknown axis '{}' (expected x, y or z)", what, i, axis));
      if (value[index]) yaml_.fail(given[i], fmt::format("{}[{}]: axis {} is listed twice", what, i, axis));
      value[index] = true;
    }
  }

  // Checks across parameters, beyond each one's range; most kinds have none.
  template <class Params>
  void check_params(const Params&, const YAML::Node&, const std::string&) {}

  // A rounding radius at most the shape's smallest size: a given one is checked against it, the
  // default lowered to it.
  void limit_rounding(double& radius, double smallest, const YAML::Node& map, const std::string& key,
                      const std::string& path) {
    if (map[key]) {
      radius = yaml_.number(map[key], path + "." + key, Range::closed(0.0, smallest));
    } else {
      radius = std::min(radius, smallest);
    }
  }

  void check_params(RoundBox& box, const YAML::Node& map, const std::string& path) {
    limit_rounding(box.radius, std::min({box.half_size.x, box.half_size.y, box.half_size.z}), map, "radius", path);
  }

  void check_params(BoxFrame& frame, const YAML::Node& map, const std::string& path) {
    const double smallest = std::min({frame.half_size.x, frame.half_size.y, frame.half_size.z});
    if (map["thickness"]) {
      frame.thickness = yaml_.number(map["thickness"], path + ".thickness", {0.0, smallest, true, false});
    } else {
      frame.thickness = std::min(frame.thickness, smallest);
    }
  }

  void check_params(Capsule& capsule, const YAML::Node& map, const std::string& path) {
    if (capsule.a == capsule.b) yaml_.fail(map, path + ".a and " + path + ".b must differ (use a sphere for a point)");
  }

  void check_params(CappedCone& cone, const YAML::Node& map, const std::string& path) {
    if (cone.bottom_radius == 0.0 && cone.top_radius == 0.0) {
      yaml_.fail(map, path + ".bottom_radius and " + path + ".top_radius must not both be 0 (that is a segment)");
    }
  }

  void check_params(CappedCylinder& cylinder, const YAML::Node& map, const std::string& path) {
    if (cylinder.a == cylinder.b) {
      yaml_.fail(map, path + ".a and " + path + ".b must differ (the cylinder runs from a to b)");
    }
  }

  void check_params(Frustum& frustum, const YAML::Node& map, const std::string& path) {
    if (frustum.a == frustum.b) {
      yaml_.fail(map, path + ".a and " + path + ".b must differ (the frustum runs from a to b)");
    }
    if (frustum.radius_a == 0.0 && frustum.radius_b == 0.0) {
      yaml_.fail(map, path + ".radius_a and " + path + ".radius_b must not both be 0 (that is a segment)");
    }
  }

  void check_params(RoundedCylinder& cylinder, const YAML::Node& map, const std::string& path) {
    limit_rounding(cylinder.edge_radius, std::min(cylinder.radius, cylinder.half_height), map, "edge_radius", path);
  }

  void check_params(RoundCone& cone, const YAML::Node& map, const std::string& path) {
    if (cone.a == cone.b) yaml_.fail(map, path + ".a and " + path + ".b must differ (use a sphere for a point)");
    if (cone.radius_a == 0.0 && cone.radius_b == 0.0) {
      yaml_.fail(map, path + ".radius_a and " + path + ".radius_b must not both be 0 (that is a segment)");
    }
    const double length = glm::length(cone.b - cone.a);
    if (!(std::abs(cone.radius_a - cone.radius_b) < length)) {
      yaml_.fail(map,
                 fmt::format("{}.radius_a and {}.radius_b must differ by less than |b - a| = {} (got {} and {}: one "
                             "ball holds the other, use a sphere)",
                             path, path, length, cone.radius_a, cone.radius_b));
    }
  }

  // A sphere's cut: a plane through it, not touching it.
  void check_cut_height(double cut_height, double radius, const YAML::Node& map, const std::string& path) {
    if (!(std::abs(cut_height) < radius)) {
      yaml_.fail(map["cut_height"] ? map["cut_height"] : map,
                 fmt::format("{}.cut_height must be in (-radius, radius) = ({}, {}) (got {})", path, -radius, radius,
                             cut_height));
    }
  }

  void check_params(CutSphere& cut, const YAML::Node& map, const std::string& path) {
    check_cut_height(cut.cut_height, cut.radius, map, path);
  }

  void check_params(CutHollowSphere& bowl, const YAML::Node& map, const std::string& path) {
    check_cut_height(bowl.cut_height, bowl.radius, map, path);
  }

  void check_params(DeathStar& star, const YAML::Node& map, const std::string& path) {
    // The spheres must meet in a circle: a carve that misses, hides inside or swallows the ball
    // is no death star (and Quilez's formula assumes the circle).
    const double low = std::abs(star.radius - star.carve_radius), high = star.radius + star.carve_radius;
    if (!(star.carve_distance > low && star.carve_distance < high)) {
      yaml_.fail(
          map["carve_distance"] ? map["carve_distance"] : map,
          fmt::format("{}.carve_distance must be in (|radius - carve_radius|, radius + carve_radius) = ({}, {}) so "
                      "that the spheres meet (got {})",
                      path, low, high, star.carve_distance));
    }
  }

  // The corners of a flat shape: not on one line (sine of the angle between two spans above
  // 1e-6, so that the device's float normal is well defined).
  void check_spans_a_plane(const glm::dvec3& u, const glm::dvec3& v, const YAML::Node& map, const std::string& what) {
    if (!(glm::length(glm::cross(u, v)) > 1e-6 * glm::length(u) * glm::length(v))) {
      yaml_.fail(map, what + " must span a plane (they are on one line, or nearly)");
    }
  }

  void check_params(Triangle& triangle, const YAML::Node& map, const std::string& path) {
    check_spans_a_plane(triangle.b - triangle.a, triangle.c - triangle.a, map,
                        path + ".a, " + path + ".b and " + path + ".c");
  }

  void check_params(Quad& quad, const YAML::Node& map, const std::string& path) {
    const std::string corners = path + ".a, .b, .c and .d";
    const glm::dvec3 v[4] = {quad.a, quad.b, quad.c, quad.d};
    // The diagonals' cross product: the normal of a convex quadrilateral listed in order.
    check_spans_a_plane(quad.c - quad.a, quad.d - quad.b, map, path + "'s diagonals a-c and b-d");
    const glm::dvec3 n = glm::normalize(glm::cross(quad.c - quad.a, quad.d - quad.b));
    const double size = std::max(glm::length(quad.c - quad.a), glm::length(quad.d - quad.b));
    for (int i = 0; i < 4; ++i) {
      if (std::abs(glm::dot(v[i] - v[0], n)) > 1e-6 * size) {
        yaml_.fail(map, fmt::format("{} must lie in one plane (corner {} is off it)", corners, "abcd"[i]));
      }
    }
    for (int i = 0; i < 4; ++i) {
      const glm::dvec3 turn = glm::cross(v[(i + 1) % 4] - v[i], v[(i + 2) % 4] - v[(i + 1) % 4]);
      if (!(glm::dot(turn, n) > 0.0))
        yaml_.fail(map, corners + " must be the corners of a convex quadrilateral, in order");
    }
  }

  void check_params(Mandelbulb& bulb, const YAML::Node& map, const std::string& path) {
    // An escaping orbit reaches |z| ~ bailout^power; the kernel squares it in float (max ~3e38).
    const double largest_bailout = std::pow(10.0, 18.0 / bulb.power);
    if (bulb.bailout > largest_bailout) {
      yaml_.fail(
          map["bailout"] ? map["bailout"] : map,
          fmt::format("{}.bailout must be at most 10^(18/power) = {:.3g} for power {} so that |z|^2 stays finite in "
                      "float (got {})",
                      path, largest_bailout, bulb.power, bulb.bailout));
    }
  }

  void check_params(RoundedRectangle& rectangle, const YAML::Node& map, const std::string& path) {
    limit_rounding(rectangle.radius, std::min(rectangle.half_width, rectangle.half_height), map, "radius", path);
  }

  void check_params(Segment& segment, const YAML::Node& map, const std::string& path) {
    if (segment.a.x == segment.b.x && segment.a.y == segment.b.y) {
      yaml_.fail(map, path + ".a and " + path + ".b must differ in x or y (use a circle for a point)");
    }
  }

  void check_params(Mandelbox& box, const YAML::Node& map, const std::string& path) {
    // Between -1 and 1 the scale folds everything into a bounded orbit: no surface to trace.
    if (std::abs(box.scale) <= 1.0) {
      yaml_.fail(map["scale"], fmt::format("{}.scale must be in [-4, -1) or (1, 4] (got {})", path, box.scale));
    }
    if (box.min_radius > box.fixed_radius) {
      yaml_.fail(map["min_radius"] ? map["min_radius"] : map,
                 fmt::format("{}.min_radius must be at most {}.fixed_radius (got {} > {})", path, path, box.min_radius,
                             box.fixed_radius));
    }
  }

  void check_params(Repeat& repeat, const YAML::Node& map, const std::string& path) {
    if (repeat.period == glm::dvec3(0.0)) {
      yaml_.fail(map["period"], path + ".period must repeat along at least one axis (a component > 0)");
    }
  }

  void check_params(RepeatLimited& repeat, const YAML::Node& map, const std::string& path) {
    if (repeat.period == glm::dvec3(0.0)) {
      yaml_.fail(map["period"], path + ".period must repeat along at least one axis (a component > 0)");
    }
    for (int axis = 0; axis < 3; ++axis) {
      if (repeat.min[axis] > repeat.max[axis]) {
        yaml_.fail(map["min"], fmt::format("{}.min[{}] must be at most {}.max[{}] (got {} > {})", path, axis, path,
                                           axis, repeat.min[axis], repeat.max[axis]));
      }
    }
  }

  void read_primitive(Node& node, const YAML::Node& params, const std::string& path) {
    yaml_.expect_map(params, path, node_keys(node));
    read_params(node, params, path);
    read_common(node, params, path);
  }

  /// The first parameter a scene file must give for this kind, if any (such kinds take the map form).
  static const char* first_required_key(const Node& node) {
    for (const ParamSpec& spec : param_table(node.kind)) {
      if (spec.required) return spec.key;
    }
    return nullptr;
  }

  void read_operator(Node& node, const YAML::Node& value, const std::string& path, int depth) {
    const char* required = first_required_key(node);
    const std::size_t most = static_cast<std::size_t>(max_children(node.kind));
    YAML::Node children;
    if (value.IsSequence()) {
      if (required) {
        yaml_.fail(value, fmt::format("{} needs {}{}: write {{{}: ..., children: [...]}}", path, required,
                                      is_smooth_operator(node.kind) ? " (a blend radius)" : "", required));
      }
      if (most == 1)
        yaml_.fail(value, fmt::format("{} takes parameters: write it as a map with children: [node]", path));
      children = value;
    } else if (value.IsMap()) {
      yaml_.expect_map(value, path, node_keys(node));
      read_params(node, value, path);
      children = yaml_.required(value, "children", path + ".children");
      read_common(node, value, path);
    } else {
      yaml_.fail(value,
                 fmt::format("{} must be a list of nodes or a map with children (got {})", path, describe_yaml(value)));
    }
    if (!children.IsSequence())
      yaml_.fail(children, fmt::format("{} children must be a list of nodes (got {})", path, describe_yaml(children)));
    const std::size_t minimum = static_cast<std::size_t>(min_children(node.kind));
    if (children.size() < minimum) {
      yaml_.fail(children, fmt::format("{} needs at least {} child node{} (got {})", path, minimum,
                                       minimum > 1 ? "s" : "", children.size()));
    }
    if (most == 1 && children.size() != 1) {
      yaml_.fail(children,
                 fmt::format("{} takes exactly 1 child node (got {}); wrap several in a union", path, children.size()));
    }
    if (most > 1 && children.size() > most) {
      yaml_.fail(children, fmt::format("{} takes at most {} child nodes (got {})", path, most, children.size()));
    }
    for (std::size_t i = 0; i < children.size(); ++i) {
      const YAML::Node child = children[i];
      const std::string child_path = fmt::format("{}[{}]", path, i);
      if (child.IsMap() && child.size() == 1 && child.begin()->first.Scalar() == "instances") {
        read_instances(node, child.begin()->second, child_path + ".instances", depth + 1);
      } else {
        node.children.push_back(read_node(child, child_path, depth + 1));
      }
    }
    // A turn's Lipschitz factor grows with the distance from its axis: it needs the child's reach.
    if ((node.kind == NodeKind::Twist || node.kind == NodeKind::Bend) && !node_bounds(node.children.front())) {
      yaml_.fail(children[0],
                 fmt::format("{} needs a bounded child: {}[0] ({}) has no bounding sphere (planes, terrain, infinite "
                             "cylinders, 2D primitives alone and repeat have none)",
                             path, path, node_kind_name(node.children.front().kind)));
    }
  }

  /// instances: {file, primitive}: one child of node per row of the CSV file (its path relative to
  /// the scene file's folder), the columns naming the primitive's keys (scene-format.md).
  void read_instances(Node& node, const YAML::Node& params, const std::string& path, int depth) {
    yaml_.expect_map(params, path, {"file", "primitive"});
    const YAML::Node file_key = yaml_.required(params, "file", path + ".file");
    const YAML::Node primitive_key = yaml_.required(params, "primitive", path + ".primitive");
    const std::string primitive = yaml_.text(primitive_key, path + ".primitive");
    const std::optional<NodeKind> kind = node_kind_from_name(primitive);
    if (!kind || !is_primitive(*kind)) {
      std::vector<std::string_view> names;
      for (NodeKind k : kAllNodeKinds) {
        if (is_primitive(k)) names.push_back(node_kind_name(k));
      }
      yaml_.fail(primitive_key, fmt::format("{}.primitive: '{}' is not a primitive", path, primitive),
                 fmt::format(" (expected one of: {})", fmt::join(names, ", ")));
    }
    std::filesystem::path file = yaml_.text(file_key, path + ".file");
    if (file.is_relative()) file = std::filesystem::path(source_name_).parent_path() / file;
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error)) {
      yaml_.fail(file_key,
                 fmt::format("{}.file: cannot read the instance file {} (no such file)", path, file.string()));
    }
    instance_files_.push_back(file.string());
    const InstanceTable table = read_instance_table(file.string(), kMaxTreeNodes - node_count_, "instance file");
    const std::vector<InstanceColumn> columns = instance_columns(table);
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
      YAML::Node keys(YAML::NodeType::Map);
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const double value = table.rows[r][c];
        if (columns[c].component < 0) {
          keys[columns[c].key] = value;
        } else {
          if (!keys[columns[c].key]) keys[columns[c].key] = YAML::Node(std::vector<double>(3, 0.0));
          keys[columns[c].key][columns[c].component] = value;
        }
      }
      YAML::Node item(YAML::NodeType::Map);
      item[primitive] = keys;
      try {
        node.children.push_back(read_node(item, fmt::format("{}[{}]", path, r), depth));
      } catch (const InputError& e) {
        // The row's own place instead of the scene's, which it has none of.
        std::string message = e.what();
        const std::string unplaced = yaml_.where(YAML::Node()) + ": ";
        if (message.starts_with(unplaced)) message.erase(0, unplaced.size());
        throw InputError(fmt::format("{}:{}: {}", table.path, table.lines[r], message));
      }
    }
  }

  /// Where a column of an instance file goes: key, and for vectors the component (x, y, z or
  /// r, g, b as 0, 1, 2; -1 for a number).
  struct InstanceColumn {
    std::string key;
    int component = -1;
  };

  static std::vector<InstanceColumn> instance_columns(const InstanceTable& table) {
    std::vector<InstanceColumn> columns;
    for (const std::string& name : table.columns) {
      InstanceColumn column{name, -1};
      static constexpr std::string_view kSuffixes[] = {"_x", "_y", "_z", "_r", "_g", "_b"};
      for (int s = 0; s < 6; ++s) {
        if (name.size() > 2 && name.ends_with(kSuffixes[s])) column = {name.substr(0, name.size() - 2), s % 3};
      }
      columns.push_back(column);
    }
    for (const InstanceColumn& column : columns) {
      if (column.component < 0) continue;
      for (int component = 0; component < 3; ++component) {
        const bool present = std::any_of(columns.begin(), columns.end(), [&](const InstanceColumn& other) {
          return other.key == column.key && other.component == component;
        });
        if (!present) {
          throw InputError(
              fmt::format("{}:1: column {} needs its companions: {}_x, {}_y, {}_z (or _r, _g, _b for a color)",
                          table.path, column.key, column.key, column.key, column.key));
        }
      }
    }
    return columns;
  }

  YamlReader yaml_;
  std::string source_name_;
  std::vector<std::string> instance_files_;
  GlslNodeContext glsl_context_;
  /// SDF nodes read so far, and those of them reached again through an alias.
  int node_count_ = 0;
  int aliased_nodes_ = 0;
  std::unordered_set<std::size_t> positions_read_;
};

/// A copy of a parsed --set value built from fresh nodes, which carry no position: messages about
/// it then say it came from --set rather than pointing at a line of the file. The copy expands
/// aliases, so it stops after kMaxOverrideNodes nodes or kMaxOverrideDepth levels (an alias bomb,
/// or an alias inside its own anchor, which yaml-cpp turns into a cycle).
class PositionlessCopy {
 public:
  explicit PositionlessCopy(const std::string& option) : option_(option) {}

  YAML::Node operator()(const YAML::Node& node, int depth = 1) {
    if (depth > kMaxOverrideDepth) {
      throw InputError(fmt::format("{}: the value nests too deep (got level {}, expected at most {})", option_, depth,
                                   kMaxOverrideDepth));
    }
    if (++count_ > kMaxOverrideNodes) {
      throw InputError(
          fmt::format("{}: the value has too many YAML values (got value {}, expected at most {}; an alias "
                      "*name counts its nodes again at every use)",
                      option_, count_, kMaxOverrideNodes));
    }
    switch (node.Type()) {
      case YAML::NodeType::Scalar:
        return YAML::Node(node.Scalar());
      case YAML::NodeType::Sequence: {
        YAML::Node out(YAML::NodeType::Sequence);
        for (const auto& item : node) out.push_back((*this)(item, depth + 1));
        return out;
      }
      case YAML::NodeType::Map: {
        YAML::Node out(YAML::NodeType::Map);
        for (const auto& entry : node)
          out.force_insert((*this)(entry.first, depth + 1), (*this)(entry.second, depth + 1));
        return out;
      }
      default:
        return YAML::Node(YAML::NodeType::Null);
    }
  }

 private:
  const std::string& option_;
  int count_ = 0;
};

/// The option as messages quote it, on one line whatever the value holds.
std::string quoted_option(const SceneOverride& override_) {
  std::string text = fmt::format("--set {}={}", override_.path, override_.value);
  for (std::size_t at; (at = text.find('\n')) != std::string::npos;) text.replace(at, 1, "\\n");
  return text;
}

void apply_override(YAML::Node& root, const SceneOverride& override_) {
  const std::string option = quoted_option(override_);
  if (override_.value.find_first_not_of(" \t") == std::string::npos) {
    throw InputError(
        fmt::format("{}: the value is empty (null removes the key: --set {}=null)", option, override_.path));
  }
  YAML::Node value;
  try {
    // One document, as in a scene file: a second one ('---') would be dropped unseen.
    const std::vector<YAML::Node> documents = YAML::LoadAll(override_.value);
    if (documents.size() > 1)
      throw InputError(fmt::format("{}: the value holds {} YAML documents, expected one", option, documents.size()));
    value = PositionlessCopy(option)(documents.empty() ? YAML::Node() : documents.front());
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: the value is not valid YAML: {}", option, e.msg));
  }
  std::vector<std::string> segments;
  std::stringstream parts(override_.path);
  for (std::string segment; std::getline(parts, segment, '.');) {
    if (segment.empty()) throw InputError(fmt::format("{}: empty component in the key path", option));
    segments.push_back(segment);
  }
  if (segments.empty()) throw InputError(fmt::format("{}: empty key path", option));
  // A null value removes the key (or list item), so that an optional part can be switched off.
  const bool remove = value.IsNull();
  // yaml-cpp's operator= on a Node writes through to the node it refers to; reset() rebinds.
  YAML::Node current;
  current.reset(root);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const std::string& segment = segments[i];
    const bool last = i + 1 == segments.size();
    // The key path up to this segment, without it.
    const auto before = segments.begin() + static_cast<std::ptrdiff_t>(i);
    YAML::Node next;
    const bool is_index = segment.find_first_not_of("0123456789") == std::string::npos;
    if (remove && (!current.IsDefined() || current.IsNull() || (current.IsMap() && !current[segment]))) {
      throw InputError(
          fmt::format("{}: the scene has no {} to remove", option, fmt::join(segments.begin(), before + 1, ".")));
    }
    // A key the file does not have yet becomes a map; assigning through current fills the parent.
    if (!current.IsDefined() || current.IsNull()) {
      if (is_index && i > 0) {
        throw InputError(fmt::format(
            "{}: the scene has no {}, so index {} reaches nothing (set the whole list, e.g. --set {}=[...])", option,
            segments[i - 1], segment, fmt::join(segments.begin(), before, ".")));
      }
      current = YAML::Node(YAML::NodeType::Map);
    }
    if (current.IsSequence()) {
      std::size_t index = 0;
      try {
        if (!is_index) throw std::invalid_argument(segment);
        index = std::stoul(segment);
      } catch (const std::exception&) {
        throw InputError(fmt::format("{}: '{}' must be a list index (a number)", option, segment));
      }
      if (index >= current.size()) {
        throw InputError(fmt::format("{}: index {} is past the end of a list of {}", option, index, current.size()));
      }
      if (last) {
        if (remove) {
          current.remove(index);
        } else {
          current[index] = value;
        }
        return;
      }
      next.reset(current[index]);
    } else if (current.IsMap()) {
      if (last) {
        if (remove) {
          current.remove(segment);
        } else {
          current[segment] = value;
        }
        return;
      }
      next.reset(current[segment]);
    } else {
      throw InputError(fmt::format("{}: '{}' is a value, not a map or list", option, segments[i - 1]));
    }
    current.reset(next);
  }
}

}  // namespace

bool image_size_fits(int width, int height) { return static_cast<long long>(width) * height <= kMaxPixels; }

SceneOverride parse_override(const std::string& option_text) {
  const std::size_t equals = option_text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw InputError(fmt::format("--set {}: expected key.path=value, e.g. --set render.epsilon=1e-5", option_text));
  }
  return {option_text.substr(0, equals), option_text.substr(equals + 1)};
}

namespace {

/// Where a tab stands in the lines up to one past the parse error's (0-based) line, which a YAML
/// error rarely says itself ("illegal map value"): YAML indents with spaces only. Else empty.
std::string tab_hint(const std::string& text, int error_line) {
  int line = 0;
  std::size_t line_start = 0;
  for (std::size_t at = 0; at < text.size() && line <= error_line + 1; ++at) {
    if (text[at] == '\t') {
      return fmt::format(" (line {} column {} holds a tab: YAML indents with spaces only)", line + 1,
                         at - line_start + 1);
    }
    if (text[at] == '\n') {
      ++line;
      line_start = at + 1;
    }
  }
  return {};
}

}  // namespace

Scene load_scene_text(const std::string& text, const std::string& source_name,
                      const std::vector<SceneOverride>& overrides, double time) {
  // yaml-cpp takes a NUL in UTF-8 text for an escape and reports it a line later ("unknown escape
  // character"). UTF-16 and UTF-32, which it reads, show by a byte-order mark or a NUL in the first
  // two bytes (YAML's encoding detection).
  const bool wide =
      text.starts_with("\xff\xfe") || text.starts_with("\xfe\xff") || text.substr(0, 2).find('\0') != std::string::npos;
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos && !wide) {
    const std::size_t line_start = text.rfind('\n', nul);
    const std::size_t column = nul - (line_start == std::string::npos ? 0 : line_start + 1);
    throw InputError(
        fmt::format("{}:{}:{}: the file holds a NUL byte (a scene file is text: YAML or JSON)", source_name,
                    std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n') + 1, column + 1));
  }
  YAML::Node root;
  try {
    check_yaml_node_count(text, source_name, kMaxYamlNodes);
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    // yaml-cpp's own message for its recursion limit is "bad file".
    throw InputError(fmt::format("{}:{}:{}: the YAML is nested more than {} levels deep (an sdf tree may have {})",
                                 source_name, e.mark.line + 1, e.mark.column + 1, e.depth(), kMaxTreeDepth));
  } catch (const YAML::ParserException& e) {
    throw InputError(fmt::format("{}:{}:{}: malformed YAML: {}{}", source_name, e.mark.line + 1, e.mark.column + 1,
                                 e.msg, tab_hint(text, e.mark.line)));
  }
  if (root.IsNull()) {
    if (overrides.empty())
      throw InputError(fmt::format("{}: the scene is empty (it needs at least an sdf tree)", source_name));
    root = YAML::Node(YAML::NodeType::Map);
  }
  for (const SceneOverride& o : overrides) apply_override(root, o);
  Scene scene = SceneReader(source_name, time).read(root, source_name);
  scene.time = time;
  return scene;
}

namespace {

std::string read_scene_file(const std::string& path) {
  // Opening a FIFO blocks until its writer comes, and reading it until the writer closes.
  const BlockingCall uninterruptible_read;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read the scene file: {}", path, std::strerror(errno)));
  // Read in pieces and stop one past the limit, so that a huge file (or an endless one such as
  // /dev/zero) costs no more than the limit.
  std::string text;
  std::array<char, 65536> piece{};
  while (in.read(piece.data(), piece.size()) || in.gcount() > 0) {
    text.append(piece.data(), static_cast<std::size_t>(in.gcount()));
    if (static_cast<long long>(text.size()) > kMaxSceneFileBytes) {
      throw InputError(fmt::format("{}: the scene file is too large (got more than {} bytes, expected at most {})",
                                   path, kMaxSceneFileBytes, kMaxSceneFileBytes));
    }
  }
  if (in.bad()) throw InputError(fmt::format("{}: cannot read the scene file: {}", path, std::strerror(errno)));
  return text;
}

}  // namespace

Scene load_scene_file(const std::string& path, const std::vector<SceneOverride>& overrides, double time) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw InputError(fmt::format("{}: is a folder, not a scene file", path));
  return load_scene_text(read_scene_file(path), path, overrides, time);
}

}  // namespace clmarch
