// Generating the cell tables.
//
// Marching cubes: on each of the cell's six faces, the level's crossings of the face's edges are
// joined by segments, directed so that seen from outside the cell the corners below the level lie
// on the segment's right; a face with four crossings (its diagonal corners on the same side) gets
// the two segments that cut off its two corners below. The rule reads only the face's four corners,
// so the cell on the other side of the face draws the same segments, in the opposite direction
// (it sees the face from the other side): every mesh edge on a face is in one triangle of each cell
// once in each direction. The segments chain into closed loops around the cell (each crossed edge
// ends one segment and starts another); each loop is split into triangles without a diagonal
// between two vertices on one face (such a diagonal would lie in the face, where the neighbour's
// loop could use it too), the shortest such split where several exist.
//
// Marching tetrahedra: the six tetrahedra of Kuhn's split (each walks from corner 0 to corner 7
// along the axes in one of their six orders, so its corners' bit sets nest: every edge runs from a
// subset to a superset), one triangle where one corner of a tetrahedron is alone on its side, two
// (a quad) where two are; each oriented by the edges' midpoints against the direction from the
// corners below to those above, which never degenerates.
#include "mesh/cell_tables.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

namespace clmarch {
namespace {

glm::dvec3 cell_corner_point(int c) { return {c & 1, (c >> 1) & 1, (c >> 2) & 1}; }

/// The cell edge between corners a and b (their bits nest).
CellEdge cell_edge_between(int a, int b) {
  const int from = std::min(a, b), to = std::max(a, b);
  if ((from & to) != from) throw std::logic_error("cell_tables: corners whose bits do not nest");
  return {static_cast<std::uint8_t>(from), static_cast<std::uint8_t>(to ^ from)};
}

glm::dvec3 cell_edge_midpoint(const CellEdge& e) {
  return 0.5 * (cell_corner_point(e.from) + cell_corner_point(e.from | e.step));
}

/// A cube edge's key for maps: from * 8 + step.
int cell_edge_key(const CellEdge& e) { return e.from * 8 + e.step; }

/// Whether two axis-aligned cube edges lie on a common face: some axis other than both edges'
/// own, on which both have the same side.
bool cell_edges_share_face(const CellEdge& a, const CellEdge& b) {
  for (int axis = 0; axis < 3; ++axis) {
    const int bit = 1 << axis;
    if ((a.step & bit) || (b.step & bit)) continue;
    if ((a.from & bit) == (b.from & bit)) return true;
  }
  return false;
}

/// Splits a loop of cube-edge vertices into triangles (keeping its direction): no diagonal
/// between vertices on one face, then the shortest diagonals (dynamic programming over the
/// polygon's triangulations).
std::vector<std::array<CellEdge, 3>> split_cell_loop(const std::vector<CellEdge>& loop) {
  const int n = static_cast<int>(loop.size());
  constexpr double kFaceDiagonal = 1000.0;
  const auto diagonal_cost = [&](int i, int j) {
    if (j - i == 1 || (i == 0 && j == n - 1)) return 0.0;
    return (cell_edges_share_face(loop[i], loop[j]) ? kFaceDiagonal : 0.0) +
           glm::length(cell_edge_midpoint(loop[i]) - cell_edge_midpoint(loop[j]));
  };
  std::vector<std::vector<double>> cost(n, std::vector<double>(n, 0.0));
  std::vector<std::vector<int>> apex(n, std::vector<int>(n, -1));
  for (int gap = 2; gap < n; ++gap) {
    for (int i = 0; i + gap < n; ++i) {
      const int j = i + gap;
      cost[i][j] = std::numeric_limits<double>::infinity();
      for (int k = i + 1; k < j; ++k) {
        const double c = cost[i][k] + cost[k][j] + diagonal_cost(i, k) + diagonal_cost(k, j);
        if (c < cost[i][j]) {
          cost[i][j] = c;
          apex[i][j] = k;
        }
      }
    }
  }
  if (cost[0][n - 1] >= kFaceDiagonal) throw std::logic_error("cell_tables: a loop with no split off the faces");
  std::vector<std::array<CellEdge, 3>> out;
  std::vector<std::pair<int, int>> pending = {{0, n - 1}};
  while (!pending.empty()) {
    const auto [i, j] = pending.back();
    pending.pop_back();
    if (j - i < 2) continue;
    const int k = apex[i][j];
    out.push_back({loop[i], loop[k], loop[j]});
    pending.push_back({i, k});
    pending.push_back({k, j});
  }
  return out;
}

CellCase marching_cube_case(int below) {
  const auto is_below = [&](int c) { return ((below >> c) & 1) != 0; };
  // Segments on the faces: start edge -> end edge.
  std::map<int, CellEdge> next;
  std::map<int, CellEdge> edges;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      // The face's corners counter-clockwise seen from outside: (u, v) with e_u x e_v outward.
      int u = (axis + 1) % 3, v = (axis + 2) % 3;
      if (side == 0) std::swap(u, v);
      const int base = side << axis;
      const std::array<int, 4> corners = {base, base | (1 << u), base | (1 << u) | (1 << v), base | (1 << v)};
      const auto flat = [&](const glm::dvec3& p) { return glm::dvec2(p[u], p[v]); };
      std::vector<int> crossed;  // face edge k joins corners k and k + 1
      for (int k = 0; k < 4; ++k) {
        if (is_below(corners[k]) != is_below(corners[(k + 1) % 4])) crossed.push_back(k);
      }
      const auto face_edge = [&](int k) { return cell_edge_between(corners[k], corners[(k + 1) % 4]); };
      const auto add_segment = [&](CellEdge p, CellEdge q, int below_corner) {
        // Direct it so that the corner below lies on its right, seen from outside.
        const glm::dvec2 a = flat(cell_edge_midpoint(p)), b = flat(cell_edge_midpoint(q)),
                         c = flat(cell_corner_point(below_corner));
        const double side_of = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (side_of > 0.0) std::swap(p, q);
        if (!next.emplace(cell_edge_key(p), q).second)
          throw std::logic_error("cell_tables: two segments leave one edge");
        edges[cell_edge_key(p)] = p;
      };
      if (crossed.size() == 2) {
        int below_corner = -1;
        for (int c : corners) {
          if (is_below(c)) below_corner = c;
        }
        add_segment(face_edge(crossed[0]), face_edge(crossed[1]), below_corner);
      } else if (crossed.size() == 4) {
        // The ambiguous face: cut off each corner below (between face edges k - 1 and k).
        for (int k = 0; k < 4; ++k) {
          if (is_below(corners[k])) add_segment(face_edge((k + 3) % 4), face_edge(k), corners[k]);
        }
      }
    }
  }
  CellCase out;
  while (!next.empty()) {
    std::vector<CellEdge> loop = {edges.at(next.begin()->first)};
    for (;;) {
      const auto it = next.find(cell_edge_key(loop.back()));
      if (it == next.end()) throw std::logic_error("cell_tables: an open loop");
      const CellEdge to = it->second;
      next.erase(it);
      if (cell_edge_key(to) == cell_edge_key(loop.front())) break;
      loop.push_back(to);
    }
    for (const auto& triangle : split_cell_loop(loop))
      out.triangles.at(static_cast<std::size_t>(out.count++)) = triangle;
  }
  return out;
}

/// Kuhn's six tetrahedra of the unit cube.
constexpr std::array<std::array<int, 4>, 6> kKuhnTetrahedra = {{
    {0, 1, 3, 7},
    {0, 1, 5, 7},
    {0, 2, 3, 7},
    {0, 2, 6, 7},
    {0, 4, 5, 7},
    {0, 4, 6, 7},
}};

CellCase marching_tetra_case(int below) {
  CellCase out;
  for (const auto& tet : kKuhnTetrahedra) {
    std::array<int, 4> low_side{}, high_side{};
    int lows = 0, highs = 0;
    for (int c : tet) (((below >> c) & 1) != 0 ? low_side[lows++] : high_side[highs++]) = c;
    if (lows == 0 || highs == 0) continue;
    glm::dvec3 up(0.0);
    for (int k = 0; k < highs; ++k) up += cell_corner_point(high_side[k]) / static_cast<double>(highs);
    for (int k = 0; k < lows; ++k) up -= cell_corner_point(low_side[k]) / static_cast<double>(lows);
    const auto add = [&](CellEdge a, CellEdge b, CellEdge c) {
      const glm::dvec3 n =
          glm::cross(cell_edge_midpoint(b) - cell_edge_midpoint(a), cell_edge_midpoint(c) - cell_edge_midpoint(a));
      out.triangles.at(static_cast<std::size_t>(out.count++)) =
          glm::dot(n, up) > 0.0 ? std::array{a, b, c} : std::array{a, c, b};
    };
    if (lows == 1 || highs == 1) {
      const int apex = lows == 1 ? low_side[0] : high_side[0];
      const std::array<int, 4>& others = lows == 1 ? high_side : low_side;
      add(cell_edge_between(apex, others[0]), cell_edge_between(apex, others[1]), cell_edge_between(apex, others[2]));
    } else {
      // A quad around the tetrahedron: low0-high0, low0-high1, low1-high1, low1-high0.
      const CellEdge a = cell_edge_between(low_side[0], high_side[0]), b = cell_edge_between(low_side[0], high_side[1]);
      const CellEdge c = cell_edge_between(low_side[1], high_side[1]), d = cell_edge_between(low_side[1], high_side[0]);
      add(a, b, c);
      add(a, c, d);
    }
  }
  return out;
}

CellTable make_cell_table(CellCase (*make)(int)) {
  CellTable table;
  for (int below = 0; below < 256; ++below) table[static_cast<std::size_t>(below)] = make(below);
  return table;
}

EdgeSteps make_edge_steps(std::initializer_list<int> steps) {
  EdgeSteps out;
  out.slot.fill(-1);
  for (int step : steps) {
    out.slot[static_cast<std::size_t>(step)] = out.count;
    out.steps[static_cast<std::size_t>(out.count++)] = step;
  }
  return out;
}

}  // namespace

const CellTable& cell_table(CellMethod method) {
  static const CellTable cubes = make_cell_table(marching_cube_case);
  static const CellTable tetrahedra = make_cell_table(marching_tetra_case);
  return method == CellMethod::Cubes ? cubes : tetrahedra;
}

const EdgeSteps& edge_steps(CellMethod method) {
  static const EdgeSteps cubes = make_edge_steps({1, 2, 4});
  static const EdgeSteps tetrahedra = make_edge_steps({1, 2, 3, 4, 5, 6, 7});
  return method == CellMethod::Cubes ? cubes : tetrahedra;
}

}  // namespace clmarch
