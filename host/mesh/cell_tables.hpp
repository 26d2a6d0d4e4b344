// The triangles of a grid cell for each of the 256 ways its corners can lie below or above the
// level, for marching cubes and for marching tetrahedra. Both tables are generated here when first
// used (cell_tables.cpp says how), never typed in.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace clmarch {

/// How a cell becomes triangles.
enum class CellMethod {
  /// Marching cubes: vertices on the cell's 12 edges only, about half the triangles of tetrahedra.
  /// A face whose diagonal corners lie on the same side (the ambiguous face) is always cut so that
  /// its corners below the level are apart, in both cells that share it, so the mesh stays closed.
  Cubes,
  /// Marching tetrahedra: each cell split into the six tetrahedra around its main diagonal (Kuhn's
  /// split), vertices also on face and main diagonals.
  Tetrahedra,
};
/// Each CellMethod's name, in enum order (`clmarch mesh --cells`).
inline constexpr std::string_view kCellMethodNames[] = {"cubes", "tetrahedra"};

/// A cell's corner c is at offset (c & 1, c >> 1 & 1, c >> 2 & 1) in cells. A cell edge runs from
/// corner `from` to corner from | step, where step's bits are disjoint from from's: along an axis
/// (step 1, 2, 4), a face diagonal (3, 5, 6) or the main diagonal (7).
struct CellEdge {
  std::uint8_t from = 0;
  std::uint8_t step = 0;
};

/// The triangles of one case, counter-clockwise seen from the side above the level.
struct CellCase {
  int count = 0;
  std::array<std::array<CellEdge, 3>, 12> triangles{};
};

/// Case bits: bit c set where corner c's value is below the level.
using CellTable = std::array<CellCase, 256>;

/// The table of method.
const CellTable& cell_table(CellMethod method);

/// The steps of the edges method puts vertices on, ascending (cubes: 1 2 4; tetrahedra: 1 ... 7),
/// and how many there are.
struct EdgeSteps {
  int count = 0;
  std::array<int, 7> steps{};
  /// For each step 1 ... 7 its position in steps, or -1.
  std::array<int, 8> slot{};
};
const EdgeSteps& edge_steps(CellMethod method);

}  // namespace clmarch
