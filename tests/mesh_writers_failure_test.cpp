// Mesh files that cannot be written: one line naming the file, no temporary file left, an older
// file at the target kept whole; a mesh that breaks TriangleMesh's rules is a bug, not a file.
#include "common/cancellation.hpp"
#include "common/errors.hpp"
#include "mesh/mesh_writers.hpp"
#include "support/mesh_checks.hpp"
#include "support/test_meshes.hpp"
#include "support/test_support.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>

#include <sys/resource.h>

namespace clmarch {
namespace {

using testing::read_text;
using testing::TempDir;

std::filesystem::path file_of(const TempDir& dir, std::size_t format) {
  return dir / (std::string("out.") + kMeshFormatNames[format]);
}

/// A file size limit for this process while it lives, with SIGXFSZ ignored so that a write past it
/// fails with EFBIG instead of killing the test (the limit binds root too).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &old_limit_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{bytes, old_limit_.rlim_max};
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old_limit_);
    std::signal(SIGXFSZ, old_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit old_limit_{};
  void (*old_handler_)(int) = nullptr;
};

using testing::CancellationReset;

TEST(MeshWritersFailure, MissingFolderFailsInOneLineAndLeavesNoFile) {
  TempDir dir;
  const TriangleMesh mesh = testing::octahedron({0.0, 0.0, 0.0}, 1.0).mesh;
  for (std::size_t i = 0; i < std::size(kMeshFormatNames); ++i) {
    const std::filesystem::path path = dir / "missing" / (std::string("out.") + kMeshFormatNames[i]);
    StagedFiles files;
    try {
      write_mesh(files, path, mesh, static_cast<MeshFormat>(i), MeshPrecision::Float);
      ADD_FAILURE() << path << " written";
    } catch (const OutputError& e) {
      EXPECT_EQ(std::string(e.what()), path.string() + ": cannot write: No such file or directory");
    }
  }
  EXPECT_EQ(dir.files(), std::vector<std::string>{});
}

// /proc takes no new files, for root too.
TEST(MeshWritersFailure, FolderThatTakesNoFilesFailsInOneLine) {
  StagedFiles files;
  try {
    write_mesh(files, "/proc/clmarch-mesh.ply", testing::octahedron({0.0, 0.0, 0.0}, 1.0).mesh, MeshFormat::Ply,
               MeshPrecision::Float);
    FAIL() << "written into /proc";
  } catch (const OutputError& e) {
    const std::string message = e.what();
    EXPECT_TRUE(message.starts_with("/proc/clmarch-mesh.ply: cannot write: ")) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// 256 KiB of a file of several MiB: the first 1 MiB chunk is cut short, in every format (GLB's
// through tinygltf's std::ostream, which ignores the stream's state).
TEST(MeshWritersFailure, WriteFailingHalfwayKeepsTheOldFileAndLeavesNoTemporary) {
  TempDir dir;
  const TriangleMesh mesh = testing::sheet(200);
  for (std::size_t i = 0; i < std::size(kMeshFormatNames); ++i) {
    std::ofstream(file_of(dir, i)) << "the previous mesh";
    StagedFiles files;
    try {
      const FileSizeLimit limit(256 * 1024);
      write_mesh(files, file_of(dir, i), mesh, static_cast<MeshFormat>(i), MeshPrecision::Double);
      ADD_FAILURE() << file_of(dir, i) << " written past the limit";
    } catch (const OutputError& e) {
      EXPECT_EQ(std::string(e.what()), file_of(dir, i).string() + ": cannot write: File too large");
    }
    EXPECT_EQ(read_text(file_of(dir, i)), "the previous mesh");
  }
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"out.glb", "out.obj", "out.ply", "out.stl"}))
      << "no temporary file stays";
}

TEST(MeshWritersFailure, CtrlCWhileWritingStopsTheWriteAndLeavesNoFile) {
  TempDir dir;
  const CancellationReset reset;
  cancellation_requested().store(true);
  StagedFiles files;
  EXPECT_THROW(write_mesh(files, dir / "out.ply", testing::sheet(200), MeshFormat::Ply, MeshPrecision::Float),
               Cancelled);
  EXPECT_EQ(dir.files(), std::vector<std::string>{});
}

// Assimp refuses an empty file of each format, and an empty mesh means the box missed the surface.
TEST(MeshWritersFailure, EmptyMeshIsRefusedAndWritesNoFile) {
  TempDir dir;
  TriangleMesh vertices_only = testing::octahedron({0.0, 0.0, 0.0}, 1.0).mesh;
  vertices_only.triangles.clear();
  for (std::size_t i = 0; i < std::size(kMeshFormatNames); ++i) {
    for (const TriangleMesh& mesh : {TriangleMesh{}, vertices_only}) {
      StagedFiles files;
      try {
        write_mesh(files, file_of(dir, i), mesh, static_cast<MeshFormat>(i), MeshPrecision::Float);
        ADD_FAILURE() << file_of(dir, i) << " written";
      } catch (const OutputError& e) {
        EXPECT_EQ(std::string(e.what()), file_of(dir, i).string() + ": cannot write: the mesh has no triangles");
      }
    }
  }
  EXPECT_EQ(dir.files(), std::vector<std::string>{});
}

TEST(MeshWritersFailure, MeshBreakingItsRulesIsABugNamingBothNumbers) {
  TempDir dir;
  TriangleMesh short_normals = testing::octahedron({0.0, 0.0, 0.0}, 1.0).mesh;
  short_normals.normals.pop_back();
  TriangleMesh bad_index = testing::octahedron({0.0, 0.0, 0.0}, 1.0).mesh;
  bad_index.triangles[3][1] = 6;
  for (const auto& [mesh, message] : {std::pair{short_normals, "TriangleMesh: 5 normals for 6 positions"},
                                      std::pair{bad_index, "TriangleMesh: triangle 3 has index 6 of 6 positions"}}) {
    StagedFiles files;
    try {
      write_mesh(files, dir / "out.ply", mesh, MeshFormat::Ply, MeshPrecision::Float);
      ADD_FAILURE() << message;
    } catch (const std::logic_error& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  }
  EXPECT_EQ(dir.files(), std::vector<std::string>{});
}

}  // namespace
}  // namespace clmarch
