// Making glsl nodes' programs.
#include "scene/glsl_program.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <string_view>

namespace clmarch {
namespace {

// FNV-1a, 64 bits: stable across runs and platforms, unlike std::hash.
std::uint64_t fnv1a(std::uint64_t hash, std::string_view text) {
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ULL;
  // A separator, so that ("ab", "c") and ("a", "bc") differ.
  return (hash ^ 0xffU) * 1099511628211ULL;
}

}  // namespace

std::shared_ptr<GlslProgram> make_glsl_program(const glsl::Source& source, double time,
                                               const glsl::UniformValues& uniforms) {
  auto program = std::make_shared<GlslProgram>();
  program->module = glsl::compile(source);
  program->time = time;
  program->uniforms = uniforms;
  program->interpreter = std::make_unique<const glsl::Interpreter>(program->module, uniforms);
  std::uint64_t hash = 14695981039346656037ULL;
  for (std::string_view part : {std::string_view(source.code), std::string_view(source.file_name),
                                std::string_view(source.distance_function), std::string_view(source.color_function)}) {
    hash = fnv1a(hash, part);
  }
  for (const auto& [name, value] : source.defines) hash = fnv1a(fnv1a(hash, name), value);
  hash = fnv1a(hash, fmt::format("{} {} {}", source.first_line, uniforms.resolution_x, uniforms.resolution_y));
  program->name = fmt::format("glsl_{:08x}", static_cast<std::uint32_t>(hash ^ (hash >> 32)));
  return program;
}

std::shared_ptr<const GlslProgram> default_glsl_program() {
  static const std::shared_ptr<const GlslProgram> program = [] {
    glsl::Source source;
    source.code = "float map(vec3 p) { return length(p) - 1.0; }\n";
    source.file_name = "<default glsl node>";
    std::shared_ptr<GlslProgram> made = make_glsl_program(source, 0.0, {});
    made->bounds_center = glm::dvec3(0.0);
    made->bounds_radius = 1.0;
    return made;
  }();
  return program;
}

}  // namespace clmarch
