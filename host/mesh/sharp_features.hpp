// Sharp features kept (`clmarch mesh --sharp`), as extended marching cubes keeps them (Kobbelt,
// Botsch, Schwanecke and Seidel, 2001): marching cubes puts every vertex on a grid edge, so a box's
// edges and corners, which cross cells, are cut off. Where the normals of a cell's vertices spread
// wider than an angle, the cell's piece of surface becomes a fan around one new vertex placed where
// the tangent planes of those vertices meet (their quadric error minimised, with the directions the
// planes do not fix taken from the vertices' mean); then each mesh edge between two such fans is
// flipped to join the two new vertices, so that the feature line becomes a line of the mesh.
//
// Only a cell's inside changes: the edges on its faces stay, so the mesh stays closed, edge-manifold
// and oriented as marching made it. Where the planes meet outside the cell, the new vertex is the
// cell's nearest point to where they meet (keeping marching's triangles there instead left a box's
// edges up to 0.8 of a cell off at 32 cells, the nearest point 0.3). Fans and flips that would
// make a sliver, turn a triangle against the field's normals or fold two triangles onto each
// other are not made: those cells keep marching's triangles.
#pragma once

#include "mesh/mesh_grid.hpp"
#include "mesh/triangle_mesh.hpp"

#include <cstdint>
#include <vector>

namespace clmarch {

struct SharpSettings {
  /// A cell is a feature where two of its vertices' normals differ by more than this.
  double angle_degrees = 30.0;
  /// Directions in which the tangent planes' quadric curves less than this share of its strongest
  /// are left to the vertices' mean (one such direction along an edge, none at a corner).
  double rank_threshold = 0.1;
};

struct SharpStats {
  /// Cells whose surface became a fan around a new vertex.
  std::uint64_t feature_cells = 0;
  /// Feature cells whose planes met outside the cell: the new vertex moved to the cell's nearest point.
  std::uint64_t clamped_cells = 0;
  /// Feature cells whose fan would have had a sliver, a triangle turned against the field's normals
  /// or two triangles folded onto each other (a cone's tip, a fractal's noise): marching's
  /// triangles kept.
  std::uint64_t folded_cells = 0;
  /// Edges flipped to join two new vertices (a flip that would make a sliver, turn a triangle
  /// against the field's normal at its old vertex or fold the two is not made).
  std::uint64_t flipped_edges = 0;
};

/// Sharpens mesh in place: cell_of_triangle[t] is the cell_key (mesh_grid.hpp) of triangle t, the triangles of a
/// cell consecutive. mesh has normals and colours; new vertices get their cell's mean colour and
/// normal. Returns what was done.
SharpStats sharpen_features(TriangleMesh& mesh, std::vector<std::uint64_t>& cell_of_triangle, const MeshGrid& grid,
                            const SharpSettings& settings);

}  // namespace clmarch
