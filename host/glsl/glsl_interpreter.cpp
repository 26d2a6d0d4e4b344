// The interpreter's entry points: the module compiled once (interpreter_program), each call run by
// an Evaluator on a frame of its thread's.
#include "glsl/glsl_interpreter.hpp"

#include "glsl/interpreter_evaluator.hpp"
#include "glsl/interpreter_program.hpp"

#include <stdexcept>
#include <vector>

namespace clmarch::glsl {

Interpreter::Interpreter(const Module& module, const UniformValues& uniforms)
    : program_(std::make_shared<const interpreter::Program>(interpreter::compile_program(module))),
      uniforms_(uniforms) {}

double Interpreter::distance(const glm::dvec3& p, double time) const {
  return run(program_->distance_function, p, time)[0];
}

glm::dvec3 Interpreter::color(const glm::dvec3& p, double time) const {
  if (program_->color_function < 0) throw std::logic_error("glsl interpreter: the module has no colour function");
  const double* rgb = run(program_->color_function, p, time);
  return {rgb[0], rgb[1], rgb[2]};
}

const double* Interpreter::run(int function, const glm::dvec3& p, double time) const {
  // One frame a thread, grown to the largest program it has run: an entry point's call never
  // starts another on its thread, and a call writes every part of the frame it reads.
  thread_local std::vector<double> frame;
  thread_local std::vector<interpreter::Place> places;
  if (frame.size() < static_cast<std::size_t>(program_->frame_size)) frame.resize(program_->frame_size);
  if (places.size() < static_cast<std::size_t>(program_->place_count)) places.resize(program_->place_count);
  const double point[3] = {p.x, p.y, p.z};
  return interpreter::Evaluator(*program_, frame.data(), places.data()).run(function, point, time, uniforms_);
}

}  // namespace clmarch::glsl
