// The writer of each mesh format into an open file (mesh_writers.cpp picks one by MeshFormat), and
// the packing of binary records they share. Internal to mesh/.
#pragma once

#include "mesh/chunked_file.hpp"
#include "mesh/mesh_writers.hpp"
#include "mesh/triangle_mesh.hpp"

#include <bit>
#include <cstdint>
#include <cstring>
#include <functional>
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

/// Binary little-endian PLY (mesh_writers.hpp says what each file holds).
void write_ply(ChunkedFile& file, const TriangleMesh& mesh, MeshPrecision precision);
/// Binary STL.
void write_stl(ChunkedFile& file, const TriangleMesh& mesh);
/// Wavefront OBJ text.
void write_obj(ChunkedFile& file, const TriangleMesh& mesh, MeshPrecision precision);
/// glTF 2.0 binary.
void write_glb(ChunkedFile& file, const TriangleMesh& mesh);

}  // namespace clmarch
