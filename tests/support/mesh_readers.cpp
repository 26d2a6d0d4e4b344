// Assimp's reading of mesh files, and the small readers of the numbers it keeps only as floats.
#include "support/mesh_readers.hpp"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

namespace clmarch::testing {
namespace {

std::vector<unsigned char> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <typename T>
T read_at(const std::vector<unsigned char>& bytes, std::size_t offset) {
  if (offset + sizeof(T) > bytes.size()) throw std::runtime_error("read past the end of the file");
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

glm::dvec3 transformed(const aiMatrix4x4& m, const aiVector3D& v, double w) {
  const glm::dvec4 p(v.x, v.y, v.z, w);
  const glm::dvec4 rows[3] = {{m.a1, m.a2, m.a3, m.a4}, {m.b1, m.b2, m.b3, m.b4}, {m.c1, m.c2, m.c3, m.c4}};
  return {glm::dot(rows[0], p), glm::dot(rows[1], p), glm::dot(rows[2], p)};
}

void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, ReadTriangles& out) {
  const aiMatrix4x4 world = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) throw std::runtime_error("a face of " + std::to_string(face.mNumIndices) + " corners");
      std::array<ReadCorner, 3> corners;
      for (int c = 0; c < 3; ++c) {
        const unsigned i = face.mIndices[c];
        corners[c].position = transformed(world, mesh.mVertices[i], 1.0);
        if (mesh.HasNormals()) corners[c].normal = transformed(world, mesh.mNormals[i], 0.0);
        if (mesh.HasVertexColors(0)) {
          const aiColor4D& color = mesh.mColors[0][i];
          corners[c].color = glm::dvec3(color.r, color.g, color.b);
        }
      }
      out.triangles.push_back(corners);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) collect(scene, *node.mChildren[c], world, out);
}

/// The size in bytes of a PLY scalar type.
std::size_t ply_type_size(const std::string& type) {
  static const std::map<std::string, std::size_t> sizes = {{"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},
                                                           {"short", 2}, {"ushort", 2},  {"int16", 2},  {"uint16", 2},
                                                           {"int", 4},   {"uint", 4},    {"int32", 4},  {"uint32", 4},
                                                           {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto found = sizes.find(type);
  if (found == sizes.end()) throw std::runtime_error("PLY type " + type);
  return found->second;
}

}  // namespace

std::size_t ReadTriangles::distinct_positions() const {
  std::set<std::array<double, 3>> positions;
  for (const auto& triangle : triangles) {
    for (const ReadCorner& corner : triangle)
      positions.insert({corner.position.x, corner.position.y, corner.position.z});
  }
  return positions.size();
}

ReadTriangles read_with_assimp(const std::filesystem::path& path) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw std::runtime_error("Assimp cannot read " + path.string() + ": " + importer.GetErrorString());
  }
  ReadTriangles out;
  collect(*scene, *scene->mRootNode, aiMatrix4x4(), out);
  return out;
}

std::vector<glm::dvec3> read_ply_positions(const std::filesystem::path& path) {
  const std::vector<unsigned char> bytes = file_bytes(path);
  const std::string text(bytes.begin(), bytes.end());
  const std::size_t end = text.find("end_header\n");
  if (end == std::string::npos) throw std::runtime_error("no end_header");
  std::istringstream header(text.substr(0, end));
  std::size_t count = 0, stride = 0;
  std::map<std::string, std::pair<std::size_t, std::string>> properties;  // name: offset, type
  bool in_vertex = false;
  for (std::string line; std::getline(header, line);) {
    std::istringstream words(line);
    std::string word, type, name;
    words >> word;
    if (word == "format" && line != "format binary_little_endian 1.0") throw std::runtime_error(line);
    if (word == "element") {
      words >> name;
      in_vertex = name == "vertex";
      if (in_vertex) words >> count;
    } else if (word == "property" && in_vertex) {
      words >> type >> name;
      properties[name] = {stride, type};
      stride += ply_type_size(type);
    }
  }
  std::vector<glm::dvec3> positions(count);
  const std::size_t body = end + std::strlen("end_header\n");
  for (int axis = 0; axis < 3; ++axis) {
    const auto& [offset, type] = properties.at(std::string(1, "xyz"[axis]));
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t at = body + i * stride + offset;
      positions[i][axis] = type == "double" ? read_at<double>(bytes, at) : read_at<float>(bytes, at);
    }
  }
  return positions;
}

std::vector<glm::dvec3> read_obj_positions(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<glm::dvec3> positions;
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("v ")) continue;
    glm::dvec3 p;
    const char* at = line.data() + 2;
    const char* end = line.data() + line.size();
    for (int axis = 0; axis < 3; ++axis) {
      while (at < end && *at == ' ') ++at;
      const auto [next, error] = std::from_chars(at, end, p[axis]);
      if (error != std::errc()) throw std::runtime_error("OBJ line " + line);
      at = next;
    }
    positions.push_back(p);
  }
  return positions;
}

std::vector<glm::dvec3> GlbChunks::vec3s(int accessor) const {
  const nlohmann::json& a = json.at("accessors").at(accessor);
  const nlohmann::json& view = json.at("bufferViews").at(a.at("bufferView").get<int>());
  if (a.at("componentType") != 5126 || a.at("type") != "VEC3" || view.contains("byteStride")) {
    throw std::runtime_error("accessor " + std::to_string(accessor) + " is not packed float vec3");
  }
  const std::size_t offset = view.value("byteOffset", std::size_t{0}) + a.value("byteOffset", std::size_t{0});
  std::vector<glm::dvec3> values(a.at("count").get<std::size_t>());
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) values[i][axis] = read_at<float>(bin, offset + (i * 3 + axis) * sizeof(float));
  }
  return values;
}

GlbChunks read_glb(const std::filesystem::path& path) {
  const std::vector<unsigned char> bytes = file_bytes(path);
  if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0 || read_at<std::uint32_t>(bytes, 4) != 2 ||
      read_at<std::uint32_t>(bytes, 8) != bytes.size()) {
    throw std::runtime_error("not a glTF 2.0 binary of its stated length");
  }
  GlbChunks chunks;
  for (std::size_t at = 12; at < bytes.size();) {
    const auto length = read_at<std::uint32_t>(bytes, at);
    const auto type = read_at<std::uint32_t>(bytes, at + 4);
    if (length % 4 != 0 || at + 8 + length > bytes.size()) throw std::runtime_error("a chunk past the end");
    const auto* data = bytes.data() + at + 8;
    if (type == 0x4E4F534A) {
      chunks.json = nlohmann::json::parse(data, data + length);
    } else if (type == 0x004E4942) {
      chunks.bin.assign(data, data + length);
    }
    at += 8 + length;
  }
  return chunks;
}

}  // namespace clmarch::testing
