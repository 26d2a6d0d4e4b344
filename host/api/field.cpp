// Evaluating a scene's field at points.
#include "api/field.hpp"

#include "common/cancellation.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/tiling_model.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace clmarch {

FieldSamples sample_field(const Scene& scene, const std::vector<glm::dvec3>& given, Backend backend,
                          const SessionOptions& options) {
  std::vector<glm::dvec3> points = given;
  if (scene.tiling) {
    for (glm::dvec3& p : points) p = floor_mod(p, scene.tiling->cell);
  }
  FieldSamples out;
  out.distance.resize(points.size());
  out.color.resize(points.size() * 3);
  out.id.resize(points.size());
  out.distance_in_double = backend == Backend::Reference || scene.render.precision == Precision::Double;
  if (points.empty()) return out;
  if (backend == Backend::OpenCl) {
    OpenClOptions cl;
    cl.device = options.device;
    cl.lanes = options.lanes;
    const PointSamples samples = eval_points_opencl(scene, points, cl);
    for (std::size_t i = 0; i < points.size(); ++i) {
      out.distance[i] = samples.distance[i];
      for (int c = 0; c < 3; ++c) out.color[3 * i + c] = samples.albedo[i][c];
      out.id[i] = samples.primitive[i];
    }
    return out;
  }
  const Material material = root_material(scene);
  using Range = tbb::blocked_range<std::size_t>;
  tbb::parallel_for(Range(0, points.size(), 4096), [&](const Range& range) {
    throw_if_cancelled();
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const SdfSample sample = reference_sample(scene.sdf, points[i], material);
      out.distance[i] = sample.distance;
      for (int c = 0; c < 3; ++c) out.color[3 * i + c] = static_cast<float>(sample.color[c]);
      out.id[i] = static_cast<float>(sample.primitive);
    }
  });
  return out;
}

}  // namespace clmarch
