// What the preview shows of a frame: the scene's own views (shaded, depth, steps, normals, status)
// and the buffers the CLI writes only to the EXR (the primitive id, the shading's layers).
#pragma once

#include "frame/frame_buffers.hpp"
#include "scene/scene.hpp"

#include <optional>
#include <string>

namespace clmarch {

enum class PreviewView { Shaded, Depth, Steps, Normals, Status, Id, Ao, Diffuse, Specular };
inline constexpr const char* kPreviewViewNames[] = {"shaded", "depth", "steps",   "normals", "status",
                                                    "id",     "ao",    "diffuse", "specular"};

/// The view called name, if any.
std::optional<PreviewView> preview_view_from_name(const std::string& name);

/// Overwrites R, G, B with the view (the scene's shaded color stays for Shaded): apply_view's
/// views, ids as distinct colours (black for a miss), a layer's r, g, b as they are.
void draw_preview_view(FrameBuffers& buffers, PreviewView view, const RenderSettings& settings);

}  // namespace clmarch
