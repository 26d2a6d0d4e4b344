// Feature cells to fans around their tangent planes' meeting point, then flips between fans.
#include "mesh/sharp_features.hpp"

#include "common/cancellation.hpp"

#include <glm/gtc/matrix_access.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace clmarch {
namespace {

/// The eigenvalues and unit eigenvectors (the columns of vectors) of the symmetric matrix a, by
/// cyclic Jacobi rotations: a 3x3 converges to double precision in a few sweeps.
void symmetric_eigen(glm::dmat3 a, glm::dvec3& values, glm::dmat3& vectors) {
  vectors = glm::dmat3(1.0);
  for (int sweep = 0; sweep < 32; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off <= 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]) || off == 0.0) break;
    for (int p = 0; p < 2; ++p) {
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // The rotation in the (p, q) plane that zeroes a[p][q].
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        glm::dmat3 rotation(1.0);
        rotation[p][p] = c;
        rotation[q][q] = c;
        rotation[q][p] = s;
        rotation[p][q] = -s;
        a = glm::transpose(rotation) * a * rotation;
        vectors = vectors * rotation;
      }
    }
  }
  values = glm::dvec3(a[0][0], a[1][1], a[2][2]);
}

/// The point nearest, in the least-squares sense, to the planes through points with normals,
/// relative to their mean: directions of the quadric weaker than rank_threshold times its strongest
/// keep the mean's coordinate.
glm::dvec3 planes_meeting_point(const std::vector<glm::dvec3>& points, const std::vector<glm::dvec3>& normals,
                                double rank_threshold) {
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  glm::dmat3 quadric(0.0);
  glm::dvec3 pull(0.0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3& n = normals[i];
    quadric += glm::outerProduct(n, n);
    pull += n * glm::dot(n, points[i] - mean);
  }
  glm::dvec3 values;
  glm::dmat3 vectors;
  symmetric_eigen(quadric, values, vectors);
  const double strongest = std::max({values.x, values.y, values.z});
  glm::dvec3 offset(0.0);
  for (int i = 0; i < 3; ++i) {
    if (values[i] <= rank_threshold * strongest) continue;
    const glm::dvec3 direction = glm::column(vectors, i);
    offset += direction * (glm::dot(direction, pull) / values[i]);
  }
  return mean + offset;
}

std::uint64_t edge_key(std::uint32_t from, std::uint32_t to) { return (std::uint64_t{from} << 32) | to; }

/// The triangles of one cell split into pieces that share no vertex.
std::vector<std::vector<MeshTriangle>> pieces_of(const MeshTriangle* first, std::size_t count) {
  std::vector<std::size_t> piece(count);
  std::iota(piece.begin(), piece.end(), 0);
  const auto root = [&](std::size_t i) {
    while (piece[i] != i) i = piece[i] = piece[piece[i]];
    return i;
  };
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = i + 1; j < count; ++j) {
      const bool shared = std::any_of(first[i].begin(), first[i].end(), [&](std::uint32_t v) {
        return std::find(first[j].begin(), first[j].end(), v) != first[j].end();
      });
      if (shared) piece[root(i)] = root(j);
    }
  }
  std::vector<std::vector<MeshTriangle>> pieces;
  std::vector<std::size_t> index_of_root(count, count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t r = root(i);
    if (index_of_root[r] == count) {
      index_of_root[r] = pieces.size();
      pieces.emplace_back();
    }
    pieces[index_of_root[r]].push_back(first[i]);
  }
  return pieces;
}

/// The boundary of a piece as one closed loop of its vertices in the triangles' direction, or empty
/// when its boundary is not one loop.
std::vector<std::uint32_t> boundary_loop(const std::vector<MeshTriangle>& piece) {
  std::unordered_set<std::uint64_t> edges;
  for (const MeshTriangle& t : piece) {
    for (int k = 0; k < 3; ++k) edges.insert(edge_key(t[static_cast<std::size_t>(k)], t[(k + 1) % 3]));
  }
  std::unordered_map<std::uint32_t, std::uint32_t> next;
  for (const std::uint64_t e : edges) {
    const auto from = static_cast<std::uint32_t>(e >> 32), to = static_cast<std::uint32_t>(e);
    if (edges.count(edge_key(to, from))) continue;
    if (!next.emplace(from, to).second) return {};
  }
  if (next.empty()) return {};
  std::vector<std::uint32_t> loop;
  std::uint32_t at = next.begin()->first;
  do {
    loop.push_back(at);
    const auto it = next.find(at);
    if (it == next.end() || loop.size() > next.size()) return {};
    at = it->second;
  } while (at != loop.front());
  return loop.size() == next.size() ? loop : std::vector<std::uint32_t>{};
}

/// Twice the area of the triangle a, b, c along its normal (counter-clockwise).
glm::dvec3 area_normal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::cross(b - a, c - a);
}

/// Whether a triangle with this area_normal is no sliver (sides of a thousandth of a cell: ten
/// times the root finding's tolerance) and faces the way of the field's normal given.
bool faces_along(const glm::dvec3& triangle, const glm::dvec3& field_normal, double cell) {
  return glm::length(triangle) > 1e-6 * cell * cell && glm::dot(triangle, field_normal) > 0.0;
}

/// Whether two triangles with these area_normals turn by less than about 155 degrees across their
/// edge: a sharper turn between two new triangles is a fold (a fractal's noise seen as features),
/// not an edge of a model. Slivers (under a thousandth of a cell's area) are let be: their normals
/// are rounding.
bool no_fold(const glm::dvec3& first, const glm::dvec3& second, double cell) {
  const double sliver = 2e-3 * cell * cell;
  if (glm::length(first) < sliver || glm::length(second) < sliver) return true;
  return glm::dot(first, second) > -0.9 * glm::length(first) * glm::length(second);
}

/// A fan triangle (a, b, centre): its edge a -> b lies on the cell's faces.
struct Fan {
  std::size_t triangle;
  std::uint32_t centre;
};

}  // namespace

SharpStats sharpen_features(TriangleMesh& mesh, std::vector<std::uint64_t>& cell_of_triangle, const MeshGrid& grid,
                            const SharpSettings& settings) {
  SharpStats stats;
  const double spread = std::cos(settings.angle_degrees * M_PI / 180.0);
  const glm::u64vec3 side = cell_key_sides(grid);
  std::vector<MeshTriangle> triangles;
  std::vector<std::uint64_t> cells;
  triangles.reserve(mesh.triangles.size());
  cells.reserve(mesh.triangles.size());
  std::vector<Fan> fans;
  std::vector<glm::dvec3> points, normals;
  for (std::size_t first = 0; first < mesh.triangles.size();) {
    throw_if_cancelled();
    const std::uint64_t key = cell_of_triangle[first];
    std::size_t end = first + 1;
    while (end < mesh.triangles.size() && cell_of_triangle[end] == key) ++end;
    for (const std::vector<MeshTriangle>& piece : pieces_of(mesh.triangles.data() + first, end - first)) {
      const auto keep = [&] {
        triangles.insert(triangles.end(), piece.begin(), piece.end());
        cells.insert(cells.end(), piece.size(), key);
      };
      const std::vector<std::uint32_t> loop = boundary_loop(piece);
      bool feature = false;
      for (std::size_t i = 0; i < loop.size() && !feature; ++i) {
        for (std::size_t j = i + 1; j < loop.size() && !feature; ++j) {
          feature = glm::dot(mesh.normals[loop[i]], mesh.normals[loop[j]]) < spread;
        }
      }
      if (!feature) {
        keep();
        continue;
      }
      points.clear();
      normals.clear();
      for (const std::uint32_t v : loop) {
        points.push_back(mesh.positions[v]);
        normals.push_back(glm::dvec3(mesh.normals[v]));
      }
      const glm::dvec3 centre = planes_meeting_point(points, normals, settings.rank_threshold);
      const glm::u64vec3 index(key % side.x, key / side.x % side.y, key / (side.x * side.y));
      const glm::dvec3 low = grid.origin + glm::dvec3(index) * grid.cell;
      const glm::dvec3 inside = (centre - low) / grid.cell;
      // Planes meeting outside the cell (the feature passes a neighbour, or the planes are nearly
      // parallel): the cell's nearest point, so that fans stay in their cells.
      const bool outside = !(glm::all(glm::greaterThanEqual(inside, glm::dvec3(0.0))) &&
                             glm::all(glm::lessThanEqual(inside, glm::dvec3(1.0))));
      const glm::dvec3 clamped = low + glm::clamp(inside, 0.0, 1.0) * grid.cell;
      // A fan triangle that is a sliver (the centre on a vertex: a cone's tip), turned against the
      // field's normals at its two vertices, or folded onto its neighbour in the fan would fold the
      // surface: marching's triangles stay.
      bool sound = true;
      glm::dvec3 previous = area_normal(mesh.positions[loop.back()], mesh.positions[loop.front()], clamped);
      for (std::size_t i = 0; i < loop.size() && sound; ++i) {
        const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        const glm::dvec3 triangle = area_normal(mesh.positions[a], mesh.positions[b], clamped);
        sound = faces_along(triangle, glm::dvec3(mesh.normals[a]) + glm::dvec3(mesh.normals[b]), grid.cell) &&
                no_fold(previous, triangle, grid.cell);
        previous = triangle;
      }
      if (!sound) {
        ++stats.folded_cells;
        keep();
        continue;
      }
      ++stats.feature_cells;
      stats.clamped_cells += outside ? 1 : 0;
      glm::vec3 normal(0.0f), color(0.0f);
      for (const std::uint32_t v : loop) {
        normal += mesh.normals[v];
        color += mesh.colors[v];
      }
      const auto centre_vertex = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.push_back(clamped);
      mesh.normals.push_back(glm::length(normal) > 0.0f ? glm::normalize(normal) : normal);
      mesh.colors.push_back(color / static_cast<float>(loop.size()));
      for (std::size_t i = 0; i < loop.size(); ++i) {
        fans.push_back({triangles.size(), centre_vertex});
        triangles.push_back({loop[i], loop[(i + 1) % loop.size()], centre_vertex});
        cells.push_back(key);
      }
    }
    first = end;
  }

  // Two fans meeting at an edge a - b: the quad a, centre2, b, centre1 is cut along the centres
  // instead, once per pair of centres, each triangle flipped once.
  std::unordered_map<std::uint64_t, std::size_t> fan_at_edge;
  for (std::size_t f = 0; f < fans.size(); ++f) {
    const MeshTriangle& t = triangles[fans[f].triangle];
    fan_at_edge.emplace(edge_key(t[0], t[1]), f);
  }
  std::vector<bool> flipped(triangles.size(), false);
  std::unordered_set<std::uint64_t> joined;
  for (const Fan& fan : fans) {
    const MeshTriangle t = triangles[fan.triangle];
    const auto across = fan_at_edge.find(edge_key(t[1], t[0]));
    if (across == fan_at_edge.end()) continue;
    const Fan& other = fans[across->second];
    if (flipped[fan.triangle] || flipped[other.triangle]) continue;
    const std::uint32_t c1 = fan.centre, c2 = other.centre;
    if (!joined.insert(edge_key(std::min(c1, c2), std::max(c1, c2))).second) continue;
    const std::uint32_t a = t[0], b = t[1];
    // Each new triangle must face like the field at its one old vertex, and the two not fold.
    const glm::dvec3 &pa = mesh.positions[a], &pb = mesh.positions[b];
    const glm::dvec3 &p1 = mesh.positions[c1], &p2 = mesh.positions[c2];
    const glm::dvec3 first = area_normal(pa, p2, p1), second = area_normal(p2, pb, p1);
    if (!faces_along(first, glm::dvec3(mesh.normals[a]), grid.cell) ||
        !faces_along(second, glm::dvec3(mesh.normals[b]), grid.cell) || !no_fold(first, second, grid.cell)) {
      joined.erase(edge_key(std::min(c1, c2), std::max(c1, c2)));
      continue;
    }
    triangles[fan.triangle] = {a, c2, c1};
    triangles[other.triangle] = {c2, b, c1};
    flipped[fan.triangle] = flipped[other.triangle] = true;
    ++stats.flipped_edges;
  }
  mesh.triangles = std::move(triangles);
  cell_of_triangle = std::move(cells);
  return stats;
}

}  // namespace clmarch
