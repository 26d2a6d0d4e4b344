// Shading against closed forms, on both backends: Lambert on a plane, Fresnel at normal incidence,
// Phong, Blinn-Phong and PBR at 60 degrees, Beer-Lambert fog at a known depth, height fog of a
// level ray, normal occlusion between two planes, shadows that must leave an unoccluded point
// fully lit (also with an occluder beyond a point light) and an occluded one dark, a mirror's
// reflection, tone mapping, the sky gradient.
#include "check/cross_check.hpp"
#include "reference/reference_renderer.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "support/test_support.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace clmarch {
namespace {

// Colors pass through float once on the device; the centre ray of these scenes is exact.
constexpr double kColorTolerance = 2e-5;

/// The colour at the centre pixel of a 1x1 render (its ray is the camera's forward axis), from
/// the OpenCL renderer and from the reference.
struct CentreColor {
  glm::dvec3 opencl;
  glm::dvec3 reference;
};

CentreColor centre_color(const std::string& yaml) {
  const Scene scene =
      testing::scene_from_yaml(yaml + "render: {width: 1, height: 1, max_steps: 500, epsilon: 1.0e-6}\n");
  const FrameBuffers b = render_opencl(scene, {}).buffers;
  const CameraBasis basis = camera_basis(scene.camera, 1, 1);
  const RayResult r = reference_trace(scene, basis.origin, pixel_ray_direction(basis, 0, 0));
  return {{b.at(Channel::R, 0, 0), b.at(Channel::G, 0, 0), b.at(Channel::B, 0, 0)}, r.color};
}

void expect_centre_color(const CentreColor& c, const glm::dvec3& expected, double tolerance = kColorTolerance) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(c.opencl[k], expected[k], tolerance) << "OpenCL channel " << k;
    EXPECT_NEAR(c.reference[k], expected[k], tolerance) << "reference channel " << k;
  }
}

// Looking straight down at the plane y = 0 from height 2.
const std::string kPlaneBelow =
    "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
    "sdf: {plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4]}}\n";

TEST(Shading, LambertOfAPlaneIsAlbedoTimesCosine) {
  // Light 60 degrees from the normal: n.l = 0.5.
  const CentreColor c =
      centre_color(kPlaneBelow +
                   "lights: [{directional: {direction: [0.8660254037844386, 0.5, 0], intensity: 2}}]\n"
                   "shading: {model: lambert, ambient: 0.1, diffuse: 0.9}\n");
  const glm::dvec3 albedo(0.8, 0.6, 0.4);
  expect_centre_color(c, albedo * (0.1 + 0.9 * 2.0 * 0.5));
}

TEST(Shading, FresnelAtNormalIncidenceIsF0) {
  // Light and view along the normal: h = n, so Fresnel-Schlick gives F0 = mix(0.04, albedo,
  // metallic), GGX gives 1 / (pi a^2) with a = roughness^2, and the Smith term is 1.
  const double roughness = 0.5, metallic = 0.25;
  const glm::dvec3 albedo(0.8, 0.6, 0.4);
  const CentreColor c = centre_color(
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4], roughness: 0.5, metallic: 0.25}}\n"
      "lights: [{directional: {direction: [0, 1, 0], intensity: 1}}]\n"
      "shading: {model: pbr, ambient: 0}\n");
  const glm::dvec3 f0 = glm::dvec3(0.04) + (albedo - glm::dvec3(0.04)) * metallic;
  const double a = roughness * roughness;
  const double distribution = 1.0 / (M_PI * a * a);
  const double specular = distribution / (4.0 + 1e-4);
  const glm::dvec3 expected = (1.0 - f0) * (1.0 - metallic) * albedo / M_PI + f0 * specular;
  expect_centre_color(c, expected, 1e-4);
}

// Light 60 degrees from the normal, seen along the normal (v = n): n.l = 1/2, the mirror direction
// of l makes 60 degrees with v (Phong: r.v = 1/2) and the half vector 30 degrees with n (Blinn-Phong
// and GGX: n.h = h.v = cos 30).
const std::string kLitAtSixtyDegrees =
    "lights: [{directional: {direction: [0.8660254037844386, 0.5, 0], intensity: 2}}]\n";

TEST(Shading, PhongAndBlinnPhongSpecularAtSixtyDegrees) {
  const glm::dvec3 albedo(0.8, 0.6, 0.4);
  const double cos30 = std::sqrt(3.0) / 2.0;
  for (const auto& [model, cosine] : {std::pair<std::string, double>{"phong", 0.5}, {"blinn_phong", cos30}}) {
    const CentreColor c = centre_color(kPlaneBelow + kLitAtSixtyDegrees + "shading: {model: " + model +
                                       ", ambient: 0.1, diffuse: 0.9, specular: 0.5, shininess: 8}\n");
    expect_centre_color(c, albedo * (0.1 + 0.9 * 0.5 * 2.0) + glm::dvec3(0.5 * std::pow(cosine, 8.0) * 2.0), 1e-4);
  }
}

TEST(Shading, PbrAtSixtyDegrees) {
  // Cook-Torrance with every term away from its normal-incidence value (docs/scene-format.md).
  const double roughness = 0.5, metallic = 0.25, n_dot_l = 0.5, n_dot_v = 1.0, cos30 = std::sqrt(3.0) / 2.0;
  const glm::dvec3 albedo(0.8, 0.6, 0.4);
  const CentreColor c = centre_color(
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4], roughness: 0.5, metallic: 0.25}}\n" +
      kLitAtSixtyDegrees + "shading: {model: pbr, ambient: 0.1}\n");
  const double a2 = std::pow(roughness, 4.0);
  const double denominator = cos30 * cos30 * (a2 - 1.0) + 1.0;
  const double distribution = a2 / (M_PI * denominator * denominator);
  const double k = (roughness + 1.0) * (roughness + 1.0) / 8.0;
  const double geometry = n_dot_v / (n_dot_v * (1.0 - k) + k) * n_dot_l / (n_dot_l * (1.0 - k) + k);
  const glm::dvec3 f0 = glm::dvec3(0.04) + (albedo - glm::dvec3(0.04)) * metallic;
  const glm::dvec3 fresnel = f0 + (1.0 - f0) * std::pow(1.0 - cos30, 5.0);
  const double specular = distribution * geometry / (4.0 * n_dot_v * n_dot_l + 1e-4);
  const glm::dvec3 lit = ((1.0 - fresnel) * (1.0 - metallic) * albedo / M_PI + fresnel * specular) * n_dot_l * 2.0;
  expect_centre_color(c, albedo * 0.1 + lit, 1e-4);
}

TEST(Shading, BeerLambertFogAtAKnownDepth) {
  // Ambient light only: the surface color is the albedo; at depth 2 the fog keeps exp(-2 d).
  const double density = 0.3;
  const CentreColor c =
      centre_color(kPlaneBelow + "shading: {ambient: 1, fog: {color: [0.2, 0.3, 0.9], density: 0.3}}\n");
  const glm::dvec3 fog(0.2, 0.3, 0.9), albedo(0.8, 0.6, 0.4);
  expect_centre_color(c, fog + (albedo - fog) * std::exp(-density * 2.0), 1e-4);
}

TEST(Shading, HeightFogOfALevelRay) {
  // A level ray (dir.y = 0) takes the limit of the height fog's integral, a exp(-y0 b) t: camera at
  // height 1, a wall at depth 5, the sun's colour equal to the fog's so that its term drops out.
  const double density = 0.04, falloff = 0.12, depth = 5.0;
  const CentreColor c = centre_color(
      "camera: {position: [0, 1, 0], look_at: [0, 1, -5]}\n"
      "sdf: {plane: {normal: [0, 0, 1], offset: 5, color: [0.8, 0.6, 0.4]}}\n"
      "shading: {ambient: 1, height_fog: {density: 0.04, falloff: 0.12, color: [0.2, 0.3, 0.9], "
      "sun_color: [0.2, 0.3, 0.9]}}\n");
  const glm::dvec3 fog(0.2, 0.3, 0.9), albedo(0.8, 0.6, 0.4);
  const double amount = density * std::exp(-1.0 * falloff) * depth;
  expect_centre_color(c, albedo + (fog - albedo) * amount, 1e-4);
}

TEST(Shading, ShadowsLeaveAnUnoccludedPointFullyLit) {
  const std::string lit = kPlaneBelow + "lights: [{point: {position: [1, 3, 0.5]}}]\nshading: {ambient: 0.1";
  const CentreColor plain = centre_color(lit + "}\n");
  for (const char* mode : {"hard", "soft", "soft_improved"}) {
    const CentreColor shadowed = centre_color(lit + ", shadows: {mode: " + mode + "}}\n");
    expect_centre_color(shadowed, plain.reference);
    EXPECT_GT(plain.reference.x, 0.3) << "the light must reach the point";
  }
}

TEST(Shading, ShadowsOfAPointLightEndAtTheLight) {
  // A sphere beyond the light, on the line from the point through the light: it casts no shadow.
  const std::string lit =
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "lights: [{point: {position: [1, 3, 0.5]}}]\nshading: {ambient: 0.1";
  const std::string plane = "plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4]}";
  const CentreColor plain = centre_color("sdf: {" + plane + "}\n" + lit + "}\n");
  for (const char* mode : {"hard", "soft", "soft_improved"}) {
    const CentreColor shadowed =
        centre_color("sdf: {union: [{" + plane + "}, {sphere: {center: [2, 6, 1], radius: 0.5}}]}\n" + lit +
                     ", shadows: {mode: " + mode + "}}\n");
    expect_centre_color(shadowed, plain.reference);
  }
}

TEST(Shading, ShadowsDarkenAnOccludedPoint) {
  // A sphere between the light and the point: only the ambient term remains.
  const std::string scene =
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {union: [{plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4]}},"
      " {sphere: {center: [1.5, 1.5, 0], radius: 0.5}}]}\n"
      "lights: [{point: {position: [3, 3, 0]}}]\n";
  for (const char* mode : {"hard", "soft", "soft_improved"}) {
    const CentreColor c = centre_color(scene + "shading: {ambient: 0.1, shadows: {mode: " + mode + "}}\n");
    expect_centre_color(c, glm::dvec3(0.8, 0.6, 0.4) * 0.1);
  }
}

TEST(Shading, NormalOcclusionBetweenAFloorAndACeiling) {
  // The floor y = 0 under a ceiling at y = 0.15, no lights, ambient 1: the color is albedo times the
  // occlusion. Along the normal the field at height h is min(h, 0.15 - h), so the samples at
  // h = 0.05 i, i = 1..5, lack 0, 0.05, 0.15, 0.25 and 0.35 of h, and
  // ao = 1 - (0.05^2 / 2 + 0.15^2 / 3 + 0.25^2 / 4 + 0.35^2 / 5) = 0.951125.
  const std::string between =
      "camera: {position: [0, 0.1, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {union: [{plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4]}},"
      " {plane: {normal: [0, -1, 0], offset: 0.15}}]}\n"
      "lights: []\n";
  const double ao = 1.0 - (0.05 * 0.05 / 2 + 0.15 * 0.15 / 3 + 0.25 * 0.25 / 4 + 0.35 * 0.35 / 5);
  expect_centre_color(centre_color(between + "shading: {ambient: 1, ambient_occlusion: {samples: 5, step: 0.05}}\n"),
                      glm::dvec3(0.8, 0.6, 0.4) * ao);
  expect_centre_color(
      centre_color(between + "shading: {ambient: 0.5, ambient_occlusion: {samples: 5, step: 0.05, power: 3}}\n"),
      glm::dvec3(0.8, 0.6, 0.4) * 0.5 * std::pow(ao, 3.0));
}

TEST(Shading, AMirrorAddsItsReflectivityTimesWhatItReflects) {
  // Looking straight down at a floor of reflectivity 0.5, no lights: its mirror ray goes straight up
  // and misses, so the color is the ambient term plus half the background.
  const CentreColor c = centre_color(
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4], reflectivity: 0.5}}\n"
      "lights: []\nshading: {ambient: 0.1, reflections: 1, background: [0.2, 0.4, 0.6]}\n");
  expect_centre_color(c, glm::dvec3(0.8, 0.6, 0.4) * 0.1 + glm::dvec3(0.2, 0.4, 0.6) * 0.5);
}

TEST(Shading, ReinhardAndGamma) {
  // Ambient 3 on albedo 1: c = 3, Reinhard 3 / 4, then gamma 2.
  const CentreColor c = centre_color(
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0}}\nshading: {ambient: 3, tone_map: reinhard, gamma: 2}\n");
  expect_centre_color(c, glm::dvec3(std::sqrt(0.75)));
}

TEST(Shading, SkyGradientOfMisses) {
  // Looking straight up at nothing: the zenith color.
  const CentreColor c = centre_color(
      "camera: {position: [0, 2, 0], look_at: [0, 5, 0], up: [0, 0, -1]}\n"
      "sdf: {sphere: {center: [0, -10, 0]}}\nshading: {sky: {horizon: [1, 1, 1], zenith: [0.1, 0.2, 0.6]}}\n");
  expect_centre_color(c, glm::dvec3(0.1, 0.2, 0.6));
}

/// Looking straight down at the point (x, 0, 0) of the plane y = 0, white, Lambert with diffuse 1
/// and no ambient light: the colour is the light's radiance there times n.l.
std::string plane_at(double x, const std::string& lights) {
  return fmt::format(
      "camera: {{position: [{0}, 2, 0], look_at: [{0}, 0, 0], up: [0, 0, -1]}}\n"
      "sdf: {{plane: {{normal: [0, 1, 0], offset: 0}}}}\nlights: [{1}]\nshading: {{ambient: 0}}\n",
      x, lights);
}

// A point light 2 above the origin with intensity 4: I / d^2 times n.l = h / d at each point.
TEST(Shading, InverseSquareFalloffAtKnownDistances) {
  const double h = 2.0, intensity = 4.0;
  for (double x : {0.0, 1.0, 3.0}) {
    const double d = std::hypot(x, h);
    const CentreColor c =
        centre_color(plane_at(x, "{point: {position: [0, 2, 0], intensity: 4, falloff: inverse_square}}"));
    expect_centre_color(c, glm::dvec3(intensity / (d * d) * h / d), 1e-5);
  }
  // falloff: none keeps today's light: I n.l at any distance.
  const CentreColor none = centre_color(plane_at(3.0, "{point: {position: [0, 2, 0], intensity: 4, falloff: none}}"));
  expect_centre_color(none, glm::dvec3(intensity * h / std::hypot(3.0, h)), 1e-5);
}

// range R windows the light by clamp(1 - (d / R)^4, 0, 1)^2: beyond R nothing arrives.
TEST(Shading, RangeWindowsTheLight) {
  const double h = 2.0, range = 3.0;
  for (double x : {0.0, 1.5, 2.5}) {
    const double d = std::hypot(x, h);
    const double q = (d / range) * (d / range);
    const double window = std::max(1.0 - q * q, 0.0);
    const CentreColor c = centre_color(plane_at(x, "{point: {position: [0, 2, 0], range: 3}}"));
    expect_centre_color(c, glm::dvec3(window * window * h / d), 1e-5);
  }
}

// A spot light 2 above the origin pointing down, full inside 20 degrees, none past 30: at the
// point x the ray from the light makes atan(x / 2) with the axis.
TEST(Shading, SpotConeEdges) {
  const double h = 2.0;
  const double inner = std::cos(20.0 * M_PI / 180.0), outer = std::cos(30.0 * M_PI / 180.0);
  const std::string spot = "{spot: {position: [0, 2, 0], direction: [0, -1, 0], inner_angle: 20, outer_angle: 30}}";
  for (double degrees : {0.0, 10.0, 19.0, 22.0, 25.0, 28.0, 31.0, 45.0}) {
    const double x = h * std::tan(degrees * M_PI / 180.0);
    const double cosine = h / std::hypot(x, h);
    const double s = std::clamp((cosine - outer) / (inner - outer), 0.0, 1.0);
    const CentreColor c = centre_color(plane_at(x, spot));
    expect_centre_color(c, glm::dvec3(s * s * (3.0 - 2.0 * s) * cosine), 1e-5);
  }
  // Equal angles: a hard edge.
  const std::string hard = "{spot: {position: [0, 2, 0], direction: [0, -1, 0], inner_angle: 25, outer_angle: 25}}";
  expect_centre_color(centre_color(plane_at(h * std::tan(24.0 * M_PI / 180.0), hard)),
                      glm::dvec3(std::cos(24.0 * M_PI / 180.0)), 1e-5);
  expect_centre_color(centre_color(plane_at(h * std::tan(26.0 * M_PI / 180.0), hard)), glm::dvec3(0.0), 1e-5);
}

// Under a ball, a light that casts shadows is blocked and one that does not reaches the floor; a
// light's shadows: true switches shadows on where the scene's shading has none.
TEST(Shading, ShadowsPerLight) {
  const std::string ball =
      "camera: {position: [0, 0.5, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {union: [{plane: {normal: [0, 1, 0], offset: 0}}, {sphere: {center: [0, 2, 0], radius: 0.5}}]}\n";
  const CentreColor blocked = centre_color(
      ball + "lights: [{directional: {direction: [0, 1, 0]}}]\nshading: {ambient: 0, shadows: {mode: hard}}\n");
  expect_centre_color(blocked, glm::dvec3(0.0));
  const CentreColor through = centre_color(ball +
                                           "lights: [{directional: {direction: [0, 1, 0], shadows: false}}]\n"
                                           "shading: {ambient: 0, shadows: {mode: hard}}\n");
  expect_centre_color(through, glm::dvec3(1.0));
  const CentreColor asked =
      centre_color(ball + "lights: [{directional: {direction: [0, 1, 0], shadows: true}}]\nshading: {ambient: 0}\n");
  expect_centre_color(asked, glm::dvec3(0.0));
}

/// The device against the reference as clmarch check compares them, at one lane and sixteen in
/// float and at sixteen in double.
void expect_check_passes(const Scene& scene, const std::string& label) {
  for (const auto& [lanes, precision] :
       {std::pair{1, Precision::Float}, std::pair{16, Precision::Float}, std::pair{16, Precision::Double}}) {
    Scene variant = scene;
    variant.render.precision = precision;
    OpenClOptions options;
    options.lanes = lanes;
    const FrameBuffers opencl = render_opencl(variant, options).buffers;
    const CheckReport report = cross_check(variant, opencl, render_reference(variant), reshade_hits(variant, opencl));
    EXPECT_TRUE(report.passed()) << label << " lanes " << lanes << " " << kPrecisionNames[static_cast<int>(precision)]
                                 << "\n"
                                 << report.to_text();
  }
}

// Spot, falloff, range and per-light shadows on a lit scene: the device agrees with the reference
// (clmarch check), at one lane and sixteen, in float and in double.
TEST(Shading, ShapedLightsPassTheCheck) {
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0, 3, 6], look_at: [0, 0, 0]}\nrender: {width: 64, height: 36}\n"
      "sdf: {union: [{plane: {normal: [0, 1, 0], offset: 0}}, {sphere: {center: [0.5, 0.6, 0], radius: 0.6}}]}\n"
      "lights:\n"
      "  - spot: {position: [0, 4, 0], direction: [0, -1, 0], inner_angle: 20, outer_angle: 30, intensity: 16, "
      "falloff: inverse_square}\n"
      "  - point: {position: [-2, 1, 1], intensity: 0.8, range: 4, shadows: false}\n"
      "  - directional: {direction: [1, 1, 0], intensity: 0.2}\n"
      "shading: {model: blinn_phong, specular: 0.3, shadows: {mode: soft}, ambient: 0.05}\n");
  expect_check_passes(scene, "shaped lights");
}

// Per-node materials (issue 29): a node's specular and shininess replace the scene's for Phong
// and Blinn-Phong, inherited down the tree; its emission adds unlit.
TEST(Shading, SpecularAndShininessPerNode) {
  const glm::dvec3 albedo(0.8, 0.6, 0.4);
  const double cos30 = std::sqrt(3.0) / 2.0;
  // The plane's own 0.25 and 4 win over the scene's 0.5 and 8; a parent's apply where the node sets none.
  const std::string own =
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4], specular: 0.25, shininess: 4}}\n";
  const std::string inherited =
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {union: {specular: 0.25, shininess: 4, children: [{plane: {normal: [0, 1, 0], offset: 0, "
      "color: [0.8, 0.6, 0.4]}}, {sphere: {center: [0, -5, 0], radius: 1}}]}}\n";
  for (const std::string& scene : {own, inherited}) {
    const CentreColor c =
        centre_color(scene + kLitAtSixtyDegrees +
                     "shading: {model: blinn_phong, ambient: 0.1, diffuse: 0.9, specular: 0.5, shininess: 8}\n");
    expect_centre_color(c, albedo * (0.1 + 0.9 * 0.5 * 2.0) + glm::dvec3(0.25 * std::pow(cos30, 4.0) * 2.0), 1e-4);
  }
}

TEST(Shading, EmissionAddsUnlit) {
  // No light and no ambient: only the emission shows; with a light it adds to the lit color.
  const std::string plane =
      "camera: {position: [0, 2, 0], look_at: [0, 0, 0], up: [0, 0, -1]}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0, color: [0.8, 0.6, 0.4], emission: [0.2, 0.3, 0.4]}}\n";
  expect_centre_color(centre_color(plane + "shading: {ambient: 0}\n"), glm::dvec3(0.2, 0.3, 0.4));
  expect_centre_color(centre_color(plane + "lights: [{directional: {direction: [0, 1, 0]}}]\nshading: {ambient: 0}\n"),
                      glm::dvec3(0.8 + 0.2, 0.6 + 0.3, 0.4 + 0.4));
}

// Materials per node through a smooth blend, an emissive operand, an operand grid of glossy and
// glowing balls: the device agrees with the reference at one lane and sixteen.
TEST(Shading, MaterialsPerNodePassTheCheck) {
  std::string balls;
  for (int i = 0; i < 60; ++i) {
    balls += fmt::format("      - sphere: {{center: [{}, 0.2, {}], radius: 0.15, specular: {}, shininess: {}{}}}\n",
                         -2.0 + 0.5 * (i % 10), -1.0 - 0.5 * (i / 10), 0.1 * (i % 5), 4 + 10 * (i % 3),
                         i % 7 == 0 ? ", emission: [1, 0.5, 0.2]" : "");
  }
  for (const char* model : {"blinn_phong", "phong", "pbr"}) {
    const Scene scene = testing::scene_from_yaml(
        "camera: {position: [0, 1.5, 5], look_at: [0, 0.3, -1]}\nrender: {width: 64, height: 36, pruning: grid}\n"
        "sdf:\n  union:\n    - plane: {normal: [0, 1, 0], offset: 0, specular: 0}\n"
        "    - smooth_union: {k: 0.3, children: [{sphere: {center: [-0.6, 0.6, 0], radius: 0.5, specular: 1, "
        "shininess: 64, "
        "roughness: 0.2}}, {sphere: {center: [0.4, 0.6, 0], radius: 0.5, specular: 0.1, shininess: 4, metallic: 1}}]}\n"
        "    - sphere: {center: [1.6, 0.4, 0.5], radius: 0.3, emission: [2, 1.5, 0.5]}\n"
        "    - union:\n" +
        balls + "lights: [{point: {position: [2, 3, 3]}}]\nshading: {model: " + model +
        ", specular: 0.5, shininess: 16, ambient: 0.1}\n");
    expect_check_passes(scene, model);
  }
}

/// Looking straight down at the point (x, 0, z) of a floor whose color is pattern, seen under the
/// ambient light alone (1): the color there.
CentreColor floor_color_at(double x, double z, const std::string& floor, double time = 0.0) {
  const std::string yaml = fmt::format(
      "camera: {{position: [{0}, 2, {1}], look_at: [{0}, 0, {1}], up: [0, 0, -1]}}\n"
      "sdf: {2}\nshading: {{ambient: 1}}\n"
      "render: {{width: 1, height: 1, max_steps: 500, epsilon: 1.0e-6}}\n",
      x, z, floor);
  const Scene scene = testing::scene_from_yaml(yaml, time);
  const FrameBuffers b = render_opencl(scene, {}).buffers;
  const CameraBasis basis = camera_basis(scene.camera, 1, 1);
  const RayResult r = reference_trace(scene, basis.origin, pixel_ray_direction(basis, 0, 0));
  return {{b.at(Channel::R, 0, 0), b.at(Channel::G, 0, 0), b.at(Channel::B, 0, 0)}, r.color};
}

const glm::dvec3 kLight(0.9, 0.8, 0.7), kDark(0.1, 0.2, 0.3);

// The checker's color at known points: a where floor(x) + floor(y) + floor(z) is even (y = 0 on
// the floor), b where odd; in the frame of the node that sets it, here a union moved by 0.5 in x
// over the floor, so the world point x is the local x + 0.5.
TEST(ColorPattern, CheckerAtKnownPointsInBothFrames) {
  const std::string world =
      "{plane: {normal: [0, 1, 0], offset: 0, color: {checker: {size: 1, colors: [[0.9, 0.8, 0.7], [0.1, 0.2, "
      "0.3]]}}}}";
  const std::string moved =
      "{union: {translate: [0.5, 0, 0], color: {checker: {size: 1, colors: [[0.9, 0.8, 0.7], [0.1, 0.2, 0.3]]}}, "
      "children: [{plane: {normal: [0, 1, 0], offset: 0}}]}}";
  expect_centre_color(floor_color_at(0.25, 0.25, world), kLight);
  expect_centre_color(floor_color_at(1.25, 0.25, world), kDark);
  expect_centre_color(floor_color_at(-0.25, 0.25, world), kDark);
  expect_centre_color(floor_color_at(-0.25, -0.75, world), kLight);
  {
    SCOPED_TRACE("local x = -0.25");
    expect_centre_color(floor_color_at(0.25, 0.25, moved), kDark);
  }
  {
    SCOPED_TRACE("local x = 0.25");
    expect_centre_color(floor_color_at(0.75, 0.25, moved), kLight);
  }
  const std::string half =
      "{plane: {normal: [0, 1, 0], offset: 0, color: {checker: {size: 0.5, colors: [[0.9, 0.8, 0.7], [0.1, 0.2, "
      "0.3]]}}}}";
  expect_centre_color(floor_color_at(0.6, 0.1, half), kDark);
}

TEST(ColorPattern, StripesAndGrid) {
  const std::string stripes =
      "{plane: {normal: [0, 1, 0], offset: 0, color: {stripes: {size: 0.5, axis: z, colors: [[0.9, 0.8, 0.7], [0.1, "
      "0.2, 0.3]]}}}}";
  expect_centre_color(floor_color_at(3.0, 0.25, stripes), kLight);
  expect_centre_color(floor_color_at(3.0, 0.75, stripes), kDark);
  expect_centre_color(floor_color_at(-7.0, -0.25, stripes), kDark);
  const std::string grid =
      "{plane: {normal: [0, 1, 0], offset: 0, color: {grid: {size: 1, line_width: 0.1, colors: [[0.9, 0.8, 0.7], [0.1, "
      "0.2, 0.3]]}}}}";
  {
    SCOPED_TRACE("a cell's middle");
    expect_centre_color(floor_color_at(0.5, 0.5, grid), kLight);
  }
  {
    SCOPED_TRACE("0.02 from the line x = 1");
    expect_centre_color(floor_color_at(1.02, 0.5, grid), kDark);
  }
  {
    SCOPED_TRACE("0.03 from the line z = -3");
    expect_centre_color(floor_color_at(0.5, -2.97, grid), kDark);
  }
  {
    SCOPED_TRACE("0.07 from z = 0, past half the width");
    expect_centre_color(floor_color_at(0.5, 0.07, grid), kLight);
  }
}

// A color of expressions of the point and the time, at t = 0.25.
TEST(ColorPattern, ExpressionsOfThePoint) {
  const std::string floor =
      "{plane: {normal: [0, 1, 0], offset: 0, color: [\"0.5 + 0.5 * sin(x)\", \"fract(z)\", \"mod(t, 1) + length(x, z) "
      "* 0\"]}}";
  expect_centre_color(floor_color_at(1.0, 2.3, floor, 0.25), glm::dvec3(0.5 + 0.5 * std::sin(1.0), 0.3, 0.25), 1e-5);
  expect_centre_color(floor_color_at(-2.0, -0.4, floor, 1.25), glm::dvec3(0.5 + 0.5 * std::sin(-2.0), 0.6, 0.25), 1e-5);
}

// Patterns, inherited through a rotated union, on the operands of an operand grid, with a smooth
// blend and anti-aliased: the device agrees with the reference.
TEST(ColorPattern, PatternsPassTheCheck) {
  std::string balls;
  for (int i = 0; i < 50; ++i) {
    balls += fmt::format(
        "      - sphere: {{center: [{}, 0.2, {}], radius: 0.15, color: {{stripes: {{size: 0.05, axis: y}}}}}}\n",
        -2.0 + 0.5 * (i % 10), -1.0 - 0.5 * (i / 10));
  }
  for (int samples : {1, 4}) {
    const Scene scene = testing::scene_from_yaml(
        "camera: {position: [0, 1.5, 5], look_at: [0, 0.3, -1]}\n"
        "render: {width: 64, height: 36, pruning: grid, samples: " +
        std::to_string(samples) +
        "}\n"
        "sdf:\n  union:\n"
        "    - union: {rotate: [0, 30, 0], color: {checker: {size: 0.5}}, children: [{plane: {normal: [0, 1, 0], "
        "offset: 0}}]}\n"
        "    - smooth_union: {k: 0.3, children: [{sphere: {center: [-0.6, 0.6, 0], radius: 0.5, color: {grid: {size: "
        "0.2, axes: [x, y, z]}}}},\n"
        "                                        {sphere: {center: [0.4, 0.6, 0], radius: 0.5, color: [\"0.5 + 0.5 * "
        "sin(8 * x)\", \"smoothstep(0, 1, y)\", 0.3]}}]}\n"
        "    - union:\n" +
        balls + "lights: [{point: {position: [2, 3, 3]}}]\nshading: {ambient: 0.2}\n");
    expect_check_passes(scene, "samples " + std::to_string(samples));
  }
}

// A floor at y = 0 lies on the checker's walls y = 0: seen from straight above and 300 away, where
// float's rounding (3e-5) is close to epsilon, every pixel still takes the color of its cell
// above the wall: the march ends outside the surface, and the hit point keeps that side.
TEST(ColorPattern, AFloorOnTheWallsTakesOneCell) {
  const Scene scene = testing::scene_from_yaml(
      "camera: {position: [0.3, 300, 0.2], look_at: [0.3, 0, 0.2], up: [0, 0, -1], fov: 1.5}\n"
      "render: {width: 96, height: 96, over_relaxation: 1, max_distance: 1000}\n"
      "sdf: {plane: {normal: [0, 1, 0], offset: 0, color: {checker: {size: 1, colors: [[1, 1, 1], [0, 0, 0]]}}}}\n"
      "shading: {ambient: 1}\n");
  const FrameBuffers b = render_opencl(scene, {}).buffers;
  const CameraBasis basis = camera_basis(scene.camera, 96, 96);
  int checked = 0;
  for (int j = 0; j < 96; ++j) {
    for (int i = 0; i < 96; ++i) {
      const glm::dvec3 hit =
          basis.origin + pixel_ray_direction(basis, i, j) * static_cast<double>(b.at(Channel::Depth, i, j));
      // Pixels near a wall in x or z may take either side: their hit points are known to 1e-4.
      if (std::abs(hit.x - std::round(hit.x)) < 0.02 || std::abs(hit.z - std::round(hit.z)) < 0.02) continue;
      const bool odd = static_cast<long long>(std::floor(hit.x) + std::floor(hit.z)) % 2 != 0;
      EXPECT_EQ(b.at(Channel::R, i, j), odd ? 0.0f : 1.0f) << "pixel " << i << ", " << j << " at y " << hit.y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 8000);
}

}  // namespace
}  // namespace clmarch
