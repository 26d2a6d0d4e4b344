// Program variants swept by `clmarch bench --sweep`: double precision (cl_khr_fp64), native math and
// -cl-fast-relaxed-math build, render and pass `clmarch check`; double precision is at least as
// close to an exact reference as float; and forward-difference normals match the closed-form
// normal of a sphere, in the reference and on the device.
#include "bench/sweep_run.hpp"
#include "check/cross_check.hpp"
#include "cl/device_program.hpp"
#include "cl/devices.hpp"
#include "codegen/kernel_source.hpp"
#include "reference/reference_renderer.hpp"
#include "reference/reference_sdf.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/camera_model.hpp"
#include "scene/scene_loader.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace clmarch {
namespace {

using testing::source_path;

Scene small_torus(const std::vector<SceneOverride>& overrides = {}) {
  Scene scene = load_scene_file(source_path("scenes/torus.yaml").string(), overrides);
  scene.render.width = 64;
  scene.render.height = 36;
  return scene;
}

OpenClOptions variant_options(int lanes, Precision precision, bool native_math, bool fast_math) {
  OpenClOptions options;
  options.lanes = lanes;
  options.variant.precision = precision;
  options.variant.native_math = native_math;
  options.variant.fast_math = fast_math;
  return options;
}

TEST(KernelVariant, SourceAndBuildOptionsSayWhatTheyAre) {
  const Scene scene = small_torus();
  KernelOptions options{KernelPurpose::Shaded, 16, {}};
  const std::string plain = generate_kernel_source(scene, options);
  EXPECT_EQ(plain.find("#define DOUBLE_PRECISION"), std::string::npos);
  EXPECT_EQ(plain.find("#define NATIVE_MATH"), std::string::npos);
  options.variant.precision = Precision::Double;
  EXPECT_NE(generate_kernel_source(scene, options).find("#define DOUBLE_PRECISION\n"), std::string::npos);
  options.variant = {Precision::Float, true, false};
  EXPECT_NE(generate_kernel_source(scene, options).find("#define NATIVE_MATH\n"), std::string::npos);
  options.variant = {Precision::Double, true, false};
  EXPECT_THROW(generate_kernel_source(scene, options), std::invalid_argument);
  // One double lane: the builtins that kernels call with float literals take double arguments.
  EXPECT_NE(
      generate_kernel_source(scene, {KernelPurpose::Shaded, 1, {Precision::Double, false, false}}).find("lane_fmax"),
      std::string::npos);
  EXPECT_EQ(kernel_build_options({}), "-cl-std=CL1.2");
  EXPECT_EQ(kernel_build_options({Precision::Float, false, true}), "-cl-std=CL1.2 -cl-fast-relaxed-math");
}

// Fused multiply-adds the source does not write are left to the compiler only on PoCL, whose
// fused operations agree at every packet width; elsewhere the program forbids them, and that
// program builds cleanly here too.
TEST(KernelVariant, FpContractionOnlyOnPocl) {
  DeviceEntry pocl, nvidia;
  pocl.platform_name = "Portable Computing Language";
  pocl.is_cpu = true;
  nvidia.platform_name = "NVIDIA CUDA";
  nvidia.is_gpu = true;
  EXPECT_TRUE(allows_fp_contraction(pocl));
  EXPECT_FALSE(allows_fp_contraction(nvidia));
  const Scene scene = small_torus();
  KernelOptions options{KernelPurpose::Shaded, 16, {}};
  EXPECT_EQ(generate_kernel_source(scene, options).find("#define NO_FP_CONTRACT\n"), std::string::npos);
  options.fp_contraction = false;
  const std::string exact = generate_kernel_source(scene, options);
  EXPECT_NE(exact.find("#define NO_FP_CONTRACT\n"), std::string::npos);
  const DeviceProgram program = build_device_program(select_device(std::nullopt), exact, testing::kLoggedBuildOptions);
  EXPECT_EQ(testing::compiler_warnings(program.build_log), "") << program.build_log;
}

struct VariantCase {
  const char* scene;
  int lanes;
  Precision precision;
  bool native_math;
  bool fast_math;
};

class KernelVariantCheck : public ::testing::TestWithParam<VariantCase> {};

// Each variant renders the shipped scene and passes the same check as the default program.
TEST_P(KernelVariantCheck, PassesTheCheck) {
  const VariantCase& v = GetParam();
  Scene scene = load_scene_file(source_path(std::string("scenes/") + v.scene).string());
  scene.render.width = 64;
  scene.render.height = 36;
  const RenderResult render = render_opencl(scene, variant_options(v.lanes, v.precision, v.native_math, v.fast_math));
  const CheckReport report =
      cross_check(scene, render.buffers, render_reference(scene), reshade_hits(scene, render.buffers));
  EXPECT_TRUE(report.passed()) << report.to_text();
  EXPECT_GT(report.both_hit, 100);
}

INSTANTIATE_TEST_SUITE_P(Variants, KernelVariantCheck,
                         ::testing::Values(VariantCase{"torus.yaml", 16, Precision::Double, false, false},
                                           VariantCase{"torus.yaml", 4, Precision::Double, false, false},
                                           VariantCase{"torus.yaml", 16, Precision::Float, true, false},
                                           VariantCase{"torus.yaml", 16, Precision::Float, false, true},
                                           VariantCase{"torus.yaml", 8, Precision::Double, false, true},
                                           VariantCase{"menger.yaml", 16, Precision::Double, false, false},
                                           VariantCase{"terrain_fbm.yaml", 16, Precision::Double, false, false},
                                           VariantCase{"tiled_spheres.yaml", 16, Precision::Double, false, false}),
                         [](const auto& info) {
                           const VariantCase& v = info.param;
                           std::string name = std::string(v.scene).substr(0, std::string(v.scene).find('.'));
                           name += "_lanes" + std::to_string(v.lanes) + "_" +
                                   kPrecisionNames[static_cast<int>(v.precision)];
                           if (v.native_math) name += "_native";
                           if (v.fast_math) name += "_fast";
                           return name;
                         });

// With a threshold below float's resolution at the torus's distance (t ~ 6: float spacing 4.8e-7),
// float rays stop at the march's floor of FLT_EPSILON * t (march_loop.cl), double rays at epsilon:
// the double render must be at least as close to the exact reference, and its normals, taken
// nearer the surface and with less rounding, clearly closer. (Both share the float camera basis
// of MarchParams and the float depth buffer, which bound how far double can pull ahead in depth.)
TEST(KernelVariant, DoubleIsAtLeastAsCloseAsFloat) {
  const Scene scene = small_torus({{"render.epsilon", "1e-7"}, {"render.max_steps", "1000"}});
  SweepSettings exact;
  exact.reference_epsilon_scale = 1e-10;
  const FrameBuffers reference = render_reference(high_accuracy_scene(scene, exact));
  const CheckReport single =
      cross_check(scene, render_opencl(scene, variant_options(16, Precision::Float, false, false)).buffers, reference);
  const CheckReport dual =
      cross_check(scene, render_opencl(scene, variant_options(16, Precision::Double, false, false)).buffers, reference);
  const std::string both = "double:\n" + dual.to_text() + "float:\n" + single.to_text();
  EXPECT_LE(dual.mask_mismatch_interior + dual.mask_mismatch_silhouette,
            single.mask_mismatch_interior + single.mask_mismatch_silhouette)
      << both;
  EXPECT_LE(dual.depth_abs.rms, single.depth_abs.rms) << both;
  EXPECT_LT(dual.normal_angle_p99, 0.5 * single.normal_angle_p99) << both;
}

double angle(const glm::dvec3& a, const glm::dvec3& b) {
  return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0));
}

// Forward differences of a sphere of radius r at a surface point with normal n are off the normal
// by (h / 2r)(1 - n_i^2) per axis before normalising: at most h / (sqrt(2) r) radians (first order),
// where central differences are second order.
TEST(ForwardNormals, ReferenceMatchesTheSphereClosedForm) {
  const Scene scene = testing::scene_from_yaml("sdf:\n  sphere: {center: [0, 0, 0], radius: 2}\n");
  constexpr double kRadius = 2.0;
  const double h = 0.01;
  double worst = 0.0, worst_central = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double z = -1.0 + (k + 0.5) / 100.0, phi = 2.399963 * k;  // Fibonacci sphere
    const glm::dvec3 n(std::sqrt(1.0 - z * z) * std::cos(phi), std::sqrt(1.0 - z * z) * std::sin(phi), z);
    const glm::dvec3 p = kRadius * n;
    const double forward = angle(reference_normal(scene.sdf, p, NormalMethod::Forward, h), n);
    EXPECT_LE(forward, h / (std::sqrt(2.0) * kRadius) * 1.05 + 1e-9) << "n " << n.x << " " << n.y << " " << n.z;
    worst = std::max(worst, forward);
    worst_central = std::max(worst_central, angle(reference_normal(scene.sdf, p, NormalMethod::Central, h), n));
  }
  // First order: the worst error is of the order of the bound, far above central differences'.
  EXPECT_GT(worst, 0.5 * h / (std::sqrt(2.0) * kRadius));
  EXPECT_LT(worst_central, 0.01 * worst);
}

TEST(ForwardNormals, KernelMatchesTheSphereClosedForm) {
  Scene scene = testing::scene_from_yaml(
      "camera: {position: [0, 0, 6], look_at: [0, 0, 0], fov: 40}\n"
      "render: {width: 48, height: 48, normal_method: forward, normal_epsilon: 0.01}\n"
      "sdf:\n  sphere: {center: [0, 0, 0], radius: 2}\n");
  constexpr double kRadius = 2.0;
  const double h = scene.render.normal_epsilon;
  for (int lanes : {1, 16}) {
    OpenClOptions options;
    options.lanes = lanes;
    options.purpose = KernelPurpose::Normals;
    const FrameBuffers b = render_opencl(scene, options).buffers;
    const CameraBasis basis = camera_basis(scene.camera, b.width, b.height);
    int hits = 0;
    double worst = 0.0;
    for (int j = 0; j < b.height; ++j) {
      for (int i = 0; i < b.width; ++i) {
        const double t = b.at(Channel::Depth, i, j);
        if (!std::isfinite(t)) continue;
        ++hits;
        const glm::dvec3 p = basis.origin + t * pixel_ray_direction(basis, i, j);
        const glm::dvec3 n(b.at(Channel::NX, i, j), b.at(Channel::NY, i, j), b.at(Channel::NZ, i, j));
        // The first-order bound, plus float rounding of the taps' difference (|p| u / h per tap).
        const double bound = h / (std::sqrt(2.0) * kRadius) * 1.05 + 4.0 * 0x1p-24 * 8.0 / h;
        EXPECT_LE(angle(n, p), bound) << "pixel " << i << "," << j << " lanes " << lanes;
        worst = std::max(worst, angle(n, p));
      }
    }
    EXPECT_GT(hits, 500);
    EXPECT_GT(worst, 0.5 * h / (std::sqrt(2.0) * kRadius)) << "not first order: is it forward differences?";
  }
}

}  // namespace
}  // namespace clmarch
