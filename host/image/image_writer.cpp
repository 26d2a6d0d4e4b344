// OpenImageIO output; every file is staged through StagedFiles (temporary, then renamed).
#include "image/image_writer.hpp"

#include "common/atomic_file.hpp"
#include "common/errors.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
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
void expect_reads_back(const std::filesystem::path& file, const OIIO::ImageSpec& spec, const std::filesystem::path& target) {
  auto in = OIIO::ImageInput::open(file.string());
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  const bool ok = in && in->spec().width == spec.width && in->spec().height == spec.height &&
                  in->spec().nchannels == spec.nchannels && in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  if (!ok) {
    const std::string why = in ? in->geterror() : OIIO::geterror();
    throw OutputError(fmt::format("{}: cannot write: the written file does not read back{}", target.string(),
                                  why.empty() ? "" : ": " + joined_lines(why)));
  }
}

/// Interleaves the given planes and writes them with OpenImageIO as format.
void write_interleaved(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers,
                       const std::vector<Channel>& channels, OIIO::TypeDesc format, bool srgb) {
  const std::size_t pixels = static_cast<std::size_t>(buffers.width) * buffers.height;
  const std::size_t nc = channels.size();
  std::vector<float> interleaved(pixels * nc);
  for (std::size_t c = 0; c < nc; ++c) {
    const std::vector<float>& plane = buffers.plane(channels[c]);
    for (std::size_t i = 0; i < pixels; ++i) interleaved[i * nc + c] = srgb ? linear_to_srgb(plane[i]) : plane[i];
  }
  files.stage(path, [&](const std::filesystem::path& temp) {
    auto out = OIIO::ImageOutput::create(temp.string());
    if (!out) throw OutputError(fmt::format("{}: cannot write: {}", path.string(), joined_lines(OIIO::geterror())));
    OIIO::ImageSpec spec(buffers.width, buffers.height, static_cast<int>(nc), format);
    spec.channelnames.clear();
    for (Channel c : channels) spec.channelnames.emplace_back(kChannelNames[static_cast<int>(c)]);
    if (srgb) spec.attribute("oiio:ColorSpace", "sRGB");
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
      if (!out->set_ioproxy(&memory)) throw OutputError(fmt::format("{}: cannot write: {}", path.string(), joined_lines(out->geterror())));
    }
    const bool ok = out->open(temp.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, interleaved.data()) &&
                    out->close();
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
    throw InputError(fmt::format("{} {}: cannot write images with extension '{}' (try .png, .exr, .tif or .jpg)", option,
                                 path.string(), path.extension().string()));
  }
}

void write_color_image(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers) {
  const std::vector<Channel> rgb = {Channel::R, Channel::G, Channel::B};
  if (is_float_format(path)) {
    write_interleaved(files, path, buffers, rgb, OIIO::TypeDesc::FLOAT, false);
  } else {
    write_interleaved(files, path, buffers, rgb, OIIO::TypeDesc::UINT8, true);
  }
}

void write_buffers_exr(StagedFiles& files, const std::filesystem::path& path, const FrameBuffers& buffers) {
  const std::vector<Channel> all = {Channel::R,     Channel::G,  Channel::B,  Channel::Depth,
                                    Channel::Steps, Channel::NX, Channel::NY, Channel::NZ};
  write_interleaved(files, path, buffers, all, OIIO::TypeDesc::FLOAT, false);
}

}  // namespace clmarch
