// Sampling bricks, closing the set over crossed faces, numbering edge vertices and writing triangles.
#include "mesh/brick_surface.hpp"

#include "common/cancellation.hpp"
#include "common/errors.hpp"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>
#include <tuple>

namespace clmarch {
namespace {

constexpr int kSamplesPerSide = kBrickSamples;
constexpr std::size_t kBrickPoints = static_cast<std::size_t>(kSamplesPerSide) * kSamplesPerSide * kSamplesPerSide;
/// A brick's lower edge ends: local coordinates 0 ... kBrickCells - 1.
constexpr int kBrickEnds = kBrickCells * kBrickCells * kBrickCells;

constexpr int brick_sample_index(int x, int y, int z) { return (z * kSamplesPerSide + y) * kSamplesPerSide + x; }
constexpr int brick_end_index(int x, int y, int z) { return (z * kBrickCells + y) * kBrickCells + x; }
constexpr std::uint16_t kFullRow = (1u << kSamplesPerSide) - 1;

/// Set bits of v, inline: without a popcnt target std::popcount calls libgcc.
inline int bit_count(std::uint64_t v) {
  v = v - ((v >> 1) & 0x5555555555555555ull);
  v = (v & 0x3333333333333333ull) + ((v >> 2) & 0x3333333333333333ull);
  v = (v + (v >> 4)) & 0x0f0f0f0f0f0f0f0full;
  return static_cast<int>((v * 0x0101010101010101ull) >> 56);
}

/// The cases of the 8 cells of row (y, z) of a brick, from its rows of below bits; false (cases
/// untouched) when every corner of the row lies on one side.
bool row_cases(const std::array<std::uint16_t, 81>& rows, int y, int z, std::array<int, 8>& cases) {
  const unsigned r00 = rows[static_cast<std::size_t>(z * kSamplesPerSide + y)];
  const unsigned r10 = rows[static_cast<std::size_t>(z * kSamplesPerSide + y + 1)];
  const unsigned r01 = rows[static_cast<std::size_t>((z + 1) * kSamplesPerSide + y)];
  const unsigned r11 = rows[static_cast<std::size_t>((z + 1) * kSamplesPerSide + y + 1)];
  if ((r00 | r10 | r01 | r11) == 0 || (r00 & r10 & r01 & r11) == kFullRow) return false;
  for (int x = 0; x < kBrickCells; ++x) {
    // Corner bits: x 1, y 2, z 4.
    cases[static_cast<std::size_t>(x)] = static_cast<int>(((r00 >> x) & 3) | (((r10 >> x) & 3) << 2) |
                                                          (((r01 >> x) & 3) << 4) | (((r11 >> x) & 3) << 6));
  }
  return true;
}

using BrickRange = tbb::blocked_range<std::size_t>;

/// The most triangles a cell of table has.
std::size_t max_triangles_per_cell(const CellTable& table) {
  int most = 0;
  for (const CellCase& cell : table) most = std::max(most, cell.count);
  return static_cast<std::size_t>(most);
}

}  // namespace

BrickSurface::BrickSurface(const MeshGrid& grid, double level, CellMethod method)
    : grid_(grid),
      level_(level),
      table_(cell_table(method)),
      steps_(edge_steps(method)),
      words_(kBrickEnds * edge_steps(method).count / 64) {
  // Bit x of a row's 8 edges to bit x * steps of its slots.
  for (unsigned mask = 0; mask < 256; ++mask) {
    for (int x = 0; x < kBrickCells; ++x) {
      if ((mask >> x) & 1u) spread_[mask] |= std::uint64_t{1} << (x * steps_.count);
    }
  }
}

std::uint64_t BrickSurface::key(const glm::ivec3& b) const {
  return (static_cast<std::uint64_t>(b.z) * static_cast<std::uint64_t>(grid_.bricks.y) +
          static_cast<std::uint64_t>(b.y)) *
             static_cast<std::uint64_t>(grid_.bricks.x) +
         static_cast<std::uint64_t>(b.x);
}

BrickSurface::BelowRows BrickSurface::below_rows(const float* samples) const {
  BelowRows rows{};
  const auto level = static_cast<float>(level_);
  for (std::size_t row = 0; row < rows.size(); ++row) {
    unsigned bits = 0;
    // The level in float, as the samples are: a value equal to it is above, NaN too.
    for (int x = 0; x < kSamplesPerSide; ++x)
      bits |= static_cast<unsigned>(samples[row * kSamplesPerSide + x] < level) << x;
    rows[row] = static_cast<std::uint16_t>(bits);
  }
  return rows;
}

bool BrickSurface::face_crossed(const BelowRows& rows, int axis, int side) const {
  unsigned any = 0, all = kFullRow;
  for (int i = 0; i < kSamplesPerSide; ++i) {
    for (int j = 0; j < kSamplesPerSide; ++j) {
      // Axis x: bit side * 8 of every row; y: the rows at y = side * 8; z: those at z = side * 8.
      unsigned bit;
      if (axis == 0) {
        bit = (rows[static_cast<std::size_t>(i * kSamplesPerSide + j)] >> (side * kBrickCells)) & 1u;
      } else {
        const int y = axis == 1 ? side * kBrickCells : i, z = axis == 2 ? side * kBrickCells : i;
        bit = (rows[static_cast<std::size_t>(z * kSamplesPerSide + y)] >> j) & 1u;
      }
      any |= bit;
      all &= bit ? kFullRow : 0u;
    }
  }
  return any != 0 && all == 0;
}

std::uint64_t BrickSurface::sample(MeshField& field, const std::vector<glm::ivec3>& bricks, std::size_t batch_points,
                                   const std::function<void(std::size_t bricks)>& on_batch) {
  // A brick queued but not yet sampled is held with slot kQueued, so that it is queued once.
  constexpr std::uint32_t kQueued = std::numeric_limits<std::uint32_t>::max();
  std::vector<glm::ivec3> pending;
  for (const glm::ivec3& b : bricks) {
    if (slot_of_.emplace(key(b), kQueued).second) pending.push_back(b);
  }
  const std::size_t per_batch = std::max<std::size_t>(1, batch_points / kBrickPoints);
  std::uint64_t added = 0;
  bool first_round = true;
  while (!pending.empty()) {
    std::vector<glm::ivec3> next;
    for (std::size_t first = 0; first < pending.size(); first += per_batch) {
      const std::size_t count = std::min(per_batch, pending.size() - first);
      const std::span<const glm::ivec3> batch(pending.data() + first, count);
      std::vector<glm::ivec3> corners(count);
      for (std::size_t b = 0; b < count; ++b) corners[b] = batch[b] * kBrickCells;
      auto block = std::make_unique<float[]>(count * kBrickPoints);
      field.sample_bricks(corners, kSamplesPerSide, grid_.cell, std::span<float>(block.get(), count * kBrickPoints));
      for (std::size_t b = 0; b < count; ++b) {
        slot_of_[key(batch[b])] = static_cast<std::uint32_t>(corners_.size());
        corners_.push_back(batch[b]);
        samples_.push_back(block.get() + b * kBrickPoints);
      }
      // The neighbours across crossed faces that are inside the grid and not yet held.
      for (std::size_t b = 0; b < count; ++b) {
        const BelowRows below = below_rows(block.get() + b * kBrickPoints);
        for (int axis = 0; axis < 3; ++axis) {
          for (int side = 0; side < 2; ++side) {
            glm::ivec3 n = batch[b];
            n[axis] += side == 0 ? -1 : 1;
            if (n[axis] < 0 || n[axis] >= grid_.bricks[axis] || slot_of_.count(key(n))) continue;
            if (!face_crossed(below, axis, side)) continue;
            slot_of_.emplace(key(n), kQueued);
            next.push_back(n);
          }
        }
      }
      blocks_.push_back(std::move(block));
      if (on_batch) on_batch(first_round ? count : 0);
    }
    added += first_round ? 0 : pending.size();
    first_round = false;
    pending = std::move(next);
  }
  return added;
}

std::uint32_t BrickSurface::vertex_number(std::uint32_t id, int bit) const {
  const std::size_t word = static_cast<std::size_t>(id) * words_ + static_cast<std::size_t>(bit >> 6);
  const std::uint64_t before = edge_bits_[word] & ((std::uint64_t{1} << (bit & 63)) - 1);
  return first_vertex_[id] + bits_before_[word] + static_cast<std::uint32_t>(bit_count(before));
}

void BrickSurface::march() {
  const std::size_t n = corners_.size();
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0u);
  std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) {
    const glm::ivec3 &p = corners_[a], &q = corners_[b];
    return std::tie(p.z, p.y, p.x) < std::tie(q.z, q.y, q.x);
  });
  std::vector<std::uint32_t> id_of_slot(n);
  for (std::uint32_t id = 0; id < n; ++id) id_of_slot[order_[id]] = id;
  upper_.assign(n, {});
  edge_bits_.assign(n * static_cast<std::size_t>(words_), 0);
  bits_before_.assign(n * static_cast<std::size_t>(words_), 0);
  std::vector<std::uint32_t> vertex_count(n, 0);
  std::vector<std::uint64_t> triangle_count(n, 0);
  std::atomic<std::uint64_t> surface_cells{0};
  const int steps = steps_.count;

  // Each brick's crossed edges, its triangles' count and its upper neighbours.
  tbb::parallel_for(BrickRange(0, n, 16), [&](const BrickRange& range) {
    throw_if_cancelled();
    std::uint64_t cells = 0;
    for (std::size_t id = range.begin(); id < range.end(); ++id) {
      const glm::ivec3 brick = corners_[order_[id]];
      for (int o = 0; o < 8; ++o) {
        // A brick past the grid has no key of its own (key() would wrap to another brick's).
        const glm::ivec3 upper = brick + step_offset(o);
        const auto it =
            glm::any(glm::greaterThanEqual(upper, grid_.bricks)) ? slot_of_.end() : slot_of_.find(key(upper));
        upper_[id][o] = o == 0                 ? static_cast<std::int32_t>(id)
                        : it == slot_of_.end() ? -1
                                               : static_cast<std::int32_t>(id_of_slot[it->second]);
      }
      const BelowRows rows = below_rows(samples_[order_[id]]);
      std::uint64_t* bits = &edge_bits_[id * static_cast<std::size_t>(words_)];
      std::uint64_t triangles = 0;
      for (int z = 0; z < kBrickCells; ++z) {
        for (int y = 0; y < kBrickCells; ++y) {
          // The row's crossed edges of each step, 8 bits over x, spread to bit x * steps + k.
          const unsigned here = rows[static_cast<std::size_t>(z * kSamplesPerSide + y)];
          std::uint64_t crossed = 0;
          for (int k = 0; k < steps; ++k) {
            const glm::ivec3 d = step_offset(steps_.steps[static_cast<std::size_t>(k)]);
            const unsigned there = rows[static_cast<std::size_t>((z + d.z) * kSamplesPerSide + y + d.y)] >> d.x;
            crossed |= spread_[(here ^ there) & 0xffu] << k;
          }
          if (crossed != 0) {
            const int first = brick_end_index(0, y, z) * steps;
            const int shift = first & 63;
            bits[first >> 6] |= crossed << shift;
            if (shift != 0 && shift + kBrickCells * steps > 64) bits[(first >> 6) + 1] |= crossed >> (64 - shift);
          }
          std::array<int, 8> cases{};
          if (!row_cases(rows, y, z, cases)) continue;
          for (int cell_case : cases) {
            triangles += static_cast<std::uint64_t>(table_[static_cast<std::size_t>(cell_case)].count);
            cells += cell_case != 0 && cell_case != 255;
          }
        }
      }
      std::uint32_t count = 0;
      for (int w = 0; w < words_; ++w) {
        bits_before_[id * static_cast<std::size_t>(words_) + static_cast<std::size_t>(w)] =
            static_cast<std::uint16_t>(count);
        count += static_cast<std::uint32_t>(bit_count(bits[w]));
      }
      vertex_count[id] = count;
      triangle_count[id] = triangles;
    }
    surface_cells += cells;
  });
  surface_cells_ = surface_cells;

  first_vertex_.assign(n + 1, 0);
  std::uint64_t vertices = 0;
  for (std::size_t id = 0; id < n; ++id) {
    first_vertex_[id] = static_cast<std::uint32_t>(vertices);
    vertices += vertex_count[id];
    if (vertices > std::numeric_limits<std::uint32_t>::max()) {
      throw OutputError(fmt::format("the mesh has more than {} vertices, which its 32-bit indices cannot number",
                                    std::numeric_limits<std::uint32_t>::max()));
    }
  }
  first_vertex_[n] = static_cast<std::uint32_t>(vertices);

  // Bricks on the grid's upper faces may have cells whose edges belong to a brick past the grid:
  // their triangles are counted by writing them, so that the count is exact before any is written.
  std::uint64_t dropped = 0;
  std::vector<MeshTriangle> scratch(static_cast<std::size_t>(kBrickEnds) * max_triangles_per_cell(table_));
  for (std::size_t id = 0; id < n; ++id) {
    if (!glm::any(glm::equal(corners_[order_[id]], grid_.bricks - 1))) continue;
    const std::uint64_t kept = brick_triangles(id, scratch.data());
    dropped += triangle_count[id] - kept;
    triangle_count[id] = kept;
  }
  dropped_triangles_ = dropped;
  first_triangle_.assign(n + 1, 0);
  for (std::size_t id = 0; id < n; ++id) first_triangle_[id + 1] = first_triangle_[id] + triangle_count[id];
}

std::uint64_t BrickSurface::brick_triangles(std::size_t id, MeshTriangle* out, std::uint64_t* cells) const {
  const BelowRows rows = below_rows(samples_[order_[id]]);
  const glm::ivec3 corner = corners_[order_[id]] * kBrickCells;
  const int steps = steps_.count;
  const MeshTriangle* const first = out;
  for (int z = 0; z < kBrickCells; ++z) {
    for (int y = 0; y < kBrickCells; ++y) {
      std::array<int, 8> cases{};
      if (!row_cases(rows, y, z, cases)) continue;
      for (int x = 0; x < kBrickCells; ++x) {
        const CellCase& cell = table_[static_cast<std::size_t>(cases[static_cast<std::size_t>(x)])];
        for (int t = 0; t < cell.count; ++t) {
          MeshTriangle triangle{};
          bool kept = true;
          for (int k = 0; k < 3 && kept; ++k) {
            const CellEdge& e = cell.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)];
            const glm::ivec3 end = glm::ivec3(x, y, z) + step_offset(e.from);
            const glm::ivec3 o = end / kBrickCells;
            const std::int32_t owner = upper_[id][static_cast<std::size_t>(o.x + 2 * o.y + 4 * o.z)];
            kept = owner >= 0;
            if (!kept) break;
            const glm::ivec3 local = end - o * kBrickCells;
            const int bit = brick_end_index(local.x, local.y, local.z) * steps + steps_.slot[e.step];
            triangle[static_cast<std::size_t>(k)] = vertex_number(static_cast<std::uint32_t>(owner), bit);
          }
          if (!kept) continue;
          *out++ = triangle;
          if (cells) *cells++ = cell_key(grid_, corner + glm::ivec3(x, y, z));
        }
      }
    }
  }
  return static_cast<std::uint64_t>(out - first);
}

void BrickSurface::append_triangles(std::size_t first_brick, std::size_t end_brick, std::vector<MeshTriangle>& out,
                                    std::vector<std::uint64_t>* cells) const {
  const std::size_t base = out.size();
  out.resize(base + (first_triangle_[end_brick] - first_triangle_[first_brick]));
  if (cells) cells->resize(out.size());
  std::atomic<bool> miscounted{false};
  tbb::parallel_for(BrickRange(first_brick, end_brick, 16), [&](const BrickRange& range) {
    throw_if_cancelled();
    for (std::size_t id = range.begin(); id < range.end(); ++id) {
      const std::size_t at = base + (first_triangle_[id] - first_triangle_[first_brick]);
      if (brick_triangles(id, out.data() + at, cells ? cells->data() + at : nullptr) !=
          first_triangle_[id + 1] - first_triangle_[id])
        miscounted = true;
    }
  });
  // Fewer triangles than counted would leave indices of 0 in out.
  if (miscounted) {
    throw std::logic_error("BrickSurface: a cell inside the grid uses an edge of a brick that was not sampled");
  }
}

void BrickSurface::append_seeds(std::size_t b, std::vector<EdgeSeed>& seeds) const {
  const glm::ivec3 corner = corners_[order_[b]] * kBrickCells;
  const float* samples = samples_[order_[b]];
  const std::uint64_t* bits = &edge_bits_[b * static_cast<std::size_t>(words_)];
  const int steps = steps_.count;
  for (int w = 0; w < words_; ++w) {
    for (std::uint64_t word = bits[w]; word != 0; word &= word - 1) {
      const int bit = w * 64 + std::countr_zero(word);
      const int end = bit / steps;
      const int step = steps_.steps[static_cast<std::size_t>(bit % steps)];
      const glm::ivec3 local(end % kBrickCells, (end / kBrickCells) % kBrickCells, end / (kBrickCells * kBrickCells));
      const glm::ivec3 to = local + step_offset(step);
      seeds.push_back({corner + local, step, samples[brick_sample_index(local.x, local.y, local.z)],
                       samples[brick_sample_index(to.x, to.y, to.z)]});
    }
  }
}

void BrickSurface::release_samples() {
  samples_.clear();
  blocks_.clear();
}

}  // namespace clmarch
