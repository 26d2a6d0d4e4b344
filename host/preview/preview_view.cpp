// Drawing the preview's views.
#include "preview/preview_view.hpp"

#include "frame/views.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <iterator>

namespace clmarch {
namespace {

/// A colour per primitive number, spread over the hues (golden-ratio steps) so neighbours differ.
glm::vec3 id_color(float id) {
  if (id < 0.0f) return glm::vec3(0.0f);
  const float hue = std::fmod(static_cast<float>(id) * 0.618034f, 1.0f) * 6.0f;
  const float x = 1.0f - std::abs(std::fmod(hue, 2.0f) - 1.0f);
  const glm::vec3 sextants[] = {{1, x, 0}, {x, 1, 0}, {0, 1, x}, {0, x, 1}, {x, 0, 1}, {1, 0, x}};
  return 0.8f * sextants[static_cast<int>(hue) % 6] + 0.1f;
}

void copy_layer(FrameBuffers& buffers, Channel r, Channel g, Channel b) {
  buffers.plane(Channel::R) = buffers.plane(r);
  buffers.plane(Channel::G) = buffers.plane(g);
  buffers.plane(Channel::B) = buffers.plane(b);
}

}  // namespace

std::optional<PreviewView> preview_view_from_name(const std::string& name) {
  for (std::size_t v = 0; v < std::size(kPreviewViewNames); ++v) {
    if (name == kPreviewViewNames[v]) return static_cast<PreviewView>(v);
  }
  return std::nullopt;
}

void draw_preview_view(FrameBuffers& buffers, PreviewView view, const RenderSettings& settings) {
  switch (view) {
    case PreviewView::Shaded:
      return apply_view(buffers, View::Shaded, settings);
    case PreviewView::Depth:
      return apply_view(buffers, View::Depth, settings);
    case PreviewView::Steps:
      return apply_view(buffers, View::Steps, settings);
    case PreviewView::Normals:
      return apply_view(buffers, View::Normals, settings);
    case PreviewView::Status:
      return apply_view(buffers, View::Status, settings);
    case PreviewView::Id: {
      const std::vector<float>& ids = buffers.plane(Channel::Id);
      for (std::size_t i = 0; i < ids.size(); ++i) {
        const glm::vec3 c = id_color(ids[i]);
        buffers.plane(Channel::R)[i] = c.r;
        buffers.plane(Channel::G)[i] = c.g;
        buffers.plane(Channel::B)[i] = c.b;
      }
      return;
    }
    case PreviewView::Ao:
      return copy_layer(buffers, Channel::AoR, Channel::AoG, Channel::AoB);
    case PreviewView::Diffuse:
      return copy_layer(buffers, Channel::DiffuseR, Channel::DiffuseG, Channel::DiffuseB);
    case PreviewView::Specular:
      return copy_layer(buffers, Channel::SpecularR, Channel::SpecularG, Channel::SpecularB);
  }
}

}  // namespace clmarch
