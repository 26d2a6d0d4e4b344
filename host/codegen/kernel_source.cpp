// Program assembly: defines first, then library files and generated code in dependency order.
#include "codegen/kernel_source.hpp"

#include "codegen/cl_literals.hpp"
#include "codegen/embedded_kernels.hpp"
#include "codegen/sdf_codegen.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace clmarch {
namespace {

std::string kernel_file(std::string_view name) {
  for (const EmbeddedFile& file : embedded_kernel_files()) {
    if (file.name == name) return fmt::format("#line 1 \"kernels/{}\"\n{}\n", name, file.contents);
  }
  throw std::logic_error(fmt::format("kernel file {} is not embedded", name));
}

std::string feature_defines(const Scene& scene, const KernelOptions& options) {
  std::string out = fmt::format("#define LANES {}\n", options.lanes);
  const bool normals = options.purpose == KernelPurpose::Normals || options.purpose == KernelPurpose::Shaded;
  const bool shading = options.purpose == KernelPurpose::Shaded;
  if (normals) {
    out += "#define NEED_NORMALS\n";
    if (scene.render.normal_method == NormalMethod::Tetrahedral) out += "#define NORMAL_TETRAHEDRAL\n";
  }
  if (shading) {
    const Shading& s = scene.shading;
    out += "#define NEED_SHADING\n";
    if (s.model == ShadingModel::Phong) out += "#define SHADING_MODEL_PHONG\n";
    if (s.model == ShadingModel::BlinnPhong) out += "#define SHADING_MODEL_BLINN_PHONG\n";
    out += fmt::format("#define SHADING_DIFFUSE {}\n", cl_float(s.diffuse));
    out += fmt::format("#define SHADING_SPECULAR {}\n", cl_float(s.specular));
    out += fmt::format("#define SHADING_SHININESS {}\n", cl_float(s.shininess));
    if (s.step_ao > 0.0) out += fmt::format("#define SHADING_STEP_AO {}\n", cl_float(s.step_ao));
    out += fmt::format("#define BACKGROUND_COLOR {}\n", cl_float4(s.background));
    out += fmt::format("#define AMBIENT_COLOR {}\n", cl_float4(s.ambient));
    out += fmt::format("#define LIGHT_COUNT {}\n", scene.lights.size());
    if (s.fog) {
      out += fmt::format("#define FOG_DENSITY {}\n", cl_float(s.fog->density));
      out += fmt::format("#define FOG_COLOR {}\n", cl_float4(s.fog->color));
    }
  }
  if (scene.tiling && options.purpose != KernelPurpose::EvalPoints) {
    out += scene.tiling->method == TilingMethod::Cells ? "#define TILING_CELLS\n" : "#define TILING_MOD\n";
    out += fmt::format("#define TILING_CELL {}\n", cl_float4(scene.tiling->cell));
  }
  return out;
}

}  // namespace

std::string generate_kernel_source(const Scene& scene, const KernelOptions& options) {
  const bool shading = options.purpose == KernelPurpose::Shaded;
  std::string src = fmt::format("/* clmarch program for {} */\n", scene.source_name);
  src += feature_defines(scene, options);
  src += kernel_file("device_types.h");
  src += kernel_file("lanes.cl");
  src += kernel_file("primitives.cl");
  src += kernel_file("operators.cl");
  if (shading) src += kernel_file("shading.cl");
  src += "#line 1 \"generated scene\"\n";
  src += generate_sdf_functions(scene.sdf);
  if (options.purpose == KernelPurpose::EvalPoints) {
    src += kernel_file("eval_points.cl");
    return src;
  }
  src += kernel_file("camera.cl");
  src += kernel_file("march_loop.cl");
  if (scene.tiling) src += kernel_file("tiling.cl");
  if (options.purpose != KernelPurpose::DepthSteps) src += kernel_file("normals.cl");
  src += kernel_file("march.cl");
  return src;
}

}  // namespace clmarch
