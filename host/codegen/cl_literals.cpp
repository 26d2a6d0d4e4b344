// OpenCL C spellings of host values.
#include "codegen/cl_literals.hpp"

#include <fmt/format.h>

#include <cmath>

namespace clmarch {

std::string cl_float(double value) {
  // 9 significant digits round-trip every float.
  std::string text = fmt::format("{:.9g}", static_cast<float>(value));
  if (text.find_first_of(".en") == std::string::npos) text += ".0";
  return text + "f";
}

std::string cl_float4(const glm::dvec3& v) { return cl_float4_of(cl_float(v.x), cl_float(v.y), cl_float(v.z)); }

std::string cl_float4_of(const std::string& x, const std::string& y, const std::string& z, const std::string& w) {
  return fmt::format("(float4)({}, {}, {}, {})", x, y, z, w);
}

}  // namespace clmarch
