// Writing a TriangleMesh as binary PLY, binary STL, OBJ or glTF binary (.glb), each file staged
// (a temporary file renamed on commit). What each file holds:
//   PLY  binary_little_endian 1.0. Element `vertex`: x, y, z (float, or double with
//        MeshPrecision::Double), then nx, ny, nz (float) where the mesh has normals, then red,
//        green, blue (uchar, the linear colour clamped to [0, 1], sRGB-encoded and rounded to 8
//        bits, as viewers show PLY colours) where it has colours. Element `face`: `property list uchar uint
//        vertex_indices`, 3 indices a face, counter-clockwise seen from outside.
//   STL  binary: an 80-byte header ("binary STL written by clmarch", padded with spaces; never
//        "solid", which readers take for ASCII STL), the triangle count (uint32), then 50 bytes a
//        triangle: its unit normal from its corners (0 for a degenerate one), its three corners
//        (float, absolute: STL has no offset, so far from the origin it keeps float's precision
//        alone), attribute 0. Positions only: no vertex normals, no colours, no shared vertices.
//   OBJ  text: `v x y z` a vertex, `v x y z r g b` where the mesh has colours (the common
//        extension; r, g, b the sRGB-encoded colour in [0, 1] to 6 digits, as for PLY), `vn nx ny
//        nz` a normal where the mesh has normals (a block's `vn` lines after its `v` lines: OBJ
//        numbers each kind apart, so vertex i has normal i), `f a//a b//b c//c` a triangle (1-based,
//        counter-clockwise; `f a b c` without normals). Positions and normals are the shortest
//        decimal that reads back as the same value: for positions the double (at most 17
//        significant digits) with MeshPrecision::Double, else the float.
//   GLB  glTF 2.0 binary through tinygltf: one buffer; one mesh of one triangle primitive with
//        POSITION (float vec3 with min and max), NORMAL and COLOR_0 (float vec3, linear as glTF
//        wants, clamped to [0, 1]) where the mesh has them, and UNSIGNED_INT indices; one material
//        (doubleSided false, metallicFactor 0: glTF's default of 1 would show a metal); one node
//        whose translation (in double) is the centre of the mesh's bounding box, the positions
//        being float offsets from it, so that a mesh far from the origin keeps its precision.
//        Positions are the scene's (y up, as glTF's). GLB's sizes are uint32: a mesh of more than
//        4 GiB fails with OutputError.
// A mesh without triangles is refused with OutputError, no file written: readers such as Assimp
// reject an empty file in each of these formats, and an empty mesh means that the sampled box
// missed the surface, which the user should hear of.
#pragma once

#include "common/atomic_file.hpp"
#include "mesh/mesh_sink.hpp"
#include "mesh/triangle_mesh.hpp"

#include <filesystem>
#include <functional>
#include <string>

namespace clmarch {

/// The file formats of meshes, by extension.
enum class MeshFormat { Ply, Stl, Obj, Glb };
/// Each MeshFormat's extension, without the dot, in enum order.
inline constexpr const char* kMeshFormatNames[] = {"ply", "stl", "obj", "glb"};

/// The format of path's extension (case-insensitive .ply .stl .obj .glb); throws InputError
/// "OPTION PATH: cannot write meshes with extension '.xyz' (expected .ply, .stl, .obj or .glb)".
MeshFormat mesh_format_of(const std::filesystem::path& path, const std::string& option);

/// Position precision of the file: float, or double where the format has it (PLY's double
/// properties, OBJ's decimal text with up to 17 significant digits); STL is float always; glTF
/// stores float positions relative to a node translation (the mesh's bounding-box centre, in
/// double) so that a far-from-origin mesh keeps its precision.
enum class MeshPrecision { Float, Double };

/// Writes the mesh that produce gives its sink to path in format as it comes, staged into files (in
/// place when they are committed; an exception from produce leaves no file). PLY and OBJ keep
/// nothing of the mesh, STL its positions, glTF all of it until the end. Throws OutputError with a
/// one-line message naming path when writing fails or the mesh has no triangles, std::logic_error
/// when the mesh breaks TriangleMesh's rules (attribute arrays of another length, an index past the
/// end, other counts than announced).
void stream_mesh(StagedFiles& files, const std::filesystem::path& path, MeshFormat format, MeshPrecision precision,
                 const std::function<void(MeshSink& sink)>& produce);

/// Writes mesh to path in format, staged into files, as stream_mesh does.
void write_mesh(StagedFiles& files, const std::filesystem::path& path, const TriangleMesh& mesh, MeshFormat format,
                MeshPrecision precision);

}  // namespace clmarch
