// Zero-copy arrays over a render's planes.
#include "frame_arrays.hpp"

#include "frame/hit_positions.hpp"
#include "frame/views.hpp"

#include <cstddef>
#include <utility>

namespace clmarch::python {
namespace {

/// Planes a, b, c interleaved into one H x W x 3 block.
std::vector<float> interleaved(const std::vector<float>& a, const std::vector<float>& b, const std::vector<float>& c) {
  std::vector<float> out(a.size() * 3);
  for (std::size_t i = 0; i < a.size(); ++i) {
    out[3 * i] = a[i];
    out[3 * i + 1] = b[i];
    out[3 * i + 2] = c[i];
  }
  return out;
}

}  // namespace

std::shared_ptr<FrameData> hold_frame(RenderResult result, const Scene& scene) {
  auto frame = std::make_shared<FrameData>();
  frame->buffers = std::move(result.buffers);
  frame->stats = std::move(result.stats);
  FrameBuffers& b = frame->buffers;
  // The color image of the scene's view, as `render -o` and the EXR's R, G, B show it.
  apply_view(b, scene.shading.view, scene.render);
  frame->positions = hit_positions(b, scene.camera);
  frame->color = interleaved(b.plane(Channel::R), b.plane(Channel::G), b.plane(Channel::B));
  frame->normal = interleaved(b.plane(Channel::NX), b.plane(Channel::NY), b.plane(Channel::NZ));
  frame->position = interleaved(frame->positions[0], frame->positions[1], frame->positions[2]);
  return frame;
}

pybind11::array_t<float> view_of(const std::vector<float>& data, const std::vector<pybind11::ssize_t>& shape,
                                 const std::shared_ptr<void>& owner) {
  // The capsule holds a reference to the owner for as long as any array made from it lives.
  pybind11::capsule base(new std::shared_ptr<void>(owner),
                         [](void* held) { delete static_cast<std::shared_ptr<void>*>(held); });
  std::vector<pybind11::ssize_t> strides(shape.size(), static_cast<pybind11::ssize_t>(sizeof(float)));
  for (std::size_t k = shape.size() - 1; k-- > 0;) strides[k] = strides[k + 1] * shape[k + 1];
  return pybind11::array_t<float>(shape, strides, data.data(), base);
}

pybind11::dict frame_channels(const std::shared_ptr<FrameData>& frame) {
  const FrameBuffers& b = frame->buffers;
  const std::shared_ptr<void> owner = frame;
  pybind11::dict channels;
  const auto add = [&](const char* name, const std::vector<float>& plane, int components = 1) {
    std::vector<pybind11::ssize_t> shape = {b.height, b.width};
    if (components > 1) shape.push_back(components);
    channels[name] = view_of(plane, shape, owner);
  };
  for (Channel c : {Channel::R, Channel::G, Channel::B, Channel::Depth, Channel::Steps, Channel::NX, Channel::NY,
                    Channel::NZ, Channel::A, Channel::Samples, Channel::Id, Channel::Status}) {
    add(kChannelNames[static_cast<int>(c)], b.plane(c));
  }
  for (Channel layer : kLayerChannels) add(kChannelNames[static_cast<int>(layer)], b.plane(layer));
  if (b.has_depth_lo) add("depth.lo", b.plane(Channel::DepthLo));
  add("P.x", frame->positions[0]);
  add("P.y", frame->positions[1]);
  add("P.z", frame->positions[2]);
  add("color", frame->color, 3);
  add("normal", frame->normal, 3);
  add("P", frame->position, 3);
  return channels;
}

}  // namespace clmarch::python
