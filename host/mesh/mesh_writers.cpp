// The choice of a mesh format by extension, the checks of a mesh before it is written, and the
// staged file every format is written into.
#include "mesh/mesh_writers.hpp"

#include "common/errors.hpp"
#include "mesh/chunked_file.hpp"
#include "mesh/format_writers.hpp"
#include "image/image_writer.hpp"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <tuple>
#include <vector>

namespace clmarch {
namespace {

/// Records packed a block at a time: large enough to keep both cores busy, small enough to stay in
/// cache.
constexpr std::size_t kRecordsPerBlock = std::size_t{1} << 15;

/// The code of lround(linear_to_srgb(x) * 255) for x in [0, 1].
int srgb_code(float linear) { return static_cast<int>(std::lround(linear_to_srgb(linear) * 255.0f)); }

/// For each code k = 1 ... 255 the least float in [0, 1] whose code is at least k, by bisection over
/// the floats' bit patterns (which order non-negative floats as their values).
std::array<float, 255> srgb_steps() {
  std::array<float, 255> steps{};
  for (int k = 1; k <= 255; ++k) {
    std::uint32_t low = 0, high = std::bit_cast<std::uint32_t>(1.0f);
    while (low < high) {
      const std::uint32_t mid = low + (high - low) / 2;
      if (srgb_code(std::bit_cast<float>(mid)) >= k) {
        high = mid;
      } else {
        low = mid + 1;
      }
    }
    steps[static_cast<std::size_t>(k - 1)] = std::bit_cast<float>(low);
  }
  return steps;
}

}  // namespace

std::uint8_t srgb_byte(float linear) {
  static const std::array<float, 255> steps = srgb_steps();
  if (std::isnan(linear)) return 0;
  return static_cast<std::uint8_t>(std::upper_bound(steps.begin(), steps.end(), linear) - steps.begin());
}

void append_records(ChunkedFile& file, std::size_t count, std::size_t record_bytes,
                    const std::function<void(std::size_t i, char* at)>& pack) {
  std::vector<char> block;
  for (std::size_t first = 0; first < count; first += kRecordsPerBlock) {
    const std::size_t n = std::min(kRecordsPerBlock, count - first);
    block.resize(n * record_bytes);
    using Range = tbb::blocked_range<std::size_t>;
    tbb::parallel_for(Range(0, n, 2048), [&](const Range& range) {
      for (std::size_t i = range.begin(); i < range.end(); ++i) pack(first + i, block.data() + i * record_bytes);
    });
    file.append(block.data(), block.size());
  }
}

MeshFormat mesh_format_of(const std::filesystem::path& path, const std::string& option) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (std::size_t i = 0; i < std::size(kMeshFormatNames); ++i) {
    if (extension == std::string(".") + kMeshFormatNames[i]) return static_cast<MeshFormat>(i);
  }
  throw InputError(fmt::format("{} {}: cannot write meshes with extension '{}' (expected .ply, .stl, .obj or .glb)",
                               option, path.string(), path.extension().string()));
}

void MeshFileWriter::begin(const MeshLayout& layout) {
  if (layout.triangles == 0)
    throw OutputError(fmt::format("{}: cannot write: the mesh has no triangles", file_.target().string()));
  layout_ = layout;
  write_begin();
}

void MeshFileWriter::add_vertices(const VertexBlock& block) {
  const std::size_t count = block.positions.size();
  for (const auto& [name, size, present] : {std::tuple{"normals", block.normals.size(), layout_.normals},
                                            std::tuple{"colors", block.colors.size(), layout_.colors}}) {
    if (size != (present ? count : 0)) {
      throw std::logic_error(fmt::format("TriangleMesh: {} {} for {} positions", size, name, count));
    }
  }
  if (triangles_ > 0 || vertices_ + count > layout_.vertices) {
    throw std::logic_error(fmt::format("TriangleMesh: vertices {} to {} of {} announced, after {} triangles", vertices_,
                                       vertices_ + count, layout_.vertices, triangles_));
  }
  write_vertices(block);
  vertices_ += count;
}

void MeshFileWriter::add_triangles(std::span<const MeshTriangle> block) {
  if (vertices_ != layout_.vertices || triangles_ + block.size() > layout_.triangles) {
    throw std::logic_error(fmt::format("TriangleMesh: triangles {} to {} of {} announced, after {} of {} vertices",
                                       triangles_, triangles_ + block.size(), layout_.triangles, vertices_,
                                       layout_.vertices));
  }
  for (std::size_t t = 0; t < block.size(); ++t) {
    for (const std::uint32_t index : block[t]) {
      if (index >= layout_.vertices) {
        throw std::logic_error(fmt::format("TriangleMesh: triangle {} has index {} of {} positions", triangles_ + t,
                                           index, layout_.vertices));
      }
    }
  }
  write_triangles(block);
  triangles_ += block.size();
}

void MeshFileWriter::finish() {
  if (vertices_ != layout_.vertices || triangles_ != layout_.triangles) {
    throw std::logic_error(fmt::format("TriangleMesh: {} vertices and {} triangles of {} and {} announced", vertices_,
                                       triangles_, layout_.vertices, layout_.triangles));
  }
  write_finish();
}

void stream_mesh(StagedFiles& files, const std::filesystem::path& path, MeshFormat format, MeshPrecision precision,
                 const std::function<void(MeshSink& sink)>& produce) {
  files.stage(path, [&](const std::filesystem::path& temp) {
    ChunkedFile file(temp, path);
    std::unique_ptr<MeshFileWriter> writer;
    switch (format) {
      case MeshFormat::Ply:
        writer = ply_writer(file, precision);
        break;
      case MeshFormat::Stl:
        writer = stl_writer(file);
        break;
      case MeshFormat::Obj:
        writer = obj_writer(file, precision);
        break;
      case MeshFormat::Glb:
        writer = glb_writer(file);
        break;
    }
    produce(*writer);
    file.close();
  });
}

void write_mesh(StagedFiles& files, const std::filesystem::path& path, const TriangleMesh& mesh, MeshFormat format,
                MeshPrecision precision) {
  stream_mesh(files, path, format, precision, [&](MeshSink& sink) { send_mesh(mesh, sink); });
}

}  // namespace clmarch
