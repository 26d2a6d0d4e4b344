// Closed-form ray hits of simple primitives in double: the ground truth that the reference march
// and the OpenCL renderer are tested against. Shares no code with any distance function.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

#include <optional>

namespace clmarch {

// Each returns the smallest t > 0 with o + t*d on the primitive's surface: the entry point for a
// ray starting outside, the exit point for one starting inside (t = 0 itself never counts).
// d need not be unit length. Parameters are in world space (no Transform).

/// Tangent rays count as hits.
std::optional<double> intersect_sphere(const glm::dvec3& o, const glm::dvec3& d, const Sphere& sphere);
/// Slab method; rays along a face or an edge count as hits.
std::optional<double> intersect_box(const glm::dvec3& o, const glm::dvec3& d, const Box& box);
/// None for a ray parallel to the plane.
std::optional<double> intersect_plane(const glm::dvec3& o, const glm::dvec3& d, const Plane& plane);
/// Roots of the torus quartic, isolated between the roots of its derivatives and bisected to full
/// double precision; a ray exactly tangent (a double root) may be reported as a miss.
std::optional<double> intersect_torus(const glm::dvec3& o, const glm::dvec3& d, const Torus& torus);

}  // namespace clmarch
