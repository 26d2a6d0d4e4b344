// Building the operand grid: per cell, the least upper bound of the operands (a BVH search), then
// the operands that can reach below it, kept or dropped in the scene's order by the rules that make
// the fold over the kept ones equal to the fold over all.
#include "prune/operand_grid.hpp"

#include "common/errors.hpp"
#include "common/progress.hpp"
#include "prune/operand_bvh.hpp"
#include "reference/reference_sdf.hpp"
#include "scene/scene_bounds.hpp"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <limits>

namespace clmarch {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Whether node's field changes by at most the distance moved, so that its value at a cell's centre
/// bounds it over the cell: not the escape-time Mandelbulb's estimate, the terrain (whose slopes
/// pass 1 before its step_factor), a repetition (whose child may not fit its cell) or a blend that is
/// an estimate.
bool is_one_lipschitz(const Node& node) {
  if (is_primitive(node.kind)) return field_quality(node.kind) != FieldQuality::Estimate;
  if (node.kind == NodeKind::Repeat || node.kind == NodeKind::RepeatPolar || node.kind == NodeKind::RepeatLimited)
    return false;
  // The chamfer, round, columns, pipe and engrave blends: up to sqrt(children) steeper.
  if (operator_lipschitz(node) > 1.0) return false;
  return std::all_of(node.children.begin(), node.children.end(), is_one_lipschitz);
}

/// A sphere with neither step_factor nor a scale: its field is its bounding sphere's distance.
bool is_bare_sphere(const Node& node) {
  return node.kind == NodeKind::Sphere && node.step_factor == 1.0 && node.transform.scale == 1.0;
}

/// The polynomial smooth minimum of kernels/operators.cl, extended to infinite bounds; it rises
/// with both arguments, so it maps bounds of its operands to bounds of its value.
double smooth_min(double a, double b, double k) {
  if (a == -kInfinity || b == -kInfinity) return -kInfinity;
  if (a == kInfinity) return b;
  if (b == kInfinity) return a;
  const double h = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);
  return b + (a - b) * h - k * h * (1.0 - h);
}

double max_component(const glm::dvec3& v) { return std::max({v.x, v.y, v.z}); }

/// Bounds of the operands over one ball of space, and the pruned list there.
class CellPruner {
 public:
  CellPruner(const Node& union_node, const glm::dvec3& offset, const OperandBvh& bvh, double rounding)
      : node_(union_node),
        offset_(offset),
        bvh_(bvh),
        rounding_(rounding),
        k_(union_node.kind == NodeKind::SmoothUnion ? smooth_k(union_node) : 0.0) {
    lipschitz_.reserve(union_node.children.size());
    for (const Node& child : union_node.children) {
      lipschitz_.push_back(is_one_lipschitz(child));
      bare_spheres_.push_back(is_bare_sphere(child));
    }
  }

  /// Appends to out the operands that can change the union's value in the ball (m, reach), ascending.
  void prune(const glm::dvec3& m, double reach, std::vector<std::uint32_t>& out) {
    m_ = m;
    reach_ = reach;
    const double least = bvh_.least_upper(m, reach, [&](std::uint32_t i) { return bounds(i).upper; });
    if (k_ == 0.0) {
      // min is the same whatever the order, and an operand above the least upper bound is never the
      // minimum (nor the first at it, which picks the material).
      collect(least + rounding_);
      out.insert(out.end(), candidates_.begin(), candidates_.end());
      return;
    }
    // The smooth minimum folds left, so an operand left out must not change the fold where it would
    // have come. One above accU + k leaves the fold as it is (blend weight 1); a prefix above
    // U + k of the next is forgotten by it (weight 0). Operands not collected are above limit: the
    // first collected one forgets them before it if limit >= U + 2k (their fold is >= limit - k),
    // and later ones leave the fold alone if limit >= U + k, U that first one's upper bound, which
    // the fold's upper bound never rises above.
    double limit = least + 2.0 * k_ + rounding_;
    for (;;) {
      collect(limit);
      const Interval first = bounds(candidates_.front());
      const double needed = first.upper + (candidates_.front() == 0 ? k_ : 2.0 * k_) + rounding_;
      if (limit >= needed) break;
      limit = needed;
    }
    kept_.clear();
    Interval acc = bounds(candidates_.front());
    kept_.push_back(candidates_.front());
    for (std::size_t c = 1; c < candidates_.size(); ++c) {
      const std::uint32_t j = candidates_[c];
      const Interval operand = bounds(j);
      if (operand.lower >= acc.upper + k_ + rounding_) continue;
      if (acc.lower >= operand.upper + k_ + rounding_) {
        kept_.clear();
        acc = operand;
      } else {
        acc = {smooth_min(acc.lower, operand.lower, k_), smooth_min(acc.upper, operand.upper, k_)};
      }
      kept_.push_back(j);
    }
    out.insert(out.end(), kept_.begin(), kept_.end());
  }

 private:
  struct Interval {
    double lower, upper;
  };

  /// Operand i's field over the ball: from its bounding sphere, and from its value at the centre
  /// where the field is 1-Lipschitz. The value is the reference's, in double; rounding_ covers
  /// the kernel's float.
  Interval bounds(std::uint32_t i) const {
    const OperandBounds& sphere = bvh_.operands()[i];
    if (bare_spheres_[i]) {
      // The bounding sphere is the operand: its distance at the centre needs no tree walk.
      const double at_centre = glm::length(m_ - sphere.center) - sphere.radius;
      return {at_centre - reach_, at_centre + reach_};
    }
    Interval b{operand_lower_bound(sphere, m_, reach_), kInfinity};
    if (lipschitz_[i]) {
      const double at_centre = reference_distance(node_.children[i], m_ + offset_);
      b.lower = std::max(b.lower, at_centre - reach_);
      b.upper = at_centre + reach_;
    }
    return b;
  }

  void collect(double limit) {
    candidates_.clear();
    bvh_.for_each_below(m_, reach_, limit, [&](std::uint32_t i) { candidates_.push_back(i); });
    std::sort(candidates_.begin(), candidates_.end());
  }

  const Node& node_;
  glm::dvec3 offset_;
  const OperandBvh& bvh_;
  double rounding_;
  double k_;
  std::vector<bool> lipschitz_, bare_spheres_;
  glm::dvec3 m_{0.0};
  double reach_ = 0.0;
  std::vector<std::uint32_t> candidates_, kept_;
};

}  // namespace

glm::dvec3 OperandGrid::cell_center(int x, int y, int z) const {
  return lower + cell_size * (glm::dvec3(x, y, z) + 0.5);
}

bool grid_can_prune(const Node& node) {
  if (node.kind != NodeKind::Union && node.kind != NodeKind::SmoothUnion) return false;
  if (node.children.size() < 2) return false;
  return std::all_of(node.children.begin(), node.children.end(),
                     [](const Node& child) { return node_bounds(child).has_value(); });
}

const Node* grid_union(const Scene& scene) {
  if (scene.render.pruning == Pruning::None) return nullptr;
  const std::size_t least = scene.render.pruning == Pruning::Grid ? 2 : kAutoGridOperands;
  const Node* best = nullptr;
  const auto visit = [&](const Node& node, const auto& self) -> void {
    if (grid_can_prune(node) && node.children.size() >= least &&
        (!best || node.children.size() > best->children.size())) {
      best = &node;
    }
    for (const Node& child : node.children) self(child, self);
  };
  visit(scene.sdf, visit);
  return best;
}

std::uint64_t grid_host_bytes(long long cells, std::uint64_t listed) {
  return 4 * (3 * static_cast<std::uint64_t>(cells) + 2 * listed);
}

OperandGrid build_operand_grid(const Node& union_node, const glm::dvec3& offset,
                               const std::optional<AvailableMemory>& memory) {
  std::vector<OperandBounds> bounds;
  bounds.reserve(union_node.children.size());
  glm::dvec3 lower(kInfinity), upper(-kInfinity);
  double gain = 1.0;
  for (const Node& child : union_node.children) {
    const BoundingSphere b = *node_bounds(child);
    bounds.push_back({b.center - offset, b.radius, b.gain});
    lower = glm::min(lower, bounds.back().center - b.radius);
    upper = glm::max(upper, bounds.back().center + b.radius);
    gain = std::max(gain, b.gain);
  }
  const std::size_t n = bounds.size();
  const double k = union_node.kind == NodeKind::SmoothUnion ? smooth_k(union_node) : 0.0;

  OperandGrid grid;
  // About four cells an operand: cells near the operands' size keep each list to the few that
  // meet it, and the grid costs a few words an operand (docs/performance.md).
  const glm::dvec3 extent = glm::max(upper - lower, glm::dvec3(1e-9));
  const double target_cells = std::clamp(8.0 * static_cast<double>(n), 64.0, static_cast<double>(kMaxGridCells) / 2.0);
  grid.cell_size = std::cbrt(extent.x * extent.y * extent.z / target_cells);
  grid.cell_size = std::max(grid.cell_size, max_component(extent) / 4096.0);
  // The margin keeps every operand's sphere a cell and 2k inside the grid, so that the bound outside
  // stays above s / gain there: (distance + margin) / gain - k.
  grid.outside_margin = grid.cell_size + 2.0 * k * gain;
  grid.outside_inverse_gain = 1.0 / gain;
  grid.outside_undershoot = k;
  grid.lower = lower - grid.outside_margin;
  const glm::dvec3 span = extent + 2.0 * grid.outside_margin;
  grid.dims = glm::max(glm::ivec3(glm::ceil(span / grid.cell_size)), glm::ivec3(1));
  grid.upper = grid.lower + glm::dvec3(grid.dims) * grid.cell_size;

  // The kernel's float: a few units of the last place of the largest coordinate met.
  const double largest = max_component(glm::max(glm::abs(grid.lower), glm::abs(grid.upper)));
  const double rounding = 64.0 * FLT_EPSILON * (largest + max_component(extent) + k);
  const double reach = 0.5 * std::sqrt(3.0) * grid.cell_size;

  const long long cells = grid.cell_count();
  // Every cell lists at least one operand; the lists' length is known only as they are pruned.
  std::atomic<std::uint64_t> listed{static_cast<std::uint64_t>(cells)};
  const auto require_memory = [&](std::uint64_t listed_at_least) {
    if (!memory) return;
    const std::uint64_t needed = grid_host_bytes(cells, listed_at_least);
    const std::string shortfall = memory_shortfall(needed, *memory);
    if (shortfall.empty()) return;
    throw InputError(
        fmt::format("the {} of {} operands needs an operand grid (render.pruning) of {} x {} x {} cells "
                    "listing at least {} operands: {} of host memory, {}",
                    node_kind_name(union_node.kind), n, grid.dims.x, grid.dims.y, grid.dims.z, listed_at_least,
                    bytes_and_gibibytes(needed), shortfall));
  };
  require_memory(listed);

  const OperandBvh bvh(std::move(bounds));
  constexpr long long kCellsPerChunk = 1024;
  const long long chunks = (cells + kCellsPerChunk - 1) / kCellsPerChunk;
  std::vector<std::vector<std::uint32_t>> chunk_operands(static_cast<std::size_t>(chunks));
  std::vector<std::uint32_t> cell_counts(static_cast<std::size_t>(cells));
  ProgressLine progress("operand grid", chunks, static_cast<double>(kCellsPerChunk));
  tbb::parallel_for(0LL, chunks, [&](long long chunk) {
    CellPruner pruner(union_node, offset, bvh, rounding);
    std::vector<std::uint32_t>& out = chunk_operands[static_cast<std::size_t>(chunk)];
    const long long end = std::min(cells, (chunk + 1) * kCellsPerChunk);
    for (long long c = chunk * kCellsPerChunk; c < end; ++c) {
      const int x = static_cast<int>(c % grid.dims.x);
      const int y = static_cast<int>((c / grid.dims.x) % grid.dims.y);
      const int z = static_cast<int>(c / (static_cast<long long>(grid.dims.x) * grid.dims.y));
      const std::size_t before = out.size();
      pruner.prune(grid.cell_center(x, y, z), reach, out);
      cell_counts[static_cast<std::size_t>(c)] = static_cast<std::uint32_t>(out.size() - before);
    }
    // The chunk's cells were counted once already.
    require_memory(listed += out.size() - static_cast<std::uint64_t>(end - chunk * kCellsPerChunk));
    progress.advance();
  });
  grid.cell_start.resize(static_cast<std::size_t>(cells) + 1);
  grid.cell_start[0] = 0;
  for (long long c = 0; c < cells; ++c) grid.cell_start[c + 1] = grid.cell_start[c] + cell_counts[c];
  // Each chunk's lists are freed as they are copied: at a million operands the lists take hundreds
  // of megabytes, and two whole copies of them set the process's peak memory.
  grid.operands.reserve(grid.cell_start.back());
  for (auto& out : chunk_operands) {
    grid.operands.insert(grid.operands.end(), out.begin(), out.end());
    std::vector<std::uint32_t>().swap(out);
  }
  return grid;
}

}  // namespace clmarch
