// One image over the ranks of an MPI job: tiles of whole rows handed out as ranks come free,
// gathered on rank 0, which writes the image and its buffers.
#pragma once

#include "cli/render_command.hpp"
#include "cli/render_outputs.hpp"
#include "scene/scene.hpp"

namespace clmarch {

/// Rows per tile for an image of height rows over ranks ranks: about eight tiles a rank, so that
/// a rank with costly rows does not hold up the others, in multiples of kBandRowAlignment (a tile
/// is then exactly its rows of the whole image's render).
int tile_rows_for(int height, int ranks);

/// Renders scene on the OpenCL device of every rank, a tile at a time; rank 0 writes files and,
/// with --stats, one line per rank. Throws RankFailure when a rank failed (rank 0 then writes nothing).
void render_image_in_tiles(const RenderCommandOptions& options, const Scene& scene, const FrameFiles& files);

}  // namespace clmarch
