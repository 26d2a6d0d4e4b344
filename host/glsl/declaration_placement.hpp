// Where each local of a function is declared. glslang's tree keeps no node for a declaration
// without initializer (`float z;`), yet WebGL zeroes a local at its declaration, every time it is
// reached: a `float z;` inside a loop starts each iteration at zero. This finds the declaration
// in the source text and places a Declaration statement there in the IR.
#pragma once

#include "glsl/glsl_ir.hpp"

#include <string_view>
#include <vector>

namespace clmarch::glsl {

/// Inserts a Declaration of each local into function's body where code declares it: before the
/// first statement at or after the declaration's place, in the innermost block around it. Where
/// the text does not show the declaration (made by a macro, say), or the place found would not
/// hold every use, the declaration goes to the top of the function, zeroing once per call.
/// code is the user's text, whose first line is line first_line of the file.
void place_local_declarations(Function& function, const std::vector<int>& locals, const Module& module,
                              std::string_view code, int first_line);

}  // namespace clmarch::glsl
