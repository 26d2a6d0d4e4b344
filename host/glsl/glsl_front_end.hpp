// The front end of user GLSL: glslang parses, preprocesses and type-checks the code as a GLSL ES
// 3.00 fragment shader (WebGL 2's and Shadertoy's language), and its typed tree is lowered to the
// IR of glsl_ir.hpp. glslang's headers stay inside glsl_front_end.cpp: its tree types are internal
// API, so one file adapts to them.
#pragma once

#include "glsl/glsl_ir.hpp"

#include <string>
#include <utility>
#include <vector>

namespace clmarch::glsl {

/// User code and what to take from it.
struct Source {
  /// The GLSL text: functions, globals, structs, #define and #if; no main, no #version.
  std::string code;
  /// The file messages name: the .glsl file, or the scene file for inline code.
  std::string file_name;
  /// The line of file_name where code's first line is (inline code in a scene file).
  int first_line = 1;
  /// #define name value, before the code (a scene's `defines:`).
  std::vector<std::pair<std::string, std::string>> defines;
  /// The distance function: one vec3 parameter, returns float, vec2, vec3 or vec4 (.x the distance).
  std::string distance_function = "map";
  /// The colour function vec3 f(vec3), or empty for none.
  std::string color_function;
};

/// Parses, checks and lowers source. Throws InputError of one line naming the file, the line and
/// column and what is wrong ("shapes.glsl:12:7: 'foo' : no matching overloaded function found"):
/// glslang's diagnostics, a missing or ill-typed entry point, and constructs a distance function
/// cannot use (textures and iChannel lookups, derivatives, discard), each refused by name.
Module compile(const Source& source);

}  // namespace clmarch::glsl
