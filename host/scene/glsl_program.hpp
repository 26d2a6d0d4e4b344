// The user code of a `glsl` node: its checked module (glsl/glsl_ir.hpp) and what the scene file
// said about it. Shared between the copies of a node (a loaded scene is copied into renderers).
#pragma once

#include "glsl/glsl_front_end.hpp"
#include "glsl/glsl_interpreter.hpp"
#include "glsl/glsl_ir.hpp"
#include "glsl/glsl_uniforms.hpp"

#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <string>

namespace clmarch {

/// A glsl node's program, shared by the copies of its node (which copy the pointer, never it).
struct GlslProgram {
  GlslProgram() = default;
  GlslProgram(const GlslProgram&) = delete;
  GlslProgram& operator=(const GlslProgram&) = delete;

  glsl::Module module;
  /// The CPU reference's evaluator of module.
  std::unique_ptr<const glsl::Interpreter> interpreter;
  /// The prefix of its translated functions ("glsl_3fa9c2e1"), a hash of what made it, so that a
  /// scene's program text is the same from run to run and equal code is translated once.
  std::string name;
  /// The .glsl file read (absolute), for the preview to watch; empty for inline code.
  std::string file;
  /// The scene's time the program's iTime reads (the scene's t, as expressions of t do).
  double time = 0.0;
  glsl::UniformValues uniforms;
  /// A sphere the user says holds the surface (`bounds:`), or none: unbounded.
  std::optional<glm::dvec3> bounds_center;
  double bounds_radius = 0.0;
};

/// The program of a glsl node made by node_of_kind: a unit sphere, `length(p) - 1.0`.
std::shared_ptr<const GlslProgram> default_glsl_program();

/// Compiles source into a program named from a hash of source and the settings (time excluded:
/// frames of an animation share their functions).
std::shared_ptr<GlslProgram> make_glsl_program(const glsl::Source& source, double time,
                                               const glsl::UniformValues& uniforms);

}  // namespace clmarch
