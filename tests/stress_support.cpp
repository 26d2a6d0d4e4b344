// Invariants and determinism checks of the stress tests.
#include "stress_support.hpp"

#include "scene/camera_model.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

namespace clmarch::stress {

std::string invariant_violation(const FrameBuffers& b, int max_steps, bool shaded) {
  for (int j = 0; j < b.height; ++j) {
    for (int i = 0; i < b.width; ++i) {
      const auto where = [&](const std::string& what) { return fmt::format("pixel {},{}: {}", i, j, what); };
      const float depth = b.at(Channel::Depth, i, j);
      const float steps = b.at(Channel::Steps, i, j);
      const float wall_steps = b.at(Channel::WallSteps, i, j);
      const glm::dvec3 n(b.at(Channel::NX, i, j), b.at(Channel::NY, i, j), b.at(Channel::NZ, i, j));
      if (std::isnan(depth) || depth < 0.0f || depth == -INFINITY) return where(fmt::format("depth {}", depth));
      if (!std::isfinite(steps) || steps != std::floor(steps) || steps < 0.0f ||
          steps > static_cast<float>(max_steps)) {
        return where(fmt::format("steps {} outside [0, {}]", steps, max_steps));
      }
      // A ray that misses the scene's bounding sphere is not marched at all.
      if (steps == 0.0f && std::isfinite(depth)) return where("a hit without a step");
      if (!(wall_steps >= 0.0f && wall_steps <= steps))
        return where(fmt::format("wall steps {} of {}", wall_steps, steps));
      if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return where("normal not finite");
      const double length = glm::length(n);
      if (!std::isfinite(depth) && length != 0.0) return where("a miss with a normal");
      if (std::isfinite(depth) && length != 0.0 && std::abs(length - 1.0) > 1e-4)
        return where(fmt::format("|normal| {}", length));
      // How the ray ended agrees with what it left: a hit, or a miss whose budget ran out at
      // exactly max_steps (issue 26's status channel).
      if (b.has_status) {
        const float status = b.at(Channel::Status, i, j);
        if (!(status >= 0.0f && status <= 3.0f && status == std::floor(status)))
          return where(fmt::format("status {}", status));
        if ((status == static_cast<float>(RayStatus::Hit)) != std::isfinite(depth))
          return where(fmt::format("status {} at depth {}", status, depth));
        if (status == static_cast<float>(RayStatus::OutOfSteps) && steps != static_cast<float>(max_steps)) {
          return where(fmt::format("out of steps after {} of {}", steps, max_steps));
        }
      }
      if (shaded) {
        for (Channel c : {Channel::R, Channel::G, Channel::B}) {
          const float v = b.at(c, i, j);
          if (!std::isfinite(v) || v < 0.0f)
            return where(fmt::format("color {} = {}", kChannelNames[static_cast<int>(c)], v));
        }
      }
    }
  }
  return "";
}

FrameBuffers render(const Scene& scene, KernelPurpose purpose, int lanes) {
  OpenClOptions options;
  options.purpose = purpose;
  options.lanes = lanes;
  return render_opencl(scene, options).buffers;
}

bool bitwise_equal(const FrameBuffers& a, const FrameBuffers& b) {
  if (a.width != b.width || a.height != b.height) return false;
  for (int c = 0; c < kChannelCount; ++c) {
    if (std::memcmp(a.planes[c].data(), b.planes[c].data(), a.planes[c].size() * sizeof(float)) != 0) return false;
  }
  return true;
}

FrameBuffers render_checked(const Scene& scene, KernelPurpose purpose, int lanes) {
  const FrameBuffers first = render(scene, purpose, lanes);
  const FrameBuffers second = render(scene, purpose, lanes);
  EXPECT_TRUE(bitwise_equal(first, second)) << "two renders of the same scene differ";
  const bool shaded = purpose == KernelPurpose::Shaded;
  const int budget = scene.render.max_steps;
  EXPECT_EQ(invariant_violation(first, budget, shaded), "");
  // Every stress scene in the other precision too (issue 26): a double render keeps the same
  // invariants.
  Scene other = scene;
  other.render.precision = scene.render.precision == Precision::Float ? Precision::Double : Precision::Float;
  EXPECT_EQ(invariant_violation(render(other, purpose, lanes), budget, shaded), "")
      << "in " << kPrecisionNames[static_cast<int>(other.render.precision)];
  return first;
}

glm::dvec3 ray_direction(const Scene& scene, int i, int j) {
  return pixel_ray_direction(camera_basis(scene.camera, scene.render.width, scene.render.height), i, j);
}

bool sweep_requested() {
  const char* value = std::getenv("CLMARCH_STRESS_SWEEP");
  return value != nullptr && std::string(value) == "1";
}

}  // namespace clmarch::stress
