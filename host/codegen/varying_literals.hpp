// Which literals of a scene's distance function change between the frames of an animation.
#pragma once

#include "codegen/sdf_codegen.hpp"
#include "scene/scene.hpp"

#include <map>
#include <string>
#include <vector>

namespace clmarch {

/// The literals that differ among the frames seen, per shape of the code: frames whose distance
/// functions and shading have the same source once their literals are left open
/// (march_scene_code) share one program, which reads the literals that differ from its values
/// buffer. A change of shape (a rotation leaving the identity, a fractal's iterations, fog
/// appearing) makes another program.
class VaryingLiterals {
 public:
  /// Takes the frame's literals in: those that differ from the first frame of its shape vary.
  /// Returns the varying literals of its shape, as slots_for(frame) would.
  ValueSlots add(const Scene& frame);
  /// The varying literals of the frame's shape (none for a shape seen in one frame only).
  ValueSlots slots_for(const Scene& frame) const;

 private:
  struct Shape {
    std::vector<float> first;
    std::vector<bool> varies;

    ValueSlots slots() const;
  };
  std::map<std::string, Shape> shapes_;  // by code_shape of SdfCode::source
};

}  // namespace clmarch
