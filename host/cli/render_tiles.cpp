// Tiles of rows: each rank renders them with OpenClRenderer::render_rows and sends its planes to
// rank 0 with the unit's report.
#include "cli/render_tiles.hpp"

#include "cli/rank_work.hpp"
#include "common/atomic_file.hpp"
#include "common/progress.hpp"
#include "distributed/mpi_world.hpp"
#include "distributed/work_queue.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <mutex>

namespace clmarch {
namespace {

/// One rank's share of the image, summed over its tiles.
struct RankTotals {
  std::string host;
  int tiles = 0;
  double pixels = 0.0;
  RenderStats stats;
};

}  // namespace

int tile_rows_for(int height, int ranks) {
  const int rows = height / (8 * std::max(ranks, 1)) / kBandRowAlignment * kBandRowAlignment;
  return std::max(rows, kBandRowAlignment);
}

void render_image_in_tiles(const RenderCommandOptions& options, const Scene& scene, const FrameFiles& files) {
  const MpiWorld& world = mpi_world();
  const int width = scene.render.width;
  const int height = scene.render.height;
  const int tile_rows = tile_rows_for(height, world.size);
  const int tiles = (height + tile_rows - 1) / tile_rows;
  const auto rows_of = [&](int tile) { return std::min(tile_rows, height - tile * tile_rows); };

  FrameBuffers whole;
  std::vector<RankTotals> totals;
  std::optional<ProgressLine> progress;
  std::mutex gathered;
  if (world.rank == 0) {
    whole = FrameBuffers(width, height);
    // Each tile's depth.lo is written where a double render writes its buffers, and only read then.
    whole.has_depth_lo = scene.render.precision == Precision::Double;
    totals.resize(static_cast<std::size_t>(world.size));
    progress.emplace("tiles", tiles, static_cast<double>(width) * tile_rows);
  }
  // Rank 0's tiles and the others' (on the coordinator's thread) fill disjoint rows of whole.
  const UnitSink sink = [&](int rank, int tile, const UnitFigures& figures, std::span<const float> planes) {
    const std::size_t count = static_cast<std::size_t>(rows_of(tile)) * width;
    const std::size_t first = static_cast<std::size_t>(tile) * tile_rows * width;
    for (int c = 0; c < kChannelCount; ++c) {
      std::copy_n(planes.begin() + static_cast<std::ptrdiff_t>(c * count), count,
                  whole.planes[static_cast<std::size_t>(c)].begin() + static_cast<std::ptrdiff_t>(first));
    }
    const std::lock_guard lock(gathered);
    RankTotals& t = totals[static_cast<std::size_t>(rank)];
    RenderStats& s = t.stats;
    if (t.tiles++ == 0) {
      t.host = figures.host;
      s.device = figures.stats.device;
      s.lanes = figures.stats.lanes;
      s.literals = figures.stats.literals;
      s.stages = figures.stats.stages;
      s.chunks = 0;
    }
    t.pixels += figures.pixels;
    s.build_ms += figures.stats.build_ms;
    s.kernel_ms += figures.stats.kernel_ms;
    s.chunks += figures.stats.chunks;
    s.steps += figures.stats.steps;
    s.wall_steps += figures.stats.wall_steps;
    s.coarse_steps += figures.stats.coarse_steps;
    s.out_of_steps += figures.stats.out_of_steps;
    s.out_of_distance += figures.stats.out_of_distance;
    progress->count();
  };
  const UnitName name = [&](int tile) {
    return fmt::format("rows {}..{} (tile {} of {})", tile * tile_rows, tile * tile_rows + rows_of(tile) - 1, tile + 1,
                       tiles);
  };
  const std::unique_ptr<WorkQueue> queue = make_work_queue(tiles, sink, name);

  OpenClOptions cl = opencl_options(options.scene);
  cl.ray_status = options.stats;
  cl.purpose = purpose_for(scene, !files.buffers.empty());
  if (world.rank == 0 && !files.dump_kernel.empty()) {
    cl.before_build = [path = files.dump_kernel](const std::string& source) { write_file_atomically(path, source); };
  }
  std::optional<OpenClRenderer> renderer;
  std::vector<float> planes;
  render_units(
      *queue,
      [&](int tile) {
        if (!renderer) renderer.emplace(scene, cl);
        const int rows = rows_of(tile);
        const RenderResult result = renderer->render_rows(tile * tile_rows, rows);
        const std::size_t count = static_cast<std::size_t>(rows) * width;
        planes.resize(count * kChannelCount);
        for (int c = 0; c < kChannelCount; ++c) {
          std::copy(result.buffers.planes[static_cast<std::size_t>(c)].begin(),
                    result.buffers.planes[static_cast<std::size_t>(c)].end(),
                    planes.begin() + static_cast<std::ptrdiff_t>(c * count));
        }
        queue->done(tile, UnitFigures{result.stats, static_cast<double>(count), ""}, planes);
      },
      name);
  if (world.rank != 0) return;
  progress.reset();
  write_outputs(files, scene, whole);
  if (!options.stats) return;
  for (int rank = 0; rank < world.size; ++rank) {
    RankTotals& t = totals[static_cast<std::size_t>(rank)];
    t.stats.rays_per_s = t.stats.kernel_ms > 0.0 ? t.pixels / (t.stats.kernel_ms * 1e-3) : 0.0;
    nlohmann::json line = stats_json(options, scene, t.stats);
    line["rank"] = rank;
    line["host"] = t.host;
    line["ranks"] = world.size;
    line["tiles"] = t.tiles;
    print_json_line(line);
  }
}

}  // namespace clmarch
