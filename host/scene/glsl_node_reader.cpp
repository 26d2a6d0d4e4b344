// Reading a glsl node of a scene file.
#include "scene/glsl_node_reader.hpp"

#include "common/errors.hpp"
#include "glsl/glsl_front_end.hpp"

#include <fmt/format.h>

#include <cctype>
#include <filesystem>
#include <optional>
#include <fstream>
#include <sstream>

namespace clmarch {
namespace {

bool is_identifier(const std::string& text) {
  if (text.empty() || !(std::isalpha(static_cast<unsigned char>(text[0])) || text[0] == '_')) return false;
  for (char c : text) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  }
  return true;
}

std::string identifier(const YamlReader& yaml, const YAML::Node& node, const std::string& what) {
  const std::string name = yaml.text(node, what);
  if (!is_identifier(name)) {
    yaml.fail(node, fmt::format("{} must name a GLSL function (got '{}')", what, name));
  }
  return name;
}

std::string read_code_file(const YamlReader& yaml, const YAML::Node& node, const std::string& what,
                           const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    yaml.fail(node, fmt::format("{}: cannot read {} (no such file)", what, file.string()));
  }
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) yaml.fail(node, fmt::format("{}: cannot read {}", what, file.string()));
  return text.str();
}

// The scene file's line of inline code's first line: a block scalar (`code: |`) starts on the
// line after its indicator.
int inline_code_line(const YAML::Node& code) {
  const int mark_line = code.Mark().line + 1;
  return code.Scalar().find('\n') != std::string::npos ? mark_line + 1 : mark_line;
}

}  // namespace

bool names_glsl_function(const YAML::Node& color) { return color.IsScalar() && is_identifier(color.Scalar()); }

std::shared_ptr<const GlslProgram> read_glsl_program(const YamlReader& yaml, const YAML::Node& map,
                                                     const std::string& path, const GlslNodeContext& context,
                                                     std::vector<std::string>& watched_files) {
  glsl::Source source;
  std::string file_read;
  std::optional<glm::dvec3> bounds_center;
  double bounds_radius = 0.0;
  const YAML::Node file_key = map["file"];
  const YAML::Node code_key = map["code"];
  if (file_key && code_key) yaml.fail(code_key, path + ": give either file or code, not both");
  if (file_key) {
    std::filesystem::path file = yaml.text(file_key, path + ".file");
    if (file.is_relative()) file = std::filesystem::path(context.scene_file).parent_path() / file;
    source.code = read_code_file(yaml, file_key, path + ".file", file);
    source.file_name = file.lexically_normal().string();
    file_read = std::filesystem::absolute(file).lexically_normal().string();
    watched_files.push_back(file.string());
  } else if (code_key) {
    source.code = yaml.text(code_key, path + ".code");
    source.file_name = context.scene_file;
    source.first_line = code_key.Mark().is_null() ? 1 : inline_code_line(code_key);
  } else {
    yaml.fail(map, path + " needs file (a .glsl file) or code (the GLSL text) giving its distance function");
  }
  if (const YAML::Node function = map["function"])
    source.distance_function = identifier(yaml, function, path + ".function");
  if (const YAML::Node color = map["color"]; color && names_glsl_function(color)) {
    source.color_function = color.Scalar();
  }
  if (const YAML::Node defines = map["defines"]) {
    if (!defines.IsMap()) yaml.fail(defines, path + ".defines must be a map of names to values, e.g. {ITER: 4}");
    for (const auto& entry : defines) {
      const std::string name = entry.first.Scalar();
      if (!is_identifier(name)) yaml.fail(entry.first, fmt::format("{}.defines: '{}' is not a macro name", path, name));
      if (!entry.second.IsScalar()) {
        yaml.fail(entry.second, fmt::format("{}.defines.{} must be one value (a number or GLSL text)", path, name));
      }
      const std::string value = entry.second.Scalar();
      if (value.find('\n') != std::string::npos) {
        yaml.fail(entry.second, fmt::format("{}.defines.{} must be one line", path, name));
      }
      source.defines.emplace_back(name, value);
    }
  }
  if (const YAML::Node bounds = map["bounds"]) {
    yaml.expect_map(bounds, path + ".bounds", {"center", "radius"});
    glm::dvec3 center(0.0);
    yaml.optional_vec3(bounds, "center", path + ".bounds.center", center);
    bounds_radius = yaml.number(yaml.required(bounds, "radius", path + ".bounds.radius"), path + ".bounds.radius",
                                Range::positive());
    bounds_center = center;
  }
  glsl::UniformValues uniforms;
  uniforms.resolution_x = context.width;
  uniforms.resolution_y = context.height;
  std::shared_ptr<GlslProgram> program = make_glsl_program(source, yaml.time(), uniforms);
  program->file = file_read;
  program->bounds_center = bounds_center;
  program->bounds_radius = bounds_radius;
  return program;
}

}  // namespace clmarch
