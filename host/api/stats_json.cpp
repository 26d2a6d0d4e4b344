// --stats figures.
#include "api/stats_json.hpp"

namespace clmarch {

nlohmann::json render_stats_json(Backend backend, const Scene& scene, const RenderStats& s) {
  const bool reference = backend == Backend::Reference;
  return {{"backend", kBackendNames[static_cast<int>(backend)]},
          {"device", s.device},
          {"lanes", s.lanes},
          {"precision", reference ? "double" : kPrecisionNames[static_cast<int>(s.precision)]},
          {"width", scene.render.width},
          {"height", scene.render.height},
          {"build_ms", s.build_ms},
          {"kernel_ms", s.kernel_ms},
          {"steps", s.steps},
          {"rays_per_s", s.rays_per_s},
          {"chunks", s.chunks},
          {"literals", s.literals},
          {"stages", s.stages},
          {"surface_steps", s.steps - s.wall_steps},
          {"wall_steps", s.wall_steps},
          {"coarse_steps", s.coarse_steps},
          {"out_of_steps", s.out_of_steps},
          {"out_of_distance", s.out_of_distance}};
}

}  // namespace clmarch
