// Meshing a scene: prune, sample in batches of bricks, extract, refine, shade.
#include "mesh/scene_mesh.hpp"

#include "common/available_memory.hpp"
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "common/progress.hpp"
#include "mesh/tetra_surface.hpp"
#include "reference/reference_sdf.hpp"
#include "scene/scene_box.hpp"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <sys/resource.h>

#include <chrono>
#include <cmath>

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

// Bytes per sample point in a batch: its offset (24), the driver's input and output planes (36,
// twice on a CPU device: host and device copies) and the values kept (4).
constexpr std::uint64_t kBytesPerBatchPoint = 24 + 2 * 36 + 4;
// Bytes per vertex: its edge record (80), the edge map's entry (~40), the mesh's position, normal
// and colour (48) and the refinement's batch (24 + 72); per triangle 12.
constexpr std::uint64_t kBytesPerVertex = 80 + 40 + 48 + 96;
constexpr std::uint64_t kBytesPerTriangle = 12;
// Vertices and triangles per active brick of 8^3 cells: the torus at 128 cells had 194 and 387
// (`clmarch mesh --stats`, 2026-11-28); twice that is kept as the margin for curvier surfaces.
constexpr std::uint64_t kVerticesPerBrick = 400;
constexpr std::uint64_t kTrianglesPerBrick = 800;
// A vertex is on the level once the field there is within this share of a cell of it: far below
// what a mesh of that cell shows, far above float rounding of coordinates in the grid.
constexpr double kConvergedCells = 1e-6;

}  // namespace

nlohmann::json MeshStats::to_json() const {
  return {{"grid", {grid_cells.x, grid_cells.y, grid_cells.z}},
          {"cell", cell},
          {"box", {{box_low.x, box_low.y, box_low.z}, {box_high.x, box_high.y, box_high.z}}},
          {"level", level},
          {"level_reason", level_reason},
          {"cells", cells},
          {"cells_sampled", cells_sampled},
          {"cells_pruned", cells_pruned},
          {"bricks", bricks},
          {"surface_cells", surface_cells},
          {"vertices", vertices},
          {"triangles", triangles},
          {"evaluations", evaluations},
          {"prune_ms", prune_ms},
          {"sample_ms", sample_ms},
          {"refine_ms", refine_ms},
          {"shade_ms", shade_ms},
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

FieldAt opencl_field(const Scene& scene, const OpenClOptions& options, const glm::dvec3& origin) {
  return [&scene, options, origin](const std::vector<glm::dvec3>& offsets) {
    FieldValues out;
    if (offsets.empty()) return out;
    PointSamples samples = eval_points_opencl(scene, offsets, options, origin);
    out.distance = std::move(samples.distance);
    out.color = std::move(samples.albedo);
    return out;
  };
}

FieldAt reference_field(const Scene& scene, const glm::dvec3& origin) {
  return [&scene, origin](const std::vector<glm::dvec3>& offsets) {
    FieldValues out;
    out.distance.resize(offsets.size());
    out.color.resize(offsets.size());
    const Material material = root_material(scene);
    using Range = tbb::blocked_range<std::size_t>;
    tbb::parallel_for(Range(0, offsets.size(), 4096), [&](const Range& range) {
      throw_if_cancelled();
      for (std::size_t i = range.begin(); i < range.end(); ++i) {
        const SdfSample sample = reference_sample(scene.sdf, origin + offsets[i], material);
        out.distance[i] = static_cast<float>(sample.distance);
        out.color[i] = glm::vec3(sample.color);
      }
    });
    return out;
  };
}

std::uint64_t predicted_mesh_bytes(std::uint64_t active_bricks, std::size_t batch_points) {
  return batch_points * kBytesPerBatchPoint + active_bricks * kBrickSamples * kBrickSamples * kBrickSamples * 4 / 8 +
         active_bricks * (kVerticesPerBrick * kBytesPerVertex + kTrianglesPerBrick * kBytesPerTriangle);
}

SceneMesh mesh_scene(const Scene& scene, const MeshSettings& settings,
                     const std::function<FieldAt(const glm::dvec3& origin)>& field_for,
                     const std::string& resolution_label) {
  SceneMesh out;
  MeshStats& stats = out.stats;
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
  stats.cells = static_cast<std::uint64_t>(grid.cells.x) * grid.cells.y * grid.cells.z;
  const FieldAt field = field_for(grid.origin);

  auto start = std::chrono::steady_clock::now();
  const ActiveBricks active = find_active_bricks(grid, field, stats.level);
  stats.prune_ms = ms_since(start);
  stats.evaluations += active.evaluations;
  stats.cells_pruned = active.pruned_cells;
  stats.bricks = active.bricks.size();
  stats.cells_sampled = stats.bricks * kBrickCells * kBrickCells * kBrickCells;
  stats.predicted_bytes = predicted_mesh_bytes(stats.bricks, settings.batch_points);
  if (const std::optional<AvailableMemory> available = available_host_memory()) {
    if (stats.predicted_bytes > available->bytes) {
      throw InputError(fmt::format(
          "{}: the mesh needs about {:.1f} GiB of host memory ({} bricks of the surface), but only {:.1f} GiB are "
          "left ({}); choose a lower resolution",
          resolution_label, static_cast<double>(stats.predicted_bytes) / (1 << 30), stats.bricks,
          static_cast<double>(available->bytes) / (1 << 30), available->source));
    }
  }

  start = std::chrono::steady_clock::now();
  TetraSurface surface(grid, stats.level);
  constexpr std::size_t kPerBrick = kBrickSamples * kBrickSamples * kBrickSamples;
  const std::size_t bricks_per_batch = std::max<std::size_t>(1, settings.batch_points / kPerBrick);
  {
    ProgressLine progress("mesh bricks", static_cast<long long>(active.bricks.size()));
    std::vector<glm::dvec3> offsets;
    for (std::size_t first = 0; first < active.bricks.size(); first += bricks_per_batch) {
      const std::size_t last = std::min(active.bricks.size(), first + bricks_per_batch);
      offsets.clear();
      for (std::size_t b = first; b < last; ++b) {
        const glm::ivec3 corner = active.bricks[b] * kBrickCells;
        for (int z = 0; z < kBrickSamples; ++z)
          for (int y = 0; y < kBrickSamples; ++y)
            for (int x = 0; x < kBrickSamples; ++x)
              offsets.push_back(glm::dvec3(corner + glm::ivec3(x, y, z)) * grid.cell);
      }
      const std::vector<float> values = field(offsets).distance;
      stats.evaluations += offsets.size();
      for (std::size_t b = first; b < last; ++b) {
        surface.add_brick(active.bricks[b], std::span<const float>(values).subspan((b - first) * kPerBrick, kPerBrick));
      }
      progress.advance(static_cast<long long>(last - first));
    }
  }
  stats.sample_ms = ms_since(start);
  stats.surface_cells = surface.surface_cells();

  // Each vertex from its interpolated place onto the level by false position on its edge, whose
  // ends straddle the level, with Anderson and Bjorck's rule (when the same end is replaced twice
  // in a row, the kept end's value is scaled by 1 - f(new) / f(replaced), or halved) and a
  // bisection when one end was kept three times: a kinked field (inside a box's corner) otherwise
  // holds the steps to a crawl (plain false position: 2e-4 after 8 steps there). Only the vertices
  // not yet within kConvergedCells of a cell of the level are evaluated again.
  start = std::chrono::steady_clock::now();
  std::vector<EdgeVertex>& vertices = surface.vertices();
  const double converged = kConvergedCells * grid.cell;
  std::vector<std::uint32_t> moving(vertices.size());
  for (std::uint32_t v = 0; v < moving.size(); ++v) moving[v] = v;
  std::vector<int> kept_count(vertices.size(), 0);
  std::vector<glm::dvec3> at;
  for (int step = 0; step < settings.refine_steps && !moving.empty(); ++step) {
    throw_if_cancelled();
    at.resize(moving.size());
    for (std::size_t k = 0; k < moving.size(); ++k) at[k] = vertices[moving[k]].position;
    const std::vector<float> values = field(at).distance;
    stats.evaluations += at.size();
    std::size_t still = 0;
    for (std::size_t k = 0; k < moving.size(); ++k) {
      const std::uint32_t v = moving[k];
      EdgeVertex& e = vertices[v];
      const float value = values[k];
      if (!std::isfinite(value) || std::abs(value - stats.level) <= converged) continue;
      const int moved = value < stats.level ? -1 : 1;
      float& replaced = moved < 0 ? e.below_value : e.above_value;
      float& kept = moved < 0 ? e.above_value : e.below_value;
      kept_count[v] = e.last_moved == moved ? kept_count[v] + 1 : 0;
      if (kept_count[v] > 0) {
        const double ratio = (value - stats.level) / (static_cast<double>(replaced) - stats.level);
        const double scale = ratio < 1.0 ? 1.0 - ratio : 0.5;
        kept = static_cast<float>(stats.level + scale * (kept - stats.level));
      }
      replaced = value;
      (moved < 0 ? e.below : e.above) = e.position;
      e.last_moved = moved;
      const double below = static_cast<double>(e.below_value) - stats.level;
      const double span = static_cast<double>(e.above_value) - e.below_value;
      double t = span > 0.0 ? std::clamp(-below / span, 0.0, 1.0) : 0.5;
      if (kept_count[v] >= 2) t = 0.5;
      e.position = e.below + t * (e.above - e.below);
      moving[still++] = v;
    }
    moving.resize(still);
  }
  // The colours at the final places (and the field, for the statistics).
  std::vector<glm::dvec3> final_places(vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v) final_places[v] = vertices[v].position;
  FieldValues last_values = field(final_places);
  stats.evaluations += final_places.size();
  stats.refine_ms = ms_since(start);

  // Normals from the field's gradient (central differences a tenth of a cell or normal_epsilon
  // apart, whichever is smaller), colours from the material at the vertex.
  start = std::chrono::steady_clock::now();
  const double h = std::min(scene.render.normal_epsilon, 0.1 * grid.cell);
  TriangleMesh& mesh = out.mesh;
  mesh.positions.resize(vertices.size());
  mesh.normals.resize(vertices.size());
  mesh.colors = std::move(last_values.color);
  std::vector<glm::dvec3> taps;
  const std::size_t vertices_per_batch = std::max<std::size_t>(1, settings.batch_points / 6);
  for (std::size_t first = 0; first < vertices.size(); first += vertices_per_batch) {
    const std::size_t last = std::min(vertices.size(), first + vertices_per_batch);
    taps.clear();
    for (std::size_t v = first; v < last; ++v) {
      for (int axis = 0; axis < 3; ++axis) {
        glm::dvec3 step(0.0);
        step[axis] = h;
        taps.push_back(vertices[v].position + step);
        taps.push_back(vertices[v].position - step);
      }
    }
    const std::vector<float> values = field(taps).distance;
    stats.evaluations += taps.size();
    for (std::size_t v = first; v < last; ++v) {
      const std::size_t t = 6 * (v - first);
      const glm::dvec3 gradient(values[t] - values[t + 1], values[t + 2] - values[t + 3],
                                values[t + 4] - values[t + 5]);
      const double length = glm::length(gradient);
      // A vanishing gradient (a crease at the level's extremum): the edge's direction up the field.
      const glm::dvec3 up = glm::normalize(vertices[v].above - vertices[v].below);
      mesh.normals[v] = glm::vec3(length > 0.0 && std::isfinite(length) ? gradient / length : up);
      mesh.positions[v] = grid.origin + vertices[v].position;
    }
  }
  mesh.triangles = surface.triangles();
  stats.shade_ms = ms_since(start);
  stats.vertices = mesh.positions.size();
  stats.triangles = mesh.triangles.size();
  stats.peak_resident_bytes = peak_resident_bytes();
  return out;
}

}  // namespace clmarch
