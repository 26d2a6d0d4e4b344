// Evaluates the IR of user GLSL on the CPU in double precision, without the OpenCL translation:
// the CPU reference's view of a glsl node, so that `clmarch check` tells a translation bug from a
// precision question. Integers wrap at 32 bits and the built-ins follow GLSL's definitions; where
// GLSL leaves a result undefined, interpreter_operators.cpp and interpreter_builtins.cpp say what
// it is here (integer division by zero gives 0, shift counts are taken modulo 32).
#pragma once

#include "glsl/glsl_ir.hpp"
#include "glsl/glsl_uniforms.hpp"

#include <glm/glm.hpp>

#include <memory>

namespace clmarch::glsl {

namespace interpreter {
struct Program;
}

/// Evaluates a module's entry points. Const and thread-safe: each call keeps its state (globals,
/// locals) on its own, in a frame of its thread.
class Interpreter {
 public:
  /// Compiles module, which need not outlive the interpreter. Throws InputError where functions
  /// call each other in a cycle (GLSL forbids recursion), std::logic_error for a module that
  /// breaks glsl_ir.hpp's contract.
  Interpreter(const Module& module, const UniformValues& uniforms);

  /// The distance function's distance (its result's .x) at p, time t. Throws InputError naming
  /// the loop's file and line when loops run more than 2^24 iterations in the call.
  double distance(const glm::dvec3& p, double time) const;
  /// The colour function at p, time t; throws std::logic_error when the module has none, and
  /// InputError for a runaway loop as distance does.
  glm::dvec3 color(const glm::dvec3& p, double time) const;

 private:
  /// The components of function's result at p.
  const double* run(int function, const glm::dvec3& p, double time) const;

  std::shared_ptr<const interpreter::Program> program_;
  UniformValues uniforms_;
};

}  // namespace clmarch::glsl
