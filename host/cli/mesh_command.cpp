// `clmarch mesh`.
#include "cli/mesh_command.hpp"

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/log.hpp"
#include "mesh/mesh_writers.hpp"
#include "mesh/scene_mesh.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace clmarch {
namespace {

/// The file's sink, refusing a mesh without triangles before the file begins: the scene's surface
/// missed its box, which is the scene's fault (exit 2), not the file's.
class SurfaceRequired final : public MeshSink {
 public:
  SurfaceRequired(MeshSink& file, std::string message) : file_(file), message_(std::move(message)) {}

  std::uint64_t kept_bytes_per_vertex() const override { return file_.kept_bytes_per_vertex(); }
  std::uint64_t kept_bytes_per_triangle() const override { return file_.kept_bytes_per_triangle(); }
  void begin(const MeshLayout& layout) override {
    if (layout.triangles == 0) throw InputError(message_);
    file_.begin(layout);
  }
  void add_vertices(const VertexBlock& block) override { file_.add_vertices(block); }
  void add_triangles(std::span<const MeshTriangle> block) override { file_.add_triangles(block); }
  void finish() override { file_.finish(); }

 private:
  MeshSink& file_;
  std::string message_;
};

}  // namespace

CLI::App* add_mesh_command(CLI::App& app, MeshCommandOptions& options) {
  CLI::App* mesh =
      app.add_subcommand("mesh", "Write a scene's surface as a watertight triangle mesh (PLY, STL, OBJ, glTF)");
  mesh->footer(
      "The field is sampled on a grid of --resolution cells along the longest side of the surface's box,\n"
      "only in the bricks of cells the surface can cross; marching cubes give a welded, watertight mesh\n"
      "whose vertices are moved onto the field. Fractals are meshed at render.epsilon (docs/meshes.md).\n"
      "Examples:\n"
      "  clmarch mesh scenes/torus.yaml -o torus.ply                       # positions, normals, colours\n"
      "  clmarch mesh scenes/mandelbulb.yaml -o bulb.stl --resolution 512 --stats\n"
      "  clmarch mesh scenes/torus.yaml -o torus.glb --set sdf.torus.minor_radius=0.4\n"
      "  clmarch mesh scenes/moving_shapes.yaml -o shapes.obj --time 1.5\n"
      "  clmarch mesh far.yaml -o far.ply --precision double                # far from the origin");
  mesh->add_option("scene", options.scene.scene_path, "Scene file (YAML or JSON), e.g. scenes/torus.yaml")
      ->required()
      ->type_name("FILE");
  mesh->add_option("-o,--output", options.output,
                   "Mesh file; the format follows the extension: .ply (binary, positions, normals, colours), .stl "
                   "(binary, positions), .obj (text, normals, colours), .glb (glTF binary). Default: SCENE_NAME.ply "
                   "(e.g. -o part.stl)")
      ->type_name("FILE");
  mesh->add_option("--resolution", options.resolution,
                   "Grid cells along the longest side of the surface's bounding box (default 256; e.g. --resolution "
                   "512)")
      ->check(CLI::Range(8, 8192));
  mesh->add_option("--set", options.scene.sets,
                   "Override any scene key: key.path=value (e.g. --set sdf.torus.minor_radius=0.4)")
      ->take_all();
  mesh->add_option("--time", options.scene.time, "Time t in seconds for expressions in the scene (e.g. --time 1.5)")
      ->check(finite_number([](double) { return true; }, "a finite number of seconds"));
  mesh->add_option("--device", options.scene.device,
                   "OpenCL device index from `clmarch devices` (default: first GPU, else first CPU)");
  mesh->add_option("--precision", options.precision,
                   "float (default), or double: the field in double on the device (cl_khr_fp64) and positions in "
                   "double in PLY and OBJ, for scenes far from the origin")
      ->check(CLI::IsMember({"float", "double"}));
  mesh->add_option("--backend", options.backend,
                   "opencl (default), or reference: the field from the double-precision CPU reference")
      ->check(CLI::IsMember({"opencl", "reference"}));
  mesh->add_option(
          "--cells", options.cells,
          "cubes (default: marching cubes), or tetrahedra: marching tetrahedra, about three times the triangles")
      ->check(CLI::IsMember({"cubes", "tetrahedra"}));
  mesh->add_flag("--sharp", options.sharp,
                 "Keep sharp edges and corners: where a cell's normals spread wider than 30 degrees, its surface "
                 "becomes a fan around the point where the tangent planes meet (cubes only; the whole mesh is then "
                 "held in memory)");
  mesh->add_flag("--stats", options.stats,
                 "Print one JSON line of figures on stdout: cells sampled and pruned, vertices, triangles, time by "
                 "phase, peak memory");
  return mesh;
}

int run_mesh_command(const MeshCommandOptions& options) {
  std::string output = options.output;
  if (output.empty()) output = std::filesystem::path(options.scene.scene_path).stem().string() + ".ply";
  const MeshFormat format = mesh_format_of(output, "--output");
  check_output_folder(output, "--output");
  if (options.backend == "reference" && options.scene.device) {
    throw InputError("--device applies to the OpenCL backend, not to --backend reference");
  }
  Scene scene = load_scene_with_options(options.scene);
  const bool in_double = options.precision == "double";
  if (in_double) scene.render.precision = Precision::Double;
  OpenClOptions cl = opencl_options(options.scene);
  MeshSettings settings;
  settings.resolution = options.resolution;
  settings.cells = options.cells == "tetrahedra" ? CellMethod::Tetrahedra : CellMethod::Cubes;
  if (options.sharp && settings.cells != CellMethod::Cubes) {
    throw InputError("--sharp applies to --cells cubes: tetrahedra put vertices inside cells, which a fan would drop");
  }
  settings.sharp = options.sharp;
  const auto start = std::chrono::steady_clock::now();
  MeshStats stats;
  StagedFiles files;
  stream_mesh(files, output, format, in_double ? MeshPrecision::Double : MeshPrecision::Float, [&](MeshSink& file) {
    SurfaceRequired sink(file, fmt::format("{}: the surface is nowhere inside its box at --resolution {}: no "
                                           "triangle to write",
                                           scene.source_name, options.resolution));
    stats = mesh_scene(
        scene, settings,
        [&](const glm::dvec3& origin) {
          return options.backend == "reference" ? reference_field(scene, origin) : opencl_field(scene, cl, origin);
        },
        fmt::format("--resolution {}", options.resolution), sink);
  });
  if (!stats.level_reason.empty()) log_warning(fmt::format("{}: {}", scene.source_name, stats.level_reason));
  const auto committed_at = std::chrono::steady_clock::now();
  files.commit();
  const auto end = std::chrono::steady_clock::now();
  log_info(fmt::format("wrote {} ({} triangles, {} vertices)", output, stats.triangles, stats.vertices));
  if (options.stats) {
    nlohmann::json line = stats.to_json();
    line["scene"] = options.scene.scene_path;
    line["output"] = output;
    line["format"] = kMeshFormatNames[static_cast<int>(format)];
    line["backend"] = options.backend;
    line["precision"] = options.precision;
    line["write_ms"] = stats.write_ms + std::chrono::duration<double, std::milli>(end - committed_at).count();
    line["total_ms"] = std::chrono::duration<double, std::milli>(end - start).count();
    std::error_code error;
    line["bytes"] = std::filesystem::file_size(output, error);
    std::cout << line.dump() << std::endl;
  }
  return kExitOk;
}

}  // namespace clmarch
