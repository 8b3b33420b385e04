#include "io/mesh_io.h"

#include <spdlog/spdlog.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/input_file.h"

namespace relight {

namespace fs = std::filesystem;

// Beyond this a coordinate is a unit mistake, and the ray tracer's float
// arithmetic loses the scene (scene.json's positions have the same bound).
constexpr float kMaxCoordinate = 1.0e7f;

namespace {

bool has_faces(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m)
    if (scene.mMeshes[m]->mNumFaces > 0) return true;
  return false;
}

// Malformed files (a PLY with a broken header) can import as faces of no
// vertex, or with primitive-type flags that do not match the faces; either
// trips an assertion (an abort) in Assimp's triangulation. Drop the empty
// faces and set the flags from the faces that are left.
void make_faces_consistent(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh* mesh = scene.mMeshes[m];
    unsigned kept = 0, types = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned n = mesh->mFaces[f].mNumIndices;
      if (n == 0) continue;
      if (kept != f) std::swap(mesh->mFaces[kept], mesh->mFaces[f]);
      ++kept;
      types |= n == 1 ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    mesh->mNumFaces = kept;  // the array is freed whole with delete[], whatever this count
    mesh->mPrimitiveTypes = types;
  }
}

// Every element of a PLY body takes at least a byte: a header claiming more
// elements than the file has bytes is corrupt, and Assimp would reserve
// memory for all of them first (out of memory, found by fuzzing).
void expect_plausible_ply_counts(const fs::path& path, std::string_view header) {
  const uintmax_t file_size = fs::file_size(path);
  std::istringstream lines{std::string(header)};
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::string keyword, name, count_word;
    if (!(words >> keyword >> name >> count_word) || keyword != "element") continue;
    // Compared as a double: the count may be far beyond any integer type.
    if (std::strtod(count_word.c_str(), nullptr) > double(file_size))
      throw InputError(path.string(), "",
                       "the PLY header claims " + count_word + " " + name +
                           " elements, more than the file's " + std::to_string(file_size) + " bytes can hold");
  }
}

// Assimp's PLY reader runs past the end of a header that has no end_header
// line, or whose end_header is not ended by a line break (crashes found by
// fuzzing); Assimp picks it for any file that starts with "ply", whatever
// its name.
void expect_sound_ply_header(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64 * 1024, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  if (head.rfind("ply", 0) != 0) return;
  const std::string_view key = "end_header";
  for (size_t at = head.find(key); at != std::string::npos; at = head.find(key, at + 1)) {
    const std::string_view rest = std::string_view(head).substr(at + key.size());
    if (rest.starts_with("\n") || rest.starts_with("\r\n")) {
      expect_plausible_ply_counts(path, std::string_view(head).substr(0, at));
      return;
    }
  }
  throw InputError(path.string(), "", "a PLY header without an end_header line");
}

}  // namespace

size_t remove_degenerate_triangles(TriangleMesh& mesh) {
  const size_t before = mesh.triangles.size();
  std::erase_if(mesh.triangles, [&](const std::array<uint32_t, 3>& t) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    const Vec3 e1 = mesh.positions[t[1]] - mesh.positions[t[0]];
    const Vec3 e2 = mesh.positions[t[2]] - mesh.positions[t[0]];
    const float scale = std::max(e1.squaredNorm(), e2.squaredNorm());
    return !(e1.cross(e2).squaredNorm() > 1e-12f * scale * scale);
  });
  return before - mesh.triangles.size();
}

void save_obj(const fs::path& path, const TriangleMesh& mesh) {
  std::string text = "# written by relight\n";
  for (const auto& p : mesh.positions) text += fmt::format("v {:.6g} {:.6g} {:.6g}\n", p.x(), p.y(), p.z());
  for (const auto& n : mesh.normals) text += fmt::format("vn {:.6g} {:.6g} {:.6g}\n", n.x(), n.y(), n.z());
  for (const auto& t : mesh.triangles) {
    if (mesh.has_normals())
      text += fmt::format("f {0}//{0} {1}//{1} {2}//{2}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    else
      text += fmt::format("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  }
  write_text_atomically(path, text);
}

TriangleMesh load_mesh(const fs::path& path) {
  const std::string name = path.string();
  expect_input_file(path, "a mesh file");

  expect_sound_ply_header(path);
  Assimp::Importer importer;
  // Import and validate first: a malformed file's inconsistent data would
  // trip Assimp's assertions (an abort) in the post-processing steps.
  const aiScene* ai = importer.ReadFile(name, 0);
  if (ai && !has_faces(*ai)) throw InputError(name, "", "the mesh has no triangles");
  if (ai) ai = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure);
  if (ai) {
    make_faces_consistent(*ai);
    // Keep our own handling of degenerates (we report them); bake node
    // transforms so the mesh is in the world frame.
    ai = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                      aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
  }
  if (!ai) throw InputError(name, "", std::string("not a readable mesh (") + importer.GetErrorString() + ")");

  TriangleMesh mesh;
  bool all_have_normals = true;
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    const aiMesh* am = ai->mMeshes[m];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    if (!am->HasNormals()) all_have_normals = false;
  }
  for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
    const aiMesh* am = ai->mMeshes[m];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const uint32_t base = uint32_t(mesh.positions.size());
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      const aiVector3D& p = am->mVertices[v];
      const Vec3 pos(p.x, p.y, p.z);
      if (!is_finite(pos))
        throw InputError(name, fmt::format("mesh {} vertex {}", m, v), "has a NaN or infinite coordinate");
      if (pos.cwiseAbs().maxCoeff() > kMaxCoordinate)
        throw InputError(name, fmt::format("mesh {} vertex {}", m, v),
                         fmt::format("has a coordinate beyond {:g} m; expected metres", kMaxCoordinate));
      mesh.positions.push_back(pos);
      if (all_have_normals) {
        const aiVector3D& n = am->mNormals[v];
        Vec3 nn(n.x, n.y, n.z);
        mesh.normals.push_back(is_finite(nn) && nn.squaredNorm() > 0 ? nn.normalized() : Vec3::Zero());
      }
    }
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k)
        if (face.mIndices[k] >= am->mNumVertices)
          throw InputError(name, fmt::format("mesh {} face {}", m, f),
                           fmt::format("refers to vertex {} of {}", face.mIndices[k], am->mNumVertices));
      mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  if (mesh.triangles.empty()) throw InputError(name, "", "the mesh has no triangles");
  if (const size_t dropped = remove_degenerate_triangles(mesh))
    spdlog::warn("{}: dropped {} degenerate (zero-area) triangles", name, dropped);
  if (mesh.triangles.empty()) throw InputError(name, "", "every triangle of the mesh is degenerate (zero area)");
  // A zero normal (from a bad file) disables smooth shading for the whole mesh.
  for (const auto& n : mesh.normals)
    if (n.isZero()) {
      mesh.normals.clear();
      break;
    }
  return mesh;
}

}  // namespace relight
