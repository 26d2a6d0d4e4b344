// A plane of the kernels' `real` (kernels/lanes.cl) on the host: floats, or doubles for a program
// built in double, as the device's buffer holds them.
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstring>
#include <vector>

namespace clmarch {

/// n values of `real`, zero at first: each one a float, or a double where in_double.
class RealPlane {
 public:
  RealPlane(std::size_t n, bool in_double)
      : in_double_(in_double), bytes_(n * (in_double ? sizeof(double) : sizeof(float))) {}

  /// Stores value at i, rounded to float unless the plane holds doubles.
  void set(std::size_t i, double value) {
    if (in_double_) {
      std::memcpy(bytes_.data() + i * sizeof(double), &value, sizeof(double));
    } else {
      const auto single = static_cast<float>(value);
      std::memcpy(bytes_.data() + i * sizeof(float), &single, sizeof(float));
    }
  }
  /// The value at i.
  double get(std::size_t i) const {
    if (in_double_) {
      double value;
      std::memcpy(&value, bytes_.data() + i * sizeof(double), sizeof(double));
      return value;
    }
    float value;
    std::memcpy(&value, bytes_.data() + i * sizeof(float), sizeof(float));
    return value;
  }
  void* data() { return bytes_.data(); }
  std::size_t size_bytes() const { return bytes_.size(); }

 private:
  bool in_double_;
  std::vector<unsigned char> bytes_;
};

/// The x, y and z planes of points, n values each (n >= points.size(); the rest zero).
inline std::vector<RealPlane> coordinate_planes(const std::vector<glm::dvec3>& points, std::size_t n, bool in_double) {
  std::vector<RealPlane> planes(3, RealPlane(n, in_double));
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) planes[axis].set(i, points[i][axis]);
  }
  return planes;
}

}  // namespace clmarch
