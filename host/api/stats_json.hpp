// The figures of one render as JSON: the object `render --stats` prints and the Python module's
// RenderResult.stats holds (docs/cli.md#--stats).
#pragma once

#include "api/render_session.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>

namespace clmarch {

nlohmann::json render_stats_json(Backend backend, const Scene& scene, const RenderStats& stats);

}  // namespace clmarch
