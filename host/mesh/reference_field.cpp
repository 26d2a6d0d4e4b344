// The mesh's field on the CPU reference, in double on every core: the same sampling and root
// finding as kernels/eval_points.cl's mesh kernels, written plainly.
#include "common/cancellation.hpp"
#include "mesh/mesh_field.hpp"
#include "reference/reference_sdf.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace clmarch {
namespace {

using PointRange = tbb::blocked_range<std::size_t>;

/// The place along an edge from a to a + d where field - level changes sign, from the values fa and
/// fb at its ends: false position with Anderson and Bjorck's rule, bisection once one end was kept
/// three times (mesh_place_vertices says why). Counts the evaluations in evaluations.
template <typename Field>
double place_on_edge(const Field& field, const glm::dvec3& a, const glm::dvec3& d, double fa, double fb,
                     const PlacementSettings& settings, std::uint32_t& evaluations) {
  double t = -fa / (fb - fa);
  t = std::isfinite(t) ? std::clamp(t, 0.0, 1.0) : 0.5;
  if (!(fa * fb < 0.0)) return t;
  double ta = 0.0, tb = 1.0;
  int last = 0, kept = 0;
  for (int step = 0; step < settings.max_steps; ++step) {
    const double f = field(a + t * d) - settings.level;
    ++evaluations;
    if (!(std::abs(f) > settings.tolerance) || !std::isfinite(f)) break;
    const bool replace_a = (f < 0.0) == (fa < 0.0);
    const int replaced = replace_a ? 1 : 2;
    kept = replaced == last ? kept + 1 : 0;
    double& kept_value = replace_a ? fb : fa;
    const double ratio = f / (replace_a ? fa : fb);
    if (kept > 0) kept_value *= ratio < 1.0 ? 1.0 - ratio : 0.5;
    (replace_a ? fa : fb) = f;
    (replace_a ? ta : tb) = t;
    last = replaced;
    const double span = fb - fa;
    double next = span != 0.0 ? ta - fa * (tb - ta) / span : 0.5 * (ta + tb);
    if (kept >= 2) next = 0.5 * (ta + tb);
    t = std::clamp(next, 0.0, 1.0);
  }
  return t;
}

class ReferenceField final : public MeshField {
 public:
  ReferenceField(const Scene& scene, const glm::dvec3& origin)
      : scene_(scene), origin_(origin), material_(root_material(scene)) {}

  std::vector<float> distances(const std::vector<glm::dvec3>& offsets) override {
    std::vector<float> out(offsets.size());
    tbb::parallel_for(PointRange(0, offsets.size(), 1024), [&](const PointRange& range) {
      throw_if_cancelled();
      for (std::size_t i = range.begin(); i < range.end(); ++i) out[i] = static_cast<float>(distance(offsets[i]));
    });
    return out;
  }

  void sample_bricks(std::span<const glm::ivec3> corners, int side, double cell, std::span<float> out) override {
    const std::size_t points = static_cast<std::size_t>(side) * side * side;
    tbb::parallel_for(PointRange(0, corners.size(), 1), [&](const PointRange& range) {
      throw_if_cancelled();
      for (std::size_t b = range.begin(); b < range.end(); ++b) {
        float* values = out.data() + b * points;
        for (int z = 0; z < side; ++z)
          for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x)
              *values++ = static_cast<float>(distance(glm::dvec3(corners[b] + glm::ivec3(x, y, z)) * cell));
      }
    });
  }

  void place_vertices(std::span<const EdgeSeed> seeds, double cell, const PlacementSettings& settings,
                      std::span<PlacedVertex> out) override {
    const auto field = [&](const glm::dvec3& offset) { return distance(offset); };
    tbb::parallel_for(PointRange(0, seeds.size(), 256), [&](const PointRange& range) {
      throw_if_cancelled();
      for (std::size_t i = range.begin(); i < range.end(); ++i) {
        const EdgeSeed& s = seeds[i];
        const glm::dvec3 a = glm::dvec3(s.point) * cell;
        const glm::dvec3 d = glm::dvec3(step_offset(s.step)) * cell;
        PlacedVertex& v = out[i];
        v.evaluations = 0;
        const double t = place_on_edge(field, a, d, s.value_from - settings.level, s.value_to - settings.level,
                                       settings, v.evaluations);
        v.place = static_cast<float>(t);
        const glm::dvec3 p = a + t * d;
        // Four taps at a tetrahedron's corners, as the kernel takes them.
        glm::dvec3 gradient(0.0);
        for (const glm::dvec3& k :
             {glm::dvec3(1, -1, -1), glm::dvec3(-1, -1, 1), glm::dvec3(-1, 1, -1), glm::dvec3(1, 1, 1)})
          gradient += k * distance(p + settings.normal_step * k);
        const double length = glm::length(gradient);
        const glm::dvec3 up = d * (s.value_to > s.value_from ? 1.0 : -1.0);
        v.normal = glm::vec3(length > 0.0 && std::isfinite(length) ? gradient / length : glm::normalize(up));
        v.color = glm::vec3(reference_sample(scene_.sdf, origin_ + p, material_).color);
        v.evaluations += 5;
      }
    });
  }

 private:
  double distance(const glm::dvec3& offset) const { return reference_distance(scene_.sdf, origin_ + offset); }

  const Scene& scene_;
  glm::dvec3 origin_;
  Material material_;
};

}  // namespace

std::unique_ptr<MeshField> reference_field(const Scene& scene, const glm::dvec3& origin) {
  return std::make_unique<ReferenceField>(scene, origin);
}

}  // namespace clmarch
