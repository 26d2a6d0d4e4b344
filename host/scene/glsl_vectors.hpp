// GLSL's vector constructors where a scene wants a YAML list: a shader author's
// `color: vec3(1, .5, 0)`, which YAML reads as text, or splits at its commas inside a flow map.
#pragma once

#include <string>
#include <string_view>

namespace clmarch {

/// text with each GLSL vector constructor (vec2..4, and the ivec, uvec, bvec, dvec ones) of plain
/// arguments written as a YAML list, the numbers in YAML's spelling: "vec3(1, .5, 0)" gives
/// "[1, 0.5, 0]". Empty when text holds no such constructor.
std::string glsl_vectors_as_yaml(std::string_view text);

/// Whether text starts a GLSL vector constructor ("vec3(", "ivec2 (").
bool starts_glsl_vector(std::string_view text);

}  // namespace clmarch
