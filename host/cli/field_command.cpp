// `clmarch field`.
#include "cli/field_command.hpp"

#include "api/field.hpp"
#include "cli/field_csv.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"

#include <fmt/format.h>

namespace clmarch {

CLI::App* add_field_command(CLI::App& app, FieldCommandOptions& options) {
  CLI::App* field = app.add_subcommand(
      "field", "Write a scene's distance and colour at the points of a CSV file (training data, probes)");
  field->footer(
      "The points file has the header x,y,z and one point a row; the output, the header\n"
      "x,y,z,distance,r,g,b and one row a point in the same order: the whole scene's signed distance\n"
      "and its linear albedo there (docs/cli.md#clmarch-field).\n"
      "Examples:\n"
      "  clmarch field scenes/torus.yaml --points points.csv -o field.csv\n"
      "  clmarch field scenes/torus.yaml --points points.csv -o ref.csv --backend reference\n"
      "  clmarch field scenes/moving_shapes.yaml --points points.csv -o field.csv --time 1.5\n"
      "  clmarch field scenes/torus.yaml --points points.csv -o field.csv --set sdf.torus.minor_radius=0.4\n"
      "  clmarch field far.yaml --points points.csv -o field.csv --precision double --device 0");
  field->add_option("scene", options.scene.scene_path, "Scene file (YAML or JSON), e.g. scenes/torus.yaml")
      ->required()
      ->type_name("FILE");
  field
      ->add_option("--points", options.points,
                   "CSV file of the points: the header x,y,z, then x,y,z of one point a row (e.g. --points "
                   "points.csv)")
      ->required()
      ->type_name("FILE");
  field
      ->add_option("-o,--output", options.output,
                   "CSV file written: x,y,z,distance,r,g,b, one row a point in the input's order (e.g. -o field.csv)")
      ->required()
      ->type_name("FILE");
  field
      ->add_option("--set", options.scene.sets,
                   "Override any scene key: key.path=value (e.g. --set sdf.torus.minor_radius=0.4)")
      ->take_all();
  field->add_option("--time", options.scene.time, "Time t in seconds for expressions in the scene (e.g. --time 1.5)")
      ->check(finite_number([](double) { return true; }, "a finite number of seconds"));
  field->add_option("--device", options.scene.device,
                    "OpenCL device index from `clmarch devices` (default: first GPU, else first CPU)");
  field
      ->add_option("--precision", options.precision,
                   "float (default), or double: the field in double on the device (cl_khr_fp64), for scenes far "
                   "from the origin")
      ->check(CLI::IsMember({"float", "double"}));
  field
      ->add_option("--backend", options.backend,
                   "opencl (default), or reference: the field from the double-precision CPU reference")
      ->check(CLI::IsMember({"opencl", "reference"}));
  return field;
}

int run_field_command(const FieldCommandOptions& options) {
  if (options.backend == "reference" && options.scene.device) {
    throw InputError("--device applies to the OpenCL backend, not to --backend reference");
  }
  // A bad output path costs nothing: it is refused before the points are read.
  check_output_folder(options.output, "--output");
  const std::vector<glm::dvec3> points = read_points_csv(options.points);
  Scene scene = load_scene_with_options(options.scene);
  if (options.precision == "double") scene.render.precision = Precision::Double;
  const FieldSamples samples =
      sample_field(scene, points, parse_backend(options.backend, "--backend"), session_options(options.scene));
  write_file_atomically(options.output, field_csv_text(points, samples));
  log_info(fmt::format("wrote {} ({} points)", options.output, points.size()));
  return kExitOk;
}

}  // namespace clmarch
