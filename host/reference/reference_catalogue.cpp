// Reference distance functions of the later catalogue primitives (cones, rounded and cut shapes,
// links, flat triangles), in double. Each is a geometric construction, written apart from
// Inigo Quilez's closed forms in kernels/primitives.cl: a solid of revolution is its profile in
// the half plane (r, y), measured to the profile's segments and arcs, with an inside test.
#include "reference/reference_geometry.hpp"
#include "reference/reference_sdf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace clmarch {
namespace {

using geometry::distance_to_arc;
using geometry::distance_to_segment;

constexpr double kPi = std::numbers::pi;

double radians(double degrees) { return degrees * kPi / 180.0; }

/// p about the y axis through center: (distance from the axis, height).
glm::dvec2 profile_point(const glm::dvec3& p, const glm::dvec3& center) {
  const glm::dvec3 l = p - center;
  return {std::hypot(l.x, l.z), l.y};
}

/// The point of the triangle abc nearest to p (Ericson's Real-Time Collision Detection 5.1.5): by
/// the Voronoi region of p among its vertices, edges and face.
glm::dvec3 closest_on_triangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denominator = 1.0 / (va + vb + vc);
  return a + ab * (vb * denominator) + ac * (vc * denominator);
}

/// The solid of revolution about the segment from a to b of the trapezoid with the radius ra at
/// a and rb at b, capped flat: in the half plane of p and the axis (distance from the axis, position
/// along it from a), the distance to the trapezoid's cap and side segments, negative inside. Its
/// edge on the axis is no boundary of the solid.
double capped_solid_of_revolution(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, double ra, double rb) {
  const double length = glm::length(b - a);
  const glm::dvec3 u = (b - a) / length;
  const double along = glm::dot(p - a, u);
  const glm::dvec2 q(glm::length(p - a - along * u), along);
  const glm::dvec2 axis_a(0.0, 0.0), rim_a(ra, 0.0), rim_b(rb, length), axis_b(0.0, length);
  const double nearest = std::min({distance_to_segment(q, axis_a, rim_a), distance_to_segment(q, rim_a, rim_b),
                                   distance_to_segment(q, rim_b, axis_b)});
  const bool inside = q.y >= 0.0 && q.y <= length && q.x <= ra + (rb - ra) * q.y / length;
  return inside ? -nearest : nearest;
}

double triangle_distance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::length(p - closest_on_triangle(p, a, b, c));
}

}  // namespace

double sd_cone(const glm::dvec3& p, const Cone& cone) {
  // The triangle apex (0, 0), rim (R, -h), base centre (0, -h); its edge on the axis is no boundary.
  const glm::dvec2 q = profile_point(p, cone.center);
  const double h = cone.height;
  const double rim_radius = h * std::tan(radians(cone.angle));
  const glm::dvec2 apex(0.0, 0.0), rim(rim_radius, -h), base(0.0, -h);
  const double nearest = std::min(distance_to_segment(q, apex, rim), distance_to_segment(q, rim, base));
  const bool inside = q.y <= 0.0 && q.y >= -h && q.x <= rim_radius * (-q.y / h);
  return inside ? -nearest : nearest;
}

double sd_rounded_cylinder(const glm::dvec3& p, const RoundedCylinder& cylinder) {
  // The upper quarter of the profile (|y| by symmetry): the flat top, the straight side and the
  // quarter circle of the rounded rim between them.
  const glm::dvec2 r = profile_point(p, cylinder.center);
  const glm::dvec2 q(r.x, std::abs(r.y));
  const double radius = cylinder.radius, h = cylinder.half_height, e = cylinder.edge_radius;
  const glm::dvec2 corner(radius - e, h - e);
  const double nearest =
      std::min({distance_to_segment(q, {0.0, h}, {radius - e, h}),
                distance_to_segment(q, {radius, 0.0}, {radius, h - e}), distance_to_arc(q, corner, e, 0.0, 0.5 * kPi)});
  const bool in_box = q.x <= radius && q.y <= h;
  const bool in_corner_square = q.x > corner.x && q.y > corner.y;
  const bool inside = in_box && (!in_corner_square || glm::length(q - corner) <= e);
  return inside ? -nearest : nearest;
}

double sd_round_cone(const glm::dvec3& p, const RoundCone& cone) {
  // In the plane of the axis and p: x off the axis, y along it from a (0) to b (L). The hull of
  // the two discs is bounded by the arc of a's circle below the common tangent, the tangent
  // segment and the arc of b's circle above it; its outward normal n has n.y = (r_a - r_b) / L.
  const glm::dvec3 axis = cone.b - cone.a;
  const double length = glm::length(axis);
  const glm::dvec3 u = axis / length;
  const double along = glm::dot(p - cone.a, u);
  const glm::dvec2 q(glm::length(p - cone.a - along * u), along);
  const double ra = cone.radius_a, rb = cone.radius_b;
  const glm::dvec2 ca(0.0, 0.0), cb(0.0, length);
  const double ny = (ra - rb) / length;
  const glm::dvec2 n(std::sqrt(1.0 - ny * ny), ny);
  const glm::dvec2 ta = ca + ra * n, tb = cb + rb * n;
  const double tangent_angle = std::atan2(n.y, n.x);
  const double nearest =
      std::min({distance_to_arc(q, ca, ra, -0.5 * kPi, tangent_angle), distance_to_segment(q, ta, tb),
                distance_to_arc(q, cb, rb, tangent_angle, 0.5 * kPi)});
  // The hull is both discs and the trapezoid ca, ta, tb, cb between them.
  const auto left_of = [&](const glm::dvec2& from, const glm::dvec2& to) {
    const glm::dvec2 e = to - from;
    return e.x * (q.y - from.y) - e.y * (q.x - from.x) >= 0.0;
  };
  const bool in_trapezoid = left_of(ca, ta) && left_of(ta, tb) && left_of(tb, cb) && left_of(cb, ca);
  const bool inside = glm::length(q - ca) <= ra || glm::length(q - cb) <= rb || in_trapezoid;
  return inside ? -nearest : nearest;
}

double sd_capped_cylinder(const glm::dvec3& p, const CappedCylinder& cylinder) {
  return capped_solid_of_revolution(p, cylinder.a, cylinder.b, cylinder.radius, cylinder.radius);
}

double sd_frustum(const glm::dvec3& p, const Frustum& frustum) {
  return capped_solid_of_revolution(p, frustum.a, frustum.b, frustum.radius_a, frustum.radius_b);
}

double sd_capped_torus(const glm::dvec3& p, const CappedTorus& torus) {
  // The spine: the points major_radius (sin t, 0, cos t) for |t| <= angle. p's own direction
  // about y is the nearest spine point's where the arc covers it, else an end is nearest.
  const glm::dvec3 l = p - torus.center;
  const glm::dvec3 q(std::abs(l.x), l.y, l.z);
  const double angle = radians(torus.angle);
  const double direction = std::atan2(q.x, q.z);
  double spine;
  if (direction <= angle) {
    spine = std::hypot(std::hypot(q.x, q.z) - torus.major_radius, q.y);
  } else {
    spine = glm::length(q - torus.major_radius * glm::dvec3(std::sin(angle), 0.0, std::cos(angle)));
  }
  return spine - torus.minor_radius;
}

double sd_link(const glm::dvec3& p, const Link& link) {
  // The spine in the xy plane: two bars x = +-R for |y| <= half_length, and the half circles of
  // radius R about (0, +-half_length) beyond them, measured in space.
  const glm::dvec3 l = p - link.center;
  const double r = link.major_radius, h = link.half_length;
  double spine =
      std::min(distance_to_segment(l, {r, -h, 0.0}, {r, h, 0.0}), distance_to_segment(l, {-r, -h, 0.0}, {-r, h, 0.0}));
  for (const double side : {1.0, -1.0}) {
    // Beyond the end (the half plane away from the centre), the nearest point of the half
    // circle is in p's direction about the end's centre; elsewhere it is a bar's end.
    const double beyond = side * l.y - h;
    if (beyond >= 0.0) spine = std::min(spine, std::hypot(std::hypot(l.x, beyond) - r, l.z));
  }
  return spine - link.minor_radius;
}

double sd_cut_sphere(const glm::dvec3& p, const CutSphere& cut) {
  // The profile: the disc's radius on y = h out to the rim (w, h), and the circle's arc from the
  // rim up to the pole.
  const glm::dvec2 q = profile_point(p, cut.center);
  const double r = cut.radius, h = cut.cut_height;
  const double w = std::sqrt(r * r - h * h);
  const double nearest = std::min(distance_to_segment(q, {0.0, h}, {w, h}),
                                  distance_to_arc(q, {0.0, 0.0}, r, std::atan2(h, w), 0.5 * kPi));
  const bool inside = glm::length(q) <= r && q.y >= h;
  return inside ? -nearest : nearest;
}

double sd_pyramid(const glm::dvec3& p, const Pyramid& pyramid) {
  // Five faces: the base square (two triangles) and four triangles up to the apex.
  const glm::dvec3 l = p - pyramid.center;
  const double s = pyramid.half_width;
  const glm::dvec3 apex(0.0, pyramid.height, 0.0);
  const glm::dvec3 corners[4] = {{s, 0.0, s}, {-s, 0.0, s}, {-s, 0.0, -s}, {s, 0.0, -s}};
  double nearest = std::min(triangle_distance(l, corners[0], corners[1], corners[2]),
                            triangle_distance(l, corners[0], corners[2], corners[3]));
  bool inside = l.y >= 0.0;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3& u = corners[i];
    const glm::dvec3& v = corners[(i + 1) % 4];
    nearest = std::min(nearest, triangle_distance(l, u, v, apex));
    // The side's outward normal: away from the base's centre, which is inside.
    glm::dvec3 n = glm::cross(v - u, apex - u);
    if (glm::dot(n, -u) > 0.0) n = -n;
    if (glm::dot(n, l - u) > 0.0) inside = false;
  }
  return inside ? -nearest : nearest;
}

double sd_triangle(const glm::dvec3& p, const Triangle& triangle) {
  return triangle_distance(p, triangle.a, triangle.b, triangle.c) - triangle.thickness;
}

double sd_quad(const glm::dvec3& p, const Quad& quad) {
  // Split along the diagonal a-c into two triangles.
  return std::min(triangle_distance(p, quad.a, quad.b, quad.c), triangle_distance(p, quad.a, quad.c, quad.d)) -
         quad.thickness;
}

double sd_triangular_prism(const glm::dvec3& p, const TriangularPrism& prism) {
  // The bound the kernel computes, built from the corners: the largest signed distance to the
  // planes of the three sides (corners at 90, 210 and 330 degrees, radius from the axis) and of
  // the two end caps.
  const glm::dvec3 l = p - prism.center;
  double largest = std::abs(l.z) - prism.half_length;
  for (int i = 0; i < 3; ++i) {
    const double from = radians(90.0 + 120.0 * i), to = radians(90.0 + 120.0 * (i + 1));
    const glm::dvec2 u = prism.radius * glm::dvec2(std::cos(from), std::sin(from));
    const glm::dvec2 v = prism.radius * glm::dvec2(std::cos(to), std::sin(to));
    // Counter-clockwise corners: the outward normal is the edge turned clockwise.
    const glm::dvec2 outward = glm::normalize(glm::dvec2(v.y - u.y, u.x - v.x));
    largest = std::max(largest, glm::dot(glm::dvec2(l.x, l.y) - u, outward));
  }
  return largest;
}

double sd_solid_angle(const glm::dvec3& p, const SolidAngle& sector) {
  // The profile: the straight side from the apex to (r sin a, r cos a) and the arc from there up
  // to the pole; inside is within the radius and within angle of +y.
  const glm::dvec2 q = profile_point(p, sector.center);
  const double a = radians(sector.angle), r = sector.radius;
  const glm::dvec2 edge = r * glm::dvec2(std::sin(a), std::cos(a));
  const double nearest =
      std::min(distance_to_segment(q, {0.0, 0.0}, edge), distance_to_arc(q, {0.0, 0.0}, r, 0.5 * kPi - a, 0.5 * kPi));
  const bool inside = glm::length(q) <= r && std::atan2(q.x, q.y) <= a;
  return inside ? -nearest : nearest;
}

double sd_cut_hollow_sphere(const glm::dvec3& p, const CutHollowSphere& bowl) {
  // The arc of the circle from the pole below up to the rim (w, cut_height), thickened.
  const glm::dvec2 q = profile_point(p, bowl.center);
  const double r = bowl.radius, h = bowl.cut_height;
  return distance_to_arc(q, {0.0, 0.0}, r, -0.5 * kPi, std::atan2(h, std::sqrt(r * r - h * h))) - bowl.thickness;
}

double sd_death_star(const glm::dvec3& p, const DeathStar& star) {
  // In the half plane (x, distance from the x axis): the big circle's arc outside the carving
  // circle, from their meeting point round to -x, and the carving circle's arc inside the big
  // one, from the meeting point round to its own -x side.
  const glm::dvec3 l = p - star.center;
  const glm::dvec2 q(l.x, std::hypot(l.y, l.z));
  const double r = star.radius, rc = star.carve_radius, d = star.carve_distance;
  const glm::dvec2 carve_center(d, 0.0);
  // The meeting point: x from r^2 - x^2 = rc^2 - (x - d)^2.
  const double mx = (r * r - rc * rc + d * d) / (2.0 * d);
  const glm::dvec2 meet(mx, std::sqrt(r * r - mx * mx));
  const double nearest = std::min(distance_to_arc(q, {0.0, 0.0}, r, std::atan2(meet.y, meet.x), kPi),
                                  distance_to_arc(q, carve_center, rc, std::atan2(meet.y, meet.x - d), kPi));
  const bool inside = glm::length(q) <= r && glm::length(q - carve_center) >= rc;
  return inside ? -nearest : nearest;
}

double sd_rhombus(const glm::dvec3& p, const Rhombus& rhombus) {
  // The rhombus polygon's distance in the xz plane, grown by the corner radius, then extruded.
  const glm::dvec3 l = p - rhombus.center;
  const double w = rhombus.half_width, dp = rhombus.half_depth;
  const double flat = geometry::convex_polygon_distance({l.x, l.z}, {{w, 0.0}, {0.0, dp}, {-w, 0.0}, {0.0, -dp}});
  return geometry::extrude(flat - rhombus.corner_radius, l.y, rhombus.half_height);
}

}  // namespace clmarch
