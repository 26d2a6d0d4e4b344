#include "reference/reference_fractals.hpp"
#include "reference/reference_noise.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "support/test_support.hpp"
#include <gtest/gtest.h>
#include <random>
#include <cstdio>
namespace clmarch {
TEST(Explore, Lipschitz) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-2.0, 2.0);
  Mandelbulb m;
  for (int power : {2, 4, 8, 16}) {
    m.power = power;
    double worst = 0;
    for (int i = 0; i < 200000; ++i) {
      glm::dvec3 p(coord(rng), coord(rng), coord(rng));
      glm::dvec3 q = p + 0.1 * glm::dvec3(coord(rng), coord(rng), coord(rng));
      double r = std::abs(sd_mandelbulb(q, m) - sd_mandelbulb(p, m)) / glm::length(q - p);
      worst = std::max(worst, r);
    }
    std::printf("power %d lipschitz ratio %g\n", power, worst);
  }
  Terrain t;
  for (int noise = 0; noise < 3; ++noise) {
    t.noise = static_cast<TerrainNoise>(noise);
    double worst = 0;
    for (int i = 0; i < 200000; ++i) {
      glm::dvec3 p(coord(rng), coord(rng), coord(rng));
      glm::dvec3 q = p + 0.1 * glm::dvec3(coord(rng), coord(rng), coord(rng));
      double r = std::abs(sd_terrain(q, t) - sd_terrain(p, t)) / glm::length(q - p);
      worst = std::max(worst, r);
    }
    std::printf("terrain noise %d lipschitz ratio %g\n", noise, worst);
  }
}
TEST(Explore, MandelbulbBound) {
  for (double power : {2.0, 3.0, 8.0, 12.0}) {
  Mandelbulb m; m.power = power; m.iterations = 12;
  const double R = mandelbulb_radius(power);
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  std::vector<glm::dvec3> surface;
  for (int i = 0; i < 20000; ++i) {
    glm::dvec3 dir = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
    double t = R + 0.01;
    double step = 1e-3;
    while (t > 0 && sd_mandelbulb(t * dir, m) > 0) t -= step;
    if (t <= 0) continue;
    double lo = t, hi = t + step;
    for (int k = 0; k < 50; ++k) { double mid = 0.5*(lo+hi); (sd_mandelbulb(mid*dir, m) > 0 ? hi : lo) = mid; }
    surface.push_back(lo * dir);
  }
  double worst = 0; int count = 0;
  std::uniform_real_distribution<double> u(0.02, 0.5);
  for (int i = 0; i < 3000; ++i) {
    glm::dvec3 b = surface[i % surface.size()];
    glm::dvec3 q = b * (1.0 + u(rng));
    double best = 1e9;
    for (auto& s : surface) best = std::min(best, glm::length(q - s));
    double d = sd_mandelbulb(q, m);
    if (d > 0) { worst = std::max(worst, d / best); ++count; }
  }
  std::printf("power %g surface %zu worst DE/upper %g over %d\n", power, surface.size(), worst, count);
  }
}
TEST(Explore, KernelVsReference) {
  const char* yamls[] = {
    "sdf:\n  mandelbulb: {}\n", "sdf:\n  mandelbulb: {power: 3, iterations: 20, bailout: 4}\n",
    "sdf:\n  mandelbulb: {power: 16, iterations: 64, bailout: 13}\n",
    "sdf:\n  menger: {iterations: 8}\n", "sdf:\n  menger: {iterations: 3, half_size: 3}\n",
    "sdf:\n  terrain: {}\n", "sdf:\n  terrain: {noise: perlin, octaves: 16}\n", "sdf:\n  terrain: {noise: derivative, octaves: 16}\n",
    "sdf:\n  terrain: {noise: value, octaves: 16, seed: 12345}\n",
  };
  std::mt19937 rng(11);
  for (const char* y : yamls) {
    Scene s = testing::scene_from_yaml(y);
    double extent = s.sdf.kind == NodeKind::Terrain ? 20.0 : 1.5;
    std::uniform_real_distribution<double> coord(-extent, extent);
    std::vector<glm::dvec3> pts;
    for (int i = 0; i < 4096; ++i) pts.push_back({coord(rng), coord(rng), coord(rng)});
    for (int lanes : {1, 16}) {
      OpenClOptions o; o.lanes = lanes;
      auto r = eval_points_opencl(s, pts, o);
      double worst = 0, worst_rel = 0;
      for (size_t i = 0; i < pts.size(); ++i) {
        double ref = reference_distance(s.sdf, pts[i]);
        double e = std::abs(r.distance[i] - ref);
        worst = std::max(worst, e);
        worst_rel = std::max(worst_rel, e / std::max(std::abs(ref), 1e-3));
        if (e > 0.01 && lanes == 1) std::printf("  at %g %g %g kernel %g ref %g\n", pts[i].x, pts[i].y, pts[i].z, r.distance[i], ref);
      }
      std::printf("%s lanes %d worst abs %g rel %g\n", y + 7, lanes, worst, worst_rel);
    }
  }
}
}
namespace clmarch {
TEST(Explore, P16) {
  for (int it : {1, 2, 3, 4, 5, 8}) {
    Scene s = testing::scene_from_yaml("sdf:\n  mandelbulb: {power: 16, bailout: 64, iterations: " + std::to_string(it) + "}\n");
    std::vector<glm::dvec3> pts = {{0.873905, 0.912428, 0.268898}};
    OpenClOptions o; o.lanes = 1;
    auto r = eval_points_opencl(s, pts, o);
    Mandelbulb m = std::get<Mandelbulb>(s.sdf.primitive);
    // float emulation
    glm::vec3 c(pts[0]); glm::vec3 z = c; float dr = 1; float rr = glm::length(z);
    for (int i = 0; i < it && rr <= 64; ++i) {
      float th = std::acos(z.z / rr) * 16.f, ph = std::atan2(z.y, z.x) * 16.f;
      float rn = std::pow(rr, 15.f); dr = rn * 16.f * dr + 1.f; float zr = rn * rr;
      z = zr * glm::vec3(std::sin(th)*std::cos(ph), std::sin(th)*std::sin(ph), std::cos(th)) + c; rr = glm::length(z);
      std::printf("   it %d r %g dr %g\n", i, rr, dr);
    }
    std::printf("it %d kernel %g ref %g float est %g\n", it, r.distance[0], reference_distance(s.sdf, pts[0]), 0.5f*std::log(rr)*rr/dr);
  }
}
}
