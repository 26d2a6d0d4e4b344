// The choice of a mesh format by extension, the checks of a mesh before it is written, and the
// staged file every format is written into.
#include "mesh/mesh_writers.hpp"

#include "common/errors.hpp"
#include "mesh/chunked_file.hpp"
#include "mesh/format_writers.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <iterator>
#include <stdexcept>

namespace clmarch {
namespace {

/// Throws std::logic_error unless mesh keeps TriangleMesh's rules: a writer would otherwise write
/// a file that readers reject or read out of bounds.
void check_mesh(const TriangleMesh& mesh) {
  const std::size_t count = mesh.positions.size();
  for (const auto& [name, size] :
       {std::pair{"normals", mesh.normals.size()}, std::pair{"colors", mesh.colors.size()}}) {
    if (size != 0 && size != count) {
      throw std::logic_error(fmt::format("TriangleMesh: {} {} for {} positions", size, name, count));
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const std::uint32_t index : mesh.triangles[t]) {
      if (index >= count) {
        throw std::logic_error(fmt::format("TriangleMesh: triangle {} has index {} of {} positions", t, index, count));
      }
    }
  }
}

}  // namespace

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

void write_mesh(StagedFiles& files, const std::filesystem::path& path, const TriangleMesh& mesh, MeshFormat format,
                MeshPrecision precision) {
  check_mesh(mesh);
  if (mesh.triangles.empty())
    throw OutputError(fmt::format("{}: cannot write: the mesh has no triangles", path.string()));
  files.stage(path, [&](const std::filesystem::path& temp) {
    ChunkedFile file(temp, path);
    switch (format) {
      case MeshFormat::Ply:
        write_ply(file, mesh, precision);
        break;
      case MeshFormat::Stl:
        write_stl(file, mesh);
        break;
      case MeshFormat::Obj:
        write_obj(file, mesh, precision);
        break;
      case MeshFormat::Glb:
        write_glb(file, mesh);
        break;
    }
    file.close();
  });
}

}  // namespace clmarch
