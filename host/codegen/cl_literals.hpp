// OpenCL C spellings of host values, exact to float precision.
#pragma once

#include <glm/glm.hpp>

#include <string>

namespace clmarch {

/// A float literal that rounds to the same float as value ("1.5f", "1.0f", "-2.5e-05f").
std::string cl_float(double value);
/// A float4 literal with w = 0: "(float4)(1.0f, 2.0f, 3.0f, 0.0f)".
std::string cl_float4(const glm::dvec3& v);
/// A float4 of spelled components, w = 0 unless given: "(float4)(x, y, z, 0.0f)".
std::string cl_float4_of(const std::string& x, const std::string& y, const std::string& z,
                         const std::string& w = "0.0f");

}  // namespace clmarch
