// OpenImageIO output; every file is staged through StagedFiles (temporary, then renamed).
#include "image/image_writer.hpp"

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "frame/hit_positions.hpp"
#include "scene/camera_model.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace clmarch {
namespace {

/// OpenImageIO's error text on one line, as every message of ours is.
std::string joined_lines(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (std::size_t at; (at = text.find('\n')) != std::string::npos;) text.replace(at, 1, "; ");
  return text;
}

bool is_float_format(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".exr" || ext == ".hdr";
}

/// Fails with OutputError unless file reads back as a whole image of spec's size.
void expect_reads_back(const std::filesystem::path& file, const OIIO::ImageSpec& spec,
                       const std::filesystem::path& target) {
  auto in = OIIO::ImageInput::open(file.string());
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  const bool ok = in && in->spec().width == spec.width && in->spec().height == spec.height &&
                  in->spec().nchannels == spec.nchannels &&
                  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  if (!ok) {
    const std::string why = in ? in->geterror() : OIIO::geterror();
    throw OutputError(fmt::format("{}: cannot write: the written file does not read back{}", target.string(),
                                  why.empty() ? "" : ": " + joined_lines(why)));
  }
}

/// A plane of an output file and its channel name there.
struct NamedPlane {
  const std::vector<float>* plane;
  std::string name;
};

/// Header attributes of an output file (the EXR's camera).
struct HeaderAttributes {
  std::vector<std::pair<std::string, std::array<float, 16>>> matrices;
  std::vector<std::pair<std::string, std::string>> strings;
};

std::vector<NamedPlane> named(const FrameBuffers& buffers, const std::vector<Channel>& channels) {
  std::vector<NamedPlane> out;
  out.reserve(channels.size());
  for (Channel c : channels) out.push_back({&buffers.plane(c), kChannelNames[static_cast<int>(c)]});
  return out;
}

/// Interleaves the given planes and writes them with OpenImageIO as format.
void write_interleaved(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers,
                       const std::vector<NamedPlane>& channels, OIIO::TypeDesc format, bool srgb,
                       const HeaderAttributes& header = {}) {
  const std::size_t pixels = static_cast<std::size_t>(buffers.width) * buffers.height;
  const std::size_t nc = channels.size();
  std::vector<float> interleaved(pixels * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::vector<float>& plane = *channels[c].plane;
    for (std::size_t i = 0; i < pixels; ++i) interleaved[i * nc + c] = srgb ? linear_to_srgb(plane[i]) : plane[i];
  }
  files.stage(path, [&](const std::filesystem::path& temp) {
    auto out = OIIO::ImageOutput::create(temp.string());
    if (!out) throw OutputError(fmt::format("{}: cannot write: {}", path.string(), joined_lines(OIIO::geterror())));
    OIIO::ImageSpec spec(buffers.width, buffers.height, static_cast<int>(nc), format);
    spec.channelnames.clear();
    for (const NamedPlane& c : channels) spec.channelnames.push_back(c.name);
    if (srgb) spec.attribute("oiio:ColorSpace", "sRGB");
    for (const auto& [name, m] : header.matrices) spec.attribute(name, OIIO::TypeMatrix44, m.data());
    for (const auto& [name, text] : header.strings) spec.attribute(name, text);
    // The file is encoded in memory and written by write_bytes, which sees every write's error;
    // OpenImageIO's own file output ignores a failed flush at close (a full disk, a size limit).
    // The few formats that cannot encode to memory are read back instead. The buffer is reserved
    // at the raw size, which compressed files stay within, so that it does not double as it grows
    // (host/render/host_memory.hpp counts it once).
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    const bool in_memory = out->supports("ioproxy");
    if (in_memory) {
      encoded.reserve(interleaved.size() * (format == OIIO::TypeDesc::FLOAT ? sizeof(float) : 1) + 65536);
      if (!out->set_ioproxy(&memory))
        throw OutputError(fmt::format("{}: cannot write: {}", path.string(), joined_lines(out->geterror())));
    }
    const bool ok =
        out->open(temp.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, interleaved.data()) && out->close();
    if (!ok) throw OutputError(fmt::format("{}: cannot write: {}", path.string(), joined_lines(out->geterror())));
    if (in_memory) {
      write_bytes(temp, memory.buffer().data(), memory.buffer().size(), path);
    } else {
      expect_reads_back(temp, spec, path);
    }
  });
}

}  // namespace

float linear_to_srgb(float linear) {
  const float x = std::clamp(std::isnan(linear) ? 0.0f : linear, 0.0f, 1.0f);
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

void check_image_path(const std::filesystem::path& path, const std::string& option) {
  check_output_folder(path, option);
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) {
    throw InputError(fmt::format("{} {}: cannot write images with extension '{}' (try .png, .exr, .tif or .jpg)",
                                 option, path.string(), path.extension().string()));
  }
}

std::vector<unsigned char> encode_color_image(const FrameBuffers& buffers, const std::string& extension) {
  const std::size_t pixels = static_cast<std::size_t>(buffers.width) * buffers.height;
  std::vector<unsigned char> rgb(pixels * 3);
  const Channel channels[] = {Channel::R, Channel::G, Channel::B};
  for (std::size_t c = 0; c < 3; ++c) {
    const std::vector<float>& plane = buffers.plane(channels[c]);
    for (std::size_t i = 0; i < pixels; ++i)
      rgb[i * 3 + c] = static_cast<unsigned char>(std::lround(linear_to_srgb(plane[i]) * 255.0f));
  }
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  auto out = OIIO::ImageOutput::create(extension);
  if (!out || !out->supports("ioproxy") || !out->set_ioproxy(&memory)) {
    throw OutputError(
        fmt::format("cannot encode a .{} image in memory: {}", extension, joined_lines(OIIO::geterror())));
  }
  OIIO::ImageSpec spec(buffers.width, buffers.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  // Fast rather than small: a preview's frame is sent once over the loopback.
  spec.attribute("png:compressionLevel", 1);
  if (!out->open("frame." + extension, spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) || !out->close()) {
    throw OutputError(fmt::format("cannot encode a .{} image: {}", extension, joined_lines(out->geterror())));
  }
  return encoded;
}

void write_color_image(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers) {
  const std::vector<NamedPlane> rgb = named(buffers, {Channel::R, Channel::G, Channel::B});
  if (is_float_format(path)) {
    write_interleaved(files, path, buffers, rgb, OIIO::TypeDesc::FLOAT, false);
  } else {
    write_interleaved(files, path, buffers, rgb, OIIO::TypeDesc::UINT8, true);
  }
}

namespace {

/// The EXR's channels of every render: the contract's eight, then A, Z (depth, by the name
/// compositors look for), samples, id, status and the shading's layers (0 where a view draws something else),
/// and depth.lo where the render was in double.
std::vector<NamedPlane> buffer_planes(const FrameBuffers& buffers) {
  std::vector<NamedPlane> planes = named(buffers, {Channel::R, Channel::G, Channel::B, Channel::Depth, Channel::Steps,
                                                   Channel::NX, Channel::NY, Channel::NZ, Channel::A});
  planes.push_back({&buffers.plane(Channel::Depth), "Z"});
  planes.push_back({&buffers.plane(Channel::Samples), "samples"});
  planes.push_back({&buffers.plane(Channel::Id), "id"});
  planes.push_back({&buffers.plane(Channel::Status), "status"});
  for (Channel layer : kLayerChannels)
    planes.push_back({&buffers.plane(layer), kChannelNames[static_cast<int>(layer)]});
  if (buffers.has_depth_lo) planes.push_back({&buffers.plane(Channel::DepthLo), "depth.lo"});
  return planes;
}

std::string vec3_text(const glm::dvec3& v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

/// A row-vector matrix (Imath's p' = p M) whose columns are the given rows of a 4 x 4 transform.
std::array<float, 16> imath_matrix(const glm::dvec4 (&rows)[4]) {
  std::array<float, 16> m{};
  for (int column = 0; column < 4; ++column) {
    for (int row = 0; row < 4; ++row)
      m[static_cast<std::size_t>(row) * 4 + static_cast<std::size_t>(column)] = static_cast<float>(rows[column][row]);
  }
  return m;
}

/// worldToCamera (OpenEXR's camera looks down -z, x right, y up) and worldToNDC (after the divide
/// by w, x and y run from -1 to 1 across the image, right and up; w is the depth along the view
/// axis and z = 1 / w).
HeaderAttributes camera_attributes(const Scene& scene, const CameraBasis& basis) {
  const glm::dvec3 o = basis.origin, f = basis.forward;
  const glm::dvec3 r = glm::normalize(basis.right_extent), u = glm::normalize(basis.up_extent);
  const glm::dvec3 sx = basis.right_extent / glm::dot(basis.right_extent, basis.right_extent);
  const glm::dvec3 sy = basis.up_extent / glm::dot(basis.up_extent, basis.up_extent);
  const glm::dvec4 camera[4] = {{r, -glm::dot(r, o)}, {u, -glm::dot(u, o)}, {-f, glm::dot(f, o)}, {0.0, 0.0, 0.0, 1.0}};
  const glm::dvec4 ndc[4] = {
      {sx, -glm::dot(sx, o)}, {sy, -glm::dot(sy, o)}, {0.0, 0.0, 0.0, 1.0}, {f, -glm::dot(f, o)}};
  HeaderAttributes header;
  header.matrices = {{"worldToCamera", imath_matrix(camera)}, {"worldToNDC", imath_matrix(ndc)}};
  header.strings = {{"clmarch:camera.position", vec3_text(scene.camera.position)},
                    {"clmarch:camera.look_at", vec3_text(scene.camera.look_at)},
                    {"clmarch:camera.up", vec3_text(scene.camera.up)},
                    {"clmarch:camera.fov", fmt::format("{}", scene.camera.fov_degrees)}};
  return header;
}

}  // namespace

void write_buffers_exr(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers) {
  write_interleaved(files, path, buffers, buffer_planes(buffers), OIIO::TypeDesc::FLOAT, false);
}

void write_buffers_exr(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers,
                       const Scene& scene) {
  const CameraBasis basis = camera_basis(scene.camera, buffers.width, buffers.height);
  const std::array<std::vector<float>, 3> position = hit_positions(buffers, scene.camera);
  std::vector<NamedPlane> planes = buffer_planes(buffers);
  planes.push_back({&position[0], "P.x"});
  planes.push_back({&position[1], "P.y"});
  planes.push_back({&position[2], "P.z"});
  write_interleaved(files, path, buffers, planes, OIIO::TypeDesc::FLOAT, false, camera_attributes(scene, basis));
}

}  // namespace clmarch
