// Literals compared bit for bit: the program spells a literal exactly, so any other bits are
// another value (-0.0 too).
#include "codegen/varying_literals.hpp"

#include "codegen/kernel_source.hpp"

#include <bit>
#include <cstdint>

namespace clmarch {

ValueSlots VaryingLiterals::add(const Scene& frame) {
  SdfCode code = march_scene_code(frame);
  const auto [it, is_new] = shapes_.try_emplace(code_shape(code.source));
  Shape& shape = it->second;
  if (is_new) {
    shape.first = std::move(code.literals);
    shape.varies.assign(shape.first.size(), false);
    return {};
  }
  for (std::size_t k = 0; k < shape.first.size(); ++k) {
    if (std::bit_cast<std::uint32_t>(shape.first[k]) != std::bit_cast<std::uint32_t>(code.literals[k]))
      shape.varies[k] = true;
  }
  return shape.slots();
}

ValueSlots VaryingLiterals::slots_for(const Scene& frame) const {
  const auto it = shapes_.find(code_shape(march_scene_code(frame).source));
  return it == shapes_.end() ? ValueSlots{} : it->second.slots();
}

ValueSlots VaryingLiterals::Shape::slots() const {
  ValueSlots slots;
  for (std::size_t k = 0; k < varies.size(); ++k) {
    if (varies[k]) slots.push_back(static_cast<int>(k));
  }
  return slots;
}

}  // namespace clmarch
