// What `clmarch render` does with a finished image, whoever rendered it (one process, the ranks
// of an MPI job): its files, the kernel work its outputs need, and its --stats line.
#pragma once

#include "api/render_session.hpp"
#include "cli/render_command.hpp"
#include "render/opencl_renderer.hpp"
#include "scene/scene.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace clmarch {

/// Where one image goes: the files named by the options, numbered when rendering a sequence.
struct FrameFiles {
  std::string output;
  std::string buffers;
  std::string dump_kernel;
};

/// Draws the scene's view into buffers and writes the image (and the buffers file) atomically:
/// both are written before either replaces its target. Logs "wrote ...".
void write_outputs(const FrameFiles& files, const Scene& scene, FrameBuffers& buffers);

/// The --stats object of one render (docs/cli.md#--stats).
nlohmann::json stats_json(const RenderCommandOptions& options, const Scene& scene, const RenderStats& stats);

/// The backend --backend names.
Backend backend_of(const RenderCommandOptions& options);

/// Prints json as one line on stdout in one write, so that the lines of several ranks, which
/// mpirun forwards to one stdout, do not interleave within a line.
void print_json_line(const nlohmann::json& json);

}  // namespace clmarch
