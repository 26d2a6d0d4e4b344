// Writing renders with OpenImageIO: the color image in any format it writes, and the multi-channel
// float EXR of all buffers.
#pragma once

#include "common/atomic_file.hpp"
#include "frame/frame_buffers.hpp"
#include "scene/scene.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace clmarch {

/// Fails with InputError (naming option) unless OpenImageIO can write path's extension and its
/// folder is writable.
void check_image_path(const std::filesystem::path& path, const std::string& option);

/// Writes R, G, B: float and linear for float formats (exr, hdr), 8-bit sRGB-encoded otherwise.
/// Staged into files: in place when they are committed.
void write_color_image(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers);

/// Writes every channel (R, G, B, depth, steps, N.x, N.y, N.z, A, Z, samples) as one float EXR,
/// staged into files.
void write_buffers_exr(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers);
/// The same with what the scene's camera adds (docs/scene-format.md, "Buffers"): the channels
/// P.x, P.y, P.z (world position of the centre ray's hit, 0 on a miss) and the header attributes
/// worldToCamera and worldToNDC (OpenEXR's standard M44f) and clmarch:camera.* (the camera keys).
void write_buffers_exr(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers,
                       const Scene& scene);

/// R, G, B encoded in memory as an 8-bit sRGB image of the format named by extension ("png",
/// "jpg"): the frames of the preview. Throws OutputError when OpenImageIO cannot.
std::vector<unsigned char> encode_color_image(const FrameBuffers& buffers, const std::string& extension);

/// The sRGB transfer function of a linear value, clamped to [0, 1].
float linear_to_srgb(float linear);

}  // namespace clmarch
