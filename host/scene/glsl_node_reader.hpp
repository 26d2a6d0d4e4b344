// Reads a glsl node's keys (file or code, function, defines, color, bounds) and compiles its code
// (glsl/glsl_front_end.hpp); every error one line naming the scene file's or the code's place.
#pragma once

#include "scene/glsl_program.hpp"
#include "scene/yaml_reader.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace clmarch {

/// What reading a glsl node needs from the scene around it.
struct GlslNodeContext {
  /// The scene file (relative `file:` paths are relative to its folder).
  std::string scene_file;
  /// The render's size, for iResolution.
  int width = 640;
  int height = 360;
};

/// The keys a glsl node takes besides its declared lipschitz and the common ones (color among them:
/// a color, or the name of a colour function).
inline constexpr std::string_view kGlslNodeKeys[] = {"file", "code", "function", "defines", "bounds"};

/// The program of the glsl node map (at path, "sdf.union.0.glsl"). Appends the .glsl file read to
/// watched_files. A `color:` that names a function is the program's; any other `color:` is left to
/// the node's common color.
std::shared_ptr<const GlslProgram> read_glsl_program(const YamlReader& yaml, const YAML::Node& map,
                                                     const std::string& path, const GlslNodeContext& context,
                                                     std::vector<std::string>& watched_files);

/// Whether a glsl node's `color:` names a GLSL function rather than giving a color.
bool names_glsl_function(const YAML::Node& color);

}  // namespace clmarch
