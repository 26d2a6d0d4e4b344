// `clmarch check`.
#include "cli/check_command.hpp"

#include "api/check.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "image/image_writer.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>

namespace clmarch {

CLI::App* add_check_command(CLI::App& app, CheckCommandOptions& options) {
  CLI::App* check =
      app.add_subcommand("check", "Render a scene with OpenCL and the CPU reference and compare them pixel by pixel");
  check->footer(
      "Exit code 0 when every figure is within its tolerance (docs/accuracy.md), 1 otherwise.\n"
      "Examples:\n"
      "  clmarch check scenes/torus.yaml --size 160x90\n"
      "  mkdir -p /tmp/torus-check && clmarch check scenes/torus.yaml --json --out-dir /tmp/torus-check\n"
      "  clmarch check scenes/two_spheres.yaml --set render.epsilon=1e-5 --lanes 1 --device 0\n"
      "  clmarch check scenes/moving_shapes.yaml --time 0.5\n"
      "  clmarch check scenes/torus.yaml --samples 16 --size 160x90   # anti-aliased on both");
  add_scene_options(*check, options.scene);
  check->add_flag("--json", options.json, "Print the report as one JSON object on stdout (e.g. --json)");
  check
      ->add_option("--out-dir", options.out_dir,
                   "When the check fails, write opencl.png, reference.png and difference.exr (all channels) into "
                   "this existing folder (e.g. --out-dir /tmp/torus-check)")
      ->type_name("DIR");
  return check;
}

int run_check_command(const CheckCommandOptions& options) {
  if (!options.out_dir.empty()) {
    std::error_code error;
    if (std::filesystem::exists(options.out_dir, error) && !std::filesystem::is_directory(options.out_dir, error)) {
      throw InputError(fmt::format("--out-dir {}: is a file, expected a folder", options.out_dir));
    }
    if (!std::filesystem::is_directory(options.out_dir, error)) {
      throw InputError(fmt::format("--out-dir {}: no such folder", options.out_dir));
    }
    // The folder must take the files a failed check writes, before two renders are spent on it.
    check_output_folder(std::filesystem::path(options.out_dir) / "difference.exr", "--out-dir");
  }
  const Scene scene = load_scene_with_options(options.scene);
  const CheckOutcome outcome = check_scene(scene, session_options(options.scene));
  const RenderResult& opencl = outcome.opencl;
  const FrameBuffers& reference = outcome.reference;
  const CheckReport& report = outcome.report;
  if (options.json) {
    nlohmann::json json = report.to_json();
    json["scene"] = options.scene.scene_path;
    json["device"] = opencl.stats.device;
    json["lanes"] = opencl.stats.lanes;
    std::cout << json.dump() << std::endl;
  } else {
    std::cout << fmt::format("{} on {} ({} lanes) against the CPU reference\n", options.scene.scene_path,
                             opencl.stats.device, opencl.stats.lanes)
              << report.to_text();
  }
  if (!report.passed() && !options.out_dir.empty()) {
    const std::filesystem::path dir(options.out_dir);
    StagedFiles written;
    write_color_image(written, dir / "opencl.png", opencl.buffers);
    write_color_image(written, dir / "reference.png", reference);
    write_buffers_exr(written, dir / "difference.exr", difference_image(opencl.buffers, reference));
    written.commit();
    log_info(fmt::format("wrote opencl.png, reference.png and difference.exr in {}", options.out_dir));
  }
  return report.passed() ? kExitOk : kExitCheckFailed;
}

}  // namespace clmarch
