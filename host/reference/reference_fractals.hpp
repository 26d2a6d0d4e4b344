// Reference distance estimators of the fractal primitives, in double: the Mandelbulb, Inigo
// Quilez's Menger sponge, the Sierpinski tetrahedron, the Mandelbox and the quaternion Julia set. Written apart from
// kernels/fractals.cl; the two are compared in tests.
#pragma once

#include "scene/scene.hpp"

#include <glm/glm.hpp>

namespace clmarch {

/// The escape-time distance estimator 0.5 log(r) r / dr of the Mandelbulb (a bound near the set,
/// not exactly 1-Lipschitz), capped at 1 and never below |p - c| - mandelbulb_radius: far away it
/// is the distance to the enclosing ball.
double sd_mandelbulb(const glm::dvec3& p, const Mandelbulb& bulb);

/// Inigo Quilez's Menger sponge: the box intersected with iterations levels of crosses. A bound
/// (1-Lipschitz; exact where one flat wall is nearest, short of the true distance near the
/// edges of the holes).
double sd_menger(const glm::dvec3& p, const Menger& sponge);

/// The Sierpinski tetrahedron by its kaleidoscopic IFS: the distance to the last level's
/// tetrahedron by its face planes, scaled back (an estimate: one copy of the level stands for
/// all), never below the distance to the ball of radius sqrt(3) size around the centre.
double sd_sierpinski(const glm::dvec3& p, const Sierpinski& tetrahedron);

/// Tom Lowe's Mandelbox by the estimate |z| / |dz/dp| of its box and sphere folds, never below the
/// distance to the ball round the cube that holds it (mandelbox_half_size).
double sd_mandelbox(const glm::dvec3& p, const Mandelbox& box);

/// The quaternion Julia set of z^2 + c at the slice w = 0 by its analytic estimate
/// 0.5 |z| log|z| / |dz|, capped at 1 and never below the distance to the ball of julia_radius.
double sd_julia(const glm::dvec3& p, const Julia& julia);

}  // namespace clmarch
