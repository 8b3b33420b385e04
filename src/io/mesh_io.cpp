#include "io/mesh_io.h"

#include <spdlog/spdlog.h>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/child_process.h"
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

// Every line of a PLY header (before end_header) is one of the format's
// keywords with its words; Assimp's reader loops for ever on a header with
// a line of junk (found by fuzzing). And every element of the body takes at
// least a byte: a header claiming more elements than the file has bytes is
// corrupt, and Assimp would reserve memory for all of them first (out of
// memory, found by fuzzing).
void expect_sound_ply_header_lines(const fs::path& path, std::string_view header) {
  static const std::set<std::string, std::less<>> kTypes = {
      "char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
      "int16", "uint16", "int32", "uint32", "float32", "float64"};
  const auto refuse = [&](int line, const std::string& why) {
    throw InputError(path.string(), fmt::format("header line {}", line), why);
  };
  const uintmax_t file_size = fs::file_size(path);
  std::istringstream lines{std::string(header)};
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    for (const unsigned char c : line)
      if (c < 0x20 || c > 0x7e) refuse(number, "a PLY header line holds a byte that is not text");
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (number == 1) {
      if (w != std::vector<std::string>{"ply"}) refuse(number, "a PLY file starts with a line 'ply'");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (w.size() != 3) refuse(number, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
    } else if (w[0] == "element") {
      if (w.size() != 3) refuse(number, "expected 'element NAME COUNT'");
      // Compared as a double: the count may be far beyond any integer type.
      if (std::strtod(w[2].c_str(), nullptr) > double(file_size))
        throw InputError(path.string(), "",
                         "the PLY header claims " + w[2] + " " + w[1] + " elements, more than the file's " +
                             std::to_string(file_size) + " bytes can hold");
    } else if (w[0] == "property") {
      const bool list = w.size() == 5 && w[1] == "list" && kTypes.contains(w[2]) && kTypes.contains(w[3]);
      if (!list && !(w.size() == 3 && kTypes.contains(w[1])))
        refuse(number, "expected 'property TYPE NAME' or 'property list TYPE TYPE NAME' with a PLY type");
    } else {
      refuse(number, "'" + w[0] + "' is not a PLY header keyword");
    }
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
      expect_sound_ply_header_lines(path, std::string_view(head).substr(0, at));
      return;
    }
  }
  throw InputError(path.string(), "", "a PLY header without an end_header line");
}

std::atomic<bool> g_repair_meshes{false};

// Refuses degenerate triangles, or with repair_meshes() drops them.
void drop_degenerate_triangles(const std::string& name, TriangleMesh& mesh) {
  const std::vector<size_t> bad = degenerate_triangles(mesh);
  if (bad.empty()) return;
  if (bad.size() == mesh.triangles.size())
    throw InputError(name, "", "every triangle of the mesh is degenerate (zero area)");
  if (!repair_meshes())
    throw InputError(name, fmt::format("triangle {}", bad.front() + 1),
                     fmt::format("is degenerate (zero area){}: remove such triangles (Blender: Mesh > Clean Up > "
                                 "Degenerate Dissolve) or run with --repair-mesh to drop them",
                                 bad.size() == 2   ? std::string(", as is 1 other")
                                 : bad.size() > 2 ? fmt::format(", as are {} others", bad.size() - 1)
                                                  : std::string()));
  size_t kept = 0, next_bad = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (next_bad < bad.size() && bad[next_bad] == t) {
      ++next_bad;
      continue;
    }
    if (mesh.has_objects()) mesh.triangle_objects[kept] = mesh.triangle_objects[t];
    if (mesh.has_materials()) mesh.triangle_materials[kept] = mesh.triangle_materials[t];
    mesh.triangles[kept++] = mesh.triangles[t];
  }
  mesh.triangles.resize(kept);
  if (!mesh.triangle_objects.empty()) mesh.triangle_objects.resize(kept);
  if (!mesh.triangle_materials.empty()) mesh.triangle_materials.resize(kept);
  spdlog::warn("{}: dropped {} degenerate (zero-area) triangles", name, bad.size());
}

}  // namespace

std::vector<size_t> degenerate_triangles(const TriangleMesh& mesh) {
  std::vector<size_t> out;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      out.push_back(i);
      continue;
    }
    const Vec3 e1 = mesh.positions[t[1]] - mesh.positions[t[0]];
    const Vec3 e2 = mesh.positions[t[2]] - mesh.positions[t[0]];
    const float scale = std::max(e1.squaredNorm(), e2.squaredNorm());
    if (!(e1.cross(e2).squaredNorm() > 1e-12f * scale * scale)) out.push_back(i);
  }
  return out;
}

size_t count_non_manifold_edges(const TriangleMesh& mesh) {
  const std::vector<uint32_t> vertex = same_position_ids(mesh.positions);
  std::vector<uint64_t> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = vertex[t[k]], b = vertex[t[(k + 1) % 3]];
      edges.push_back((uint64_t(std::min(a, b)) << 32) | std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  size_t count = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    count += j - i > 2;
    i = j;
  }
  return count;
}

bool repair_meshes() { return g_repair_meshes.load(); }
void set_repair_meshes(bool repair) { g_repair_meshes.store(repair); }

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

namespace {

// Each mesh of the file as its nodes place it in the world: the node's
// name (the object's, in Blender's exports) and transform. A mesh placed by
// two nodes is there twice.
struct PlacedMesh {
  unsigned mesh;
  std::string object;
  aiMatrix4x4 transform;
};

std::vector<PlacedMesh> placed_meshes(const std::string& name, const aiScene& ai) {
  // An explicit stack, and a bound on the nodes visited: a malformed file's
  // node graph could be deep enough to overflow the call stack.
  constexpr size_t kMaxNodes = 1u << 20;
  std::vector<PlacedMesh> placed;
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack = {{ai.mRootNode, aiMatrix4x4()}};
  for (size_t visited = 0; !stack.empty(); ++visited) {
    if (visited > kMaxNodes) throw InputError(name, "", fmt::format("has over {} nodes", kMaxNodes));
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (!node) continue;
    const aiMatrix4x4 world = parent * node->mTransformation;
    for (unsigned k = 0; k < node->mNumMeshes; ++k)
      if (node->mMeshes[k] < ai.mNumMeshes) placed.push_back({node->mMeshes[k], node->mName.C_Str(), world});
    for (unsigned c = node->mNumChildren; c-- > 0;) stack.emplace_back(node->mChildren[c], world);
  }
  return placed;
}

// The material of Assimp's mesh `m` as the file names it: its index in
// `names` (added there the first time), or kNoMaterial where the file gives
// none (Assimp's placeholder).
uint32_t material_of(const aiScene& ai, unsigned m, std::vector<std::string>& names,
                     std::unordered_map<std::string, uint32_t>& index) {
  const unsigned k = ai.mMeshes[m]->mMaterialIndex;
  if (k >= ai.mNumMaterials || !ai.mMaterials[k]) return TriangleMesh::kNoMaterial;
  const std::string name = ai.mMaterials[k]->GetName().C_Str();
  if (name.empty() || name == AI_DEFAULT_MATERIAL_NAME) return TriangleMesh::kNoMaterial;
  const auto [it, added] = index.try_emplace(name, uint32_t(names.size()));
  if (added) names.push_back(name);
  return it->second;
}

// The file through Assimp, flattened to one mesh in the world frame, each
// triangle keeping the name of its object and its material; throws InputError.
TriangleMesh read_with_assimp(const fs::path& path) {
  const std::string name = path.string();
  Assimp::Importer importer;
  // Import and validate first: a malformed file's inconsistent data would
  // trip Assimp's assertions (an abort) in the post-processing steps.
  const aiScene* ai = importer.ReadFile(name, 0);
  if (ai && !has_faces(*ai)) throw InputError(name, "", "the mesh has no triangles");
  if (ai) ai = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure);
  if (ai) {
    make_faces_consistent(*ai);
    // Keep our own handling of degenerates (we report them).
    ai = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
  }
  if (!ai) throw InputError(name, "", std::string("not a readable mesh (") + importer.GetErrorString() + ")");

  const std::vector<PlacedMesh> placed = placed_meshes(name, *ai);
  TriangleMesh mesh;
  std::unordered_map<std::string, uint32_t> object_index;  // a scene may have thousands of objects
  std::unordered_map<std::string, uint32_t> material_index;
  bool all_have_normals = true;
  for (const PlacedMesh& p : placed) {
    const aiMesh* am = ai->mMeshes[p.mesh];
    if ((am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && !am->HasNormals()) all_have_normals = false;
  }
  for (const PlacedMesh& p : placed) {
    const aiMesh* am = ai->mMeshes[p.mesh];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const unsigned m = p.mesh;
    const aiMatrix3x3 normal_transform = aiMatrix3x3(p.transform).Inverse().Transpose();
    const uint32_t base = uint32_t(mesh.positions.size());
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      const aiVector3D q = p.transform * am->mVertices[v];
      const Vec3 pos(q.x, q.y, q.z);
      if (!is_finite(pos))
        throw InputError(name, fmt::format("mesh {} vertex {}", m, v), "has a NaN or infinite coordinate");
      if (pos.cwiseAbs().maxCoeff() > kMaxCoordinate)
        throw InputError(name, fmt::format("mesh {} vertex {}", m, v),
                         fmt::format("has a coordinate beyond {:g} m; expected metres", kMaxCoordinate));
      mesh.positions.push_back(pos);
      if (all_have_normals) {
        const aiVector3D n = normal_transform * am->mNormals[v];
        Vec3 nn(n.x, n.y, n.z);
        mesh.normals.push_back(is_finite(nn) && nn.squaredNorm() > 0 ? nn.normalized() : Vec3::Zero());
      }
    }
    const auto [object, added] = object_index.try_emplace(p.object, uint32_t(mesh.objects.size()));
    if (added) mesh.objects.push_back(p.object);
    const uint32_t material = material_of(*ai, m, mesh.materials, material_index);
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k)
        if (face.mIndices[k] >= am->mNumVertices)
          throw InputError(name, fmt::format("mesh {} face {}", m, f),
                           fmt::format("refers to vertex {} of {}", face.mIndices[k], am->mNumVertices));
      mesh.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
      mesh.triangle_objects.push_back(object->second);
      mesh.triangle_materials.push_back(material);
    }
  }
  return mesh;
}

// What the reading child hands back: 'M' and the mesh's arrays, or 'E' and
// the InputError's place and message.
template <class T>
void append_array(std::string& out, const std::vector<T>& v) {
  const uint64_t n = v.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  if (n) out.append(reinterpret_cast<const char*>(v.data()), n * sizeof(T));
}

template <class T>
bool take_array(std::string_view& in, std::vector<T>& v) {
  uint64_t n = 0;
  if (in.size() < sizeof n) return false;
  std::memcpy(&n, in.data(), sizeof n);
  in.remove_prefix(sizeof n);
  if (n > in.size() / sizeof(T)) return false;
  v.resize(n);
  if (n) std::memcpy(static_cast<void*>(v.data()), in.data(), n * sizeof(T));
  in.remove_prefix(n * sizeof(T));
  return true;
}

// Names joined with a '\0' after each, and split again.
std::vector<char> joined_names(const std::vector<std::string>& names) {
  std::vector<char> out;
  for (const std::string& n : names) {
    out.insert(out.end(), n.begin(), n.end());
    out.push_back('\0');
  }
  return out;
}

std::vector<std::string> split_names(const std::vector<char>& joined) {
  std::vector<std::string> names;
  for (auto begin = joined.begin(); begin != joined.end();) {
    const auto end = std::find(begin, joined.end(), '\0');
    names.emplace_back(begin, end);
    begin = end == joined.end() ? end : end + 1;
  }
  return names;
}

std::string encode_reading(const fs::path& path) {
  std::string out;
  try {
    const TriangleMesh mesh = read_with_assimp(path);
    out.push_back('M');
    append_array(out, mesh.positions);
    append_array(out, mesh.normals);
    append_array(out, mesh.triangles);
    append_array(out, mesh.triangle_objects);
    append_array(out, mesh.triangle_materials);
    append_array(out, joined_names(mesh.objects));
    append_array(out, joined_names(mesh.materials));
  } catch (const InputError& e) {
    out = "E" + e.where() + '\0' + e.message();
  }
  return out;
}

TriangleMesh decode_reading(const std::string& name, std::string_view in) {
  if (!in.empty() && in[0] == 'E') {
    in.remove_prefix(1);
    const size_t split = in.find('\0');
    throw InputError(name, std::string(in.substr(0, split)),
                     split == std::string_view::npos ? "unreadable" : std::string(in.substr(split + 1)));
  }
  TriangleMesh mesh;
  if (in.empty() || in[0] != 'M') throw InputError(name, "", "the mesh reader returned nothing");
  in.remove_prefix(1);
  std::vector<char> objects, materials;
  if (!take_array(in, mesh.positions) || !take_array(in, mesh.normals) || !take_array(in, mesh.triangles) ||
      !take_array(in, mesh.triangle_objects) || !take_array(in, mesh.triangle_materials) || !take_array(in, objects) ||
      !take_array(in, materials))
    throw InputError(name, "", "the mesh reader returned a cut-off mesh");
  mesh.objects = split_names(objects);
  mesh.materials = split_names(materials);
  return mesh;
}

}  // namespace

uint64_t mesh_reader_memory_limit(uint64_t file_bytes) { return (uint64_t(1) << 30) + 64 * file_bytes; }

TriangleMesh load_mesh(const fs::path& path, const Progress& progress) {
  const std::string name = path.string();
  expect_input_file(path, "a mesh file");
  expect_sound_ply_header(path);
  // Assimp's readers crash, hang or reserve memory for what a header claims
  // on some malformed files (several found by fuzzing, in PLY, OFF and STL);
  // reading in a child process turns those into an error about the file.
  // 20 s plus 2 s per megabyte is far beyond what a sound file takes (a
  // 1M-triangle OBJ reads in a few seconds), and under the fuzzers' 30 s
  // limit for one input.
  const uintmax_t bytes = fs::file_size(path);
  ChildLimits limits;
  limits.time = std::chrono::seconds(20 + 2 * (bytes >> 20));
  limits.memory_bytes = mesh_reader_memory_limit(bytes);
  const ChildResult read =
      run_in_child([&] { return encode_reading(path); }, limits, [&] { return progress.cancelled(); });
  if (read.cancelled) throw Cancelled();
  if (!read.ok)
    throw InputError(name, "", "the mesh reader " + read.failure +
                                   " on this file: it is malformed, or export it again (OBJ is the safest)");
  TriangleMesh mesh = decode_reading(name, read.bytes);

  if (mesh.triangles.empty()) throw InputError(name, "", "the mesh has no triangles");
  for (const auto& t : mesh.triangles)
    for (uint32_t i : t)
      if (i >= mesh.positions.size()) throw InputError(name, "", "the mesh reader returned a face past the vertices");
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
    throw InputError(name, "", "the mesh reader returned normals that do not match the vertices");
  for (uint32_t object : mesh.triangle_objects)
    if (object >= mesh.objects.size()) throw InputError(name, "", "the mesh reader returned an unnamed object");
  for (uint32_t material : mesh.triangle_materials)
    if (material != TriangleMesh::kNoMaterial && material >= mesh.materials.size())
      throw InputError(name, "", "the mesh reader returned an unnamed material");
  drop_degenerate_triangles(name, mesh);
  if (const size_t edges = count_non_manifold_edges(mesh))
    spdlog::warn("{}: {} edge{} shared by three or more triangles (non-manifold); rendered as two-sided surfaces",
                 name, edges, edges > 1 ? "s" : "");
  // A zero normal (from a bad file) disables smooth shading for the whole mesh.
  for (const auto& n : mesh.normals)
    if (n.isZero()) {
      mesh.normals.clear();
      break;
    }
  return mesh;
}

}  // namespace relight
