// The writer of each mesh format into an open file (mesh_writers.cpp picks one by MeshFormat), and
// the packing of binary records they share. Internal to mesh/.
#pragma once

#include "mesh/chunked_file.hpp"
#include "mesh/mesh_sink.hpp"
#include "mesh/mesh_writers.hpp"
#include "mesh/triangle_mesh.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <span>
#include <type_traits>

namespace clmarch {

// PLY's and STL's binary numbers and glTF's buffer are little-endian, and are copied from memory
// as they are.
static_assert(std::endian::native == std::endian::little, "the binary mesh writers assume a little-endian host");

/// Copies value's bytes to at and moves at past them (a binary record being packed).
template <typename T>
void pack(char*& at, T value) {
  static_assert(std::is_arithmetic_v<T>);
  std::memcpy(at, &value, sizeof value);
  at += sizeof value;
}

/// Appends count records of record_bytes each, record i packed by pack(i, at) into at: blocks of
/// records are packed on every core, then appended in order.
void append_records(ChunkedFile& file, std::size_t count, std::size_t record_bytes,
                    const std::function<void(std::size_t i, char* at)>& pack);

/// The 8-bit sRGB code of a linear colour channel (clamped to [0, 1], NaN as 0), as viewers show
/// PLY colours: lround(linear_to_srgb(linear) * 255), found among the 255 places where it steps.
std::uint8_t srgb_byte(float linear);

/// A file's MeshSink: the checks every format needs (the announced counts kept, indices in range,
/// attributes one a vertex; a mesh breaking them is a bug: std::logic_error naming the numbers as
/// TriangleMesh's rules do; no triangles: OutputError naming the file), then the format's writing.
class MeshFileWriter : public MeshSink {
 public:
  explicit MeshFileWriter(ChunkedFile& file) : file_(file) {}

  void begin(const MeshLayout& layout) final;
  void add_vertices(const VertexBlock& block) final;
  void add_triangles(std::span<const MeshTriangle> block) final;
  void finish() final;

 protected:
  /// The format's part of each call; vertices_written() and triangles_written() count the blocks
  /// before this one.
  virtual void write_begin() = 0;
  virtual void write_vertices(const VertexBlock& block) = 0;
  virtual void write_triangles(std::span<const MeshTriangle> block) = 0;
  virtual void write_finish() {}

  ChunkedFile& file() { return file_; }
  const MeshLayout& layout() const { return layout_; }
  std::uint64_t vertices_written() const { return vertices_; }
  std::uint64_t triangles_written() const { return triangles_; }

 private:
  ChunkedFile& file_;
  MeshLayout layout_;
  std::uint64_t vertices_ = 0;
  std::uint64_t triangles_ = 0;
};

/// Binary little-endian PLY, written as the mesh comes (mesh_writers.hpp says what each file holds).
std::unique_ptr<MeshFileWriter> ply_writer(ChunkedFile& file, MeshPrecision precision);
/// Binary STL: the positions kept (as STL's triangles repeat their corners), the triangles written
/// as they come.
std::unique_ptr<MeshFileWriter> stl_writer(ChunkedFile& file);
/// Wavefront OBJ text, written as the mesh comes.
std::unique_ptr<MeshFileWriter> obj_writer(ChunkedFile& file, MeshPrecision precision);
/// glTF 2.0 binary: the mesh kept whole and written at finish (GLB's header gives the sizes of its
/// chunks, and tinygltf writes a whole model).
std::unique_ptr<MeshFileWriter> glb_writer(ChunkedFile& file);

}  // namespace clmarch
