// Meshing a scene: prune, sample in batches of bricks, extract, refine, shade.
#include "mesh/scene_mesh.hpp"

#include "common/available_memory.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/progress.hpp"
#include "common/log.hpp"
#include "mesh/brick_surface.hpp"
#include "mesh/sharp_features.hpp"
#include "scene/scene_box.hpp"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace clmarch {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// The first primitive of the tree whose field is an estimate (fractals, height fields), if any.
const Node* first_estimate(const Node& node) {
  if (is_primitive(node.kind)) return field_quality(node.kind) == FieldQuality::Estimate ? &node : nullptr;
  for (const Node& child : node.children) {
    if (const Node* found = first_estimate(child)) return found;
  }
  return nullptr;
}

std::uint64_t peak_resident_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
}

// Bytes per brick: its samples (kBrickSamples^3 floats), its record (corner, slot, neighbours:
// ~80) and its edge set (8 bytes and a 16-bit count per 64 edges: 512 edge ends times the method's
// steps).
constexpr std::uint64_t kBrickSampleBytes = kBrickSamples * kBrickSamples * kBrickSamples * 4;
constexpr std::uint64_t kBrickRecordBytes = 80;
// Bytes per point of a batch on the host: the brick samples' device copy (4) and the vertex
// batches' 8 input and 8 output planes and their seeds and results (~96 a vertex, a quarter of the
// points) and the block of placed vertices handed to the sink (48 a vertex).
constexpr std::uint64_t kBytesPerBatchPoint = 4 + (96 + 48) / 4;
// The most triangles a brick adds to a block past MeshSettings::triangles_per_block: 512 cells of
// at most 12 triangles (tetrahedra).
constexpr std::uint64_t kBrickTriangles = 512 * 12;
// Vertices and triangles per sampled brick of 8^3 cells, twice the most measured (`clmarch mesh
// --stats`, 2026-11-28: cubes 52 for the sphere at 1024 cells, 69 for the Mandelbulb at 256;
// tetrahedra 192 for the Mandelbulb at 256), as the margin for curvier surfaces.
constexpr std::uint64_t kCubeVerticesPerBrick = 140;
constexpr std::uint64_t kCubeTrianglesPerBrick = 280;
constexpr std::uint64_t kTetraVerticesPerBrick = 400;
constexpr std::uint64_t kTetraTrianglesPerBrick = 800;
}  // namespace

nlohmann::json MeshStats::to_json() const {
  return {{"grid", {grid_cells.x, grid_cells.y, grid_cells.z}},
          {"cell", cell},
          {"box", {{box_low.x, box_low.y, box_low.z}, {box_high.x, box_high.y, box_high.z}}},
          {"level", level},
          {"level_reason", level_reason},
          {"cell_method", cell_method},
          {"cells", cells},
          {"cells_sampled", cells_sampled},
          {"cells_pruned", cells_pruned},
          {"bricks", bricks},
          {"bricks_restored", bricks_restored},
          {"surface_cells", surface_cells},
          {"vertices", vertices},
          {"triangles", triangles},
          {"evaluations", evaluations},
          {"setup_ms", setup_ms},
          {"prune_ms", prune_ms},
          {"sample_ms", sample_ms},
          {"march_ms", march_ms},
          {"place_ms", place_ms},
          {"sharp", sharp},
          {"feature_cells", feature_cells},
          {"feature_cells_clamped", feature_cells_clamped},
          {"feature_cells_folded", feature_cells_folded},
          {"flipped_edges", flipped_edges},
          {"sharp_ms", sharp_ms},
          {"predicted_bytes", predicted_bytes},
          {"peak_resident_bytes", peak_resident_bytes}};
}

void surface_box(const Scene& scene, double level, glm::dvec3& low, glm::dvec3& high) {
  if (scene.tiling) {
    throw InputError(
        fmt::format("{}: tiling repeats the tree without end: a mesh needs a bounded surface", scene.source_name));
  }
  const std::optional<BoundingBox> box = node_box(scene.sdf);
  if (!box) {
    throw InputError(fmt::format(
        "{}: sdf: the surface is unbounded (a plane, a half-space, a terrain): a mesh needs a bounded surface; "
        "intersect it with a box",
        scene.source_name));
  }
  low = box->low - box->gain * level;
  high = box->high + box->gain * level;
  if (!(high.x > low.x && high.y > low.y && high.z > low.z) || !std::isfinite(glm::length(high - low))) {
    throw InputError(fmt::format("{}: sdf: the surface's bounding box is empty or infinite", scene.source_name));
  }
}

std::uint64_t predicted_mesh_bytes(std::uint64_t active_bricks, std::size_t batch_points,
                                   std::size_t triangles_per_block, CellMethod cells,
                                   std::uint64_t kept_bytes_per_vertex, std::uint64_t kept_bytes_per_triangle) {
  const std::uint64_t edge_set = 512 * static_cast<std::uint64_t>(edge_steps(cells).count) / 64 * 10;
  const bool cubes = cells == CellMethod::Cubes;
  const std::uint64_t vertices = cubes ? kCubeVerticesPerBrick : kTetraVerticesPerBrick;
  const std::uint64_t triangles = cubes ? kCubeTrianglesPerBrick : kTetraTrianglesPerBrick;
  return batch_points * kBytesPerBatchPoint + (triangles_per_block + kBrickTriangles) * sizeof(MeshTriangle) +
         active_bricks * (kBrickSampleBytes + kBrickRecordBytes + edge_set + vertices * kept_bytes_per_vertex +
                          triangles * kept_bytes_per_triangle);
}

MeshStats mesh_scene(const Scene& scene, const MeshSettings& settings, const MeshFieldFor& field_for,
                     const std::string& resolution_label, MeshSink& sink) {
  MeshStats stats;
  stats.sharp = settings.sharp;
  if (settings.sharp && settings.cells != CellMethod::Cubes) {
    throw std::invalid_argument("MeshSettings: sharp features need marching cubes' cells, not tetrahedra");
  }
  if (const Node* estimate = first_estimate(scene.sdf)) {
    stats.level = scene.render.epsilon;
    stats.level_reason = fmt::format(
        "the field of {} is an estimate, whose sign is no inside/outside test: meshed where it falls to "
        "render.epsilon = {:g}, the renderer's hit threshold",
        node_kind_name(estimate->kind), scene.render.epsilon);
  }
  glm::dvec3 low, high;
  surface_box(scene, stats.level, low, high);
  stats.box_low = low;
  stats.box_high = high;
  const MeshGrid grid = mesh_grid(low, high, settings.resolution);
  stats.grid_cells = grid.cells;
  stats.cell = grid.cell;
  stats.cell_method = std::string(kCellMethodNames[static_cast<int>(settings.cells)]);
  stats.cells = static_cast<std::uint64_t>(grid.cells.x) * grid.cells.y * grid.cells.z;
  auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<MeshField> field = field_for(grid.origin);
  stats.setup_ms = ms_since(start);

  start = std::chrono::steady_clock::now();
  ActiveBricks active;
  if (settings.prune) {
    active = find_active_bricks(grid, *field, stats.level);
  } else {
    for (int z = 0; z < grid.bricks.z; ++z)
      for (int y = 0; y < grid.bricks.y; ++y)
        for (int x = 0; x < grid.bricks.x; ++x) active.bricks.emplace_back(x, y, z);
  }
  stats.prune_ms = ms_since(start);
  stats.evaluations += active.evaluations;
  // With sharp features the whole mesh is kept (and its triangles' cells, and the triangles remade)
  // before the sink has it.
  MeshCollector kept;
  MeshSink& receiver = settings.sharp ? kept : sink;
  const std::uint64_t kept_per_triangle = sizeof(MeshTriangle) + sizeof(std::uint64_t);
  stats.predicted_bytes =
      predicted_mesh_bytes(active.bricks.size(), settings.batch_points, settings.triangles_per_block, settings.cells,
                           sink.kept_bytes_per_vertex() + (settings.sharp ? kept.kept_bytes_per_vertex() : 0),
                           sink.kept_bytes_per_triangle() + (settings.sharp ? 2 * kept_per_triangle : 0));
  if (const std::optional<AvailableMemory> available = available_host_memory()) {
    if (stats.predicted_bytes > available->bytes) {
      throw InputError(fmt::format(
          "{}: the mesh needs about {:.1f} GiB of host memory ({} bricks of the surface), but only {:.1f} GiB are "
          "left ({}); choose a lower resolution",
          resolution_label, static_cast<double>(stats.predicted_bytes) / (1 << 30), active.bricks.size(),
          static_cast<double>(available->bytes) / (1 << 30), available->source));
    }
  }

  start = std::chrono::steady_clock::now();
  BrickSurface surface(grid, stats.level, settings.cells);
  {
    ProgressLine progress("mesh bricks", static_cast<long long>(active.bricks.size()));
    stats.bricks_restored = surface.sample(*field, active.bricks, settings.batch_points, [&](std::size_t bricks) {
      progress.advance(static_cast<long long>(bricks));
    });
  }
  stats.bricks = surface.bricks();
  stats.cells_sampled = stats.bricks * kBrickCells * kBrickCells * kBrickCells;
  stats.cells_pruned = stats.cells - stats.cells_sampled;
  stats.evaluations += stats.bricks * kBrickSamples * kBrickSamples * kBrickSamples;
  stats.sample_ms = ms_since(start);

  start = std::chrono::steady_clock::now();
  surface.march();
  stats.surface_cells = surface.surface_cells();
  if (surface.dropped_triangles() > 0) {
    log_warning(
        fmt::format("{}: the surface reaches the mesh grid's boundary: {} triangles there left out, the mesh "
                    "is open",
                    scene.source_name, surface.dropped_triangles()));
  }
  stats.march_ms = ms_since(start);

  // Each vertex onto the level, with its normal (four taps a tenth of a cell or
  // normal_epsilon from it, whichever is smaller) and colour, a batch of bricks' vertices at a time,
  // each batch handed to the sink as it is placed. write_ms is the time in the sink, when the sink
  // is the caller's.
  const auto timed = [&](const auto& call) {
    const auto write_start = std::chrono::steady_clock::now();
    call();
    if (&receiver == &sink) stats.write_ms += ms_since(write_start);
  };
  start = std::chrono::steady_clock::now();
  const std::uint32_t vertices = surface.vertices();
  const std::uint64_t triangles = surface.triangles();
  timed([&] { receiver.begin({vertices, triangles, true, true}); });
  PlacementSettings placement;
  placement.level = stats.level;
  placement.tolerance = settings.tolerance_cells * grid.cell;
  placement.max_steps = settings.refine_steps;
  placement.normal_step = std::min(scene.render.normal_epsilon, 0.1 * grid.cell);
  {
    ProgressLine progress("mesh vertices", static_cast<long long>(vertices));
    const std::size_t per_batch = std::max<std::size_t>(1, settings.batch_points / 4);
    std::vector<EdgeSeed> seeds;
    std::vector<PlacedVertex> placed;
    std::vector<glm::dvec3> positions;
    std::vector<glm::vec3> normals, colors;
    for (std::size_t b = 0; b < surface.bricks();) {
      seeds.clear();
      for (; b < surface.bricks() && seeds.size() < per_batch; ++b) surface.append_seeds(b, seeds);
      placed.resize(seeds.size());
      field->place_vertices(seeds, grid.cell, placement, placed);
      positions.resize(seeds.size());
      normals.resize(seeds.size());
      colors.resize(seeds.size());
      using Range = tbb::blocked_range<std::size_t>;
      tbb::parallel_for(Range(0, seeds.size(), 4096), [&](const Range& range) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
          const EdgeSeed& s = seeds[i];
          const glm::dvec3 at =
              glm::dvec3(s.point) + static_cast<double>(placed[i].place) * glm::dvec3(step_offset(s.step));
          positions[i] = grid.origin + at * grid.cell;
          normals[i] = placed[i].normal;
          colors[i] = placed[i].color;
        }
      });
      for (const PlacedVertex& v : placed) stats.evaluations += v.evaluations;
      timed([&] { receiver.add_vertices({positions, normals, colors}); });
      progress.advance(static_cast<long long>(seeds.size()));
    }
  }
  // write_ms holds the sink's time of placing alone so far.
  stats.place_ms = ms_since(start) - stats.write_ms;

  // The triangles, made again from the samples a block of bricks at a time (marching's time).
  std::vector<std::uint64_t> cells;
  {
    std::vector<MeshTriangle> block;
    for (std::size_t b = 0; b < surface.bricks();) {
      std::size_t end = b + 1;
      while (end < surface.bricks() &&
             surface.first_triangle(end) - surface.first_triangle(b) < settings.triangles_per_block)
        ++end;
      start = std::chrono::steady_clock::now();
      if (settings.sharp) {
        surface.append_triangles(b, end, kept.mesh.triangles, &cells);
      } else {
        block.clear();
        surface.append_triangles(b, end, block);
      }
      stats.march_ms += ms_since(start);
      if (!settings.sharp) timed([&] { sink.add_triangles(block); });
      b = end;
    }
  }
  surface.release_samples();
  stats.vertices = vertices;
  stats.triangles = triangles;
  if (settings.sharp) {
    start = std::chrono::steady_clock::now();
    const SharpStats sharp = sharpen_features(kept.mesh, cells, grid, SharpSettings{});
    stats.feature_cells = sharp.feature_cells;
    stats.feature_cells_clamped = sharp.clamped_cells;
    stats.feature_cells_folded = sharp.folded_cells;
    stats.flipped_edges = sharp.flipped_edges;
    stats.vertices = kept.mesh.positions.size();
    stats.triangles = kept.mesh.triangles.size();
    stats.sharp_ms = ms_since(start);
    const auto write_start = std::chrono::steady_clock::now();
    send_mesh(kept.mesh, sink);
    stats.write_ms += ms_since(write_start);
  } else {
    timed([&] { sink.finish(); });
  }
  stats.peak_resident_bytes = peak_resident_bytes();
  return stats;
}

SceneMesh mesh_scene(const Scene& scene, const MeshSettings& settings, const MeshFieldFor& field_for,
                     const std::string& resolution_label) {
  MeshCollector collector;
  SceneMesh out;
  out.stats = mesh_scene(scene, settings, field_for, resolution_label, collector);
  out.mesh = std::move(collector.mesh);
  return out;
}

}  // namespace clmarch
