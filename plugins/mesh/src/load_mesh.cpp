// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/mesh/load_mesh.h"

#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <Eigen/Core>
#include <Eigen/LU>  // determinant
#include <assimp/Importer.hpp>

#include "child_reader.h"
#include "cubespring/voxelize.h"  // default_memory_limit
#include "mesh_format.h"
#include "off_file.h"
#include "ply_file.h"

namespace cubespring {
namespace {

std::string format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

Status file_error(const std::string& path, const std::string& problem) { return Status::error(path + ": " + problem); }

// assimp's own message, cut short: its ASCII STL reader quotes the whole rest of the file after a
// bad number (a 700 kB message for one bad digit)
std::string reader_message(const char* message) {
  constexpr std::size_t kShown = 200;
  const std::string text(message);
  // assimp catches its own failed allocation and passes on only its name
  if (text == "std::bad_alloc") {
    return "it asked for more memory than it may take (std::bad_alloc): is the file malformed?";
  }
  if (text.size() <= kShown + 40) return text;
  return text.substr(0, kShown) + "... (" + std::to_string(text.size() - kShown) +
         " more characters of assimp's message)";
}

// assimp reports a missing file only as "Unable to open file"; checking first gives one clear
// message for missing files, directories and files without read permission.
Status check_readable(const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    return file_error(path, "cannot open: it is a directory, not a mesh file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) return file_error(path, "cannot open: no such file, or it is not readable");
  return {};
}

// Primitives of the scene as the importer made it, before triangulation.
struct PrimitiveCounts {
  std::uint64_t points = 0;
  std::uint64_t lines = 0;
  std::uint64_t polygons = 0;  ///< triangles and larger polygons
};

PrimitiveCounts count_primitives(const aiScene& scene) {
  PrimitiveCounts counts;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    // a point cloud comes as vertices without faces (the OBJ importer makes one of `v` lines)
    if (mesh.mNumFaces == 0) counts.points += mesh.mNumVertices;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const unsigned corners = mesh.mFaces[f].mNumIndices;
      if (corners == 1) ++counts.points;
      if (corners == 2) ++counts.lines;
      if (corners >= 3) ++counts.polygons;
    }
  }
  return counts;
}

Status no_triangles_error(const std::string& path, const aiScene& scene) {
  if (scene.mNumMeshes == 0) {
    return file_error(path,
                      "has no triangles: assimp found no mesh in it (is it really a file of "
                      "the format its extension names?)");
  }
  const PrimitiveCounts counts = count_primitives(scene);
  std::ostringstream out;
  out << "has no triangles (it holds " << counts.points << " points and " << counts.lines
      << " lines, which are ignored): a surface of triangles or polygons is needed";
  return file_error(path, out.str());
}

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4,  //
      m.b1, m.b2, m.b3, m.b4,     //
      m.c1, m.c2, m.c3, m.c4,     //
      m.d1, m.d2, m.d3, m.d4;
  return out;
}

std::string material_name(const aiScene& scene, const aiMesh& mesh) {
  if (mesh.mMaterialIndex >= scene.mNumMaterials) return "";
  aiString name;
  if (scene.mMaterials[mesh.mMaterialIndex]->Get(AI_MATKEY_NAME, name) != AI_SUCCESS) return "";
  const std::string text(name.C_Str());
  // assimp adds a material of this name to files that have none (STL, OBJ without usemtl)
  return text == AI_DEFAULT_MATERIAL_NAME ? std::string() : text;
}

int count_triangles(const aiMesh& mesh) {
  int count = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) count += mesh.mFaces[f].mNumIndices == 3 ? 1 : 0;
  return count;
}

// The mesh under construction: parts are appended in the order of the scene graph.
struct MeshBuilder {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<MeshPart> parts;
};

// Appends one (node, mesh) reference as a part. `transform` is the node's accumulated
// transform, `scale` the file unit in metres.
Status append_part(const aiScene& scene, const aiNode& node, const aiMesh& mesh, const Eigen::Matrix4d& transform,
                   double scale, const std::string& path, MeshBuilder& out) {
  const std::string name = mesh.mName.length > 0 ? mesh.mName.C_Str() : node.mName.C_Str();
  const std::size_t first_vertex = out.vertices.size();
  if (first_vertex + mesh.mNumVertices > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      out.triangles.size() + mesh.mNumFaces > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    return file_error(path, "has more vertices or triangles than a TriangleMesh can index (2^31 - 1)");
  }
  const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d translation = transform.topRightCorner<3, 1>();
  for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
    const aiVector3D& p = mesh.mVertices[v];
    const Eigen::Vector3d file_point(p.x, p.y, p.z);
    const Eigen::Vector3d point = scale * (linear * file_point + translation);
    // checked here, where the part and vertex are known: join_identical_vertices would only keep
    // a NaN apart from every other vertex
    if (!point.allFinite()) {
      std::ostringstream message;
      message << "part '" << name << "': vertex " << v << " is (" << p.x << ", " << p.y << ", " << p.z << ")";
      if (file_point.allFinite()) message << " in the file, but overflows with transform and scale";
      message << ": coordinates must be finite numbers";
      return file_error(path, message.str());
    }
    out.vertices.push_back(point);
  }
  // a mirroring transform turns the surface inside-out; reversing each triangle turns it back
  const bool mirrored = linear.determinant() < 0.0;
  MeshPart part{name, material_name(scene, mesh), static_cast<int>(out.triangles.size()), 0};
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;  // a point or line that triangulation left alone
    Eigen::Vector3i triangle;
    for (int corner = 0; corner < 3; ++corner) {
      const unsigned index = face.mIndices[corner];
      if (index >= mesh.mNumVertices) {
        std::ostringstream message;
        message << "part '" << name << "': face " << f << " refers to vertex " << index << ", but the mesh has "
                << mesh.mNumVertices << " vertices";
        return file_error(path, message.str());
      }
      triangle[corner] = static_cast<int>(first_vertex + index);
    }
    if (mirrored) std::swap(triangle[1], triangle[2]);
    out.triangles.push_back(triangle);
    ++part.triangle_count;
  }
  out.parts.push_back(std::move(part));
  return {};
}

// Walks the node tree depth-first (children in file order), with an explicit stack because
// files can nest nodes deeply.
Status append_scene(const aiScene& scene, double scale, const std::string& path, MeshBuilder& out) {
  struct Visit {
    const aiNode* node;
    Eigen::Matrix4d parent_transform;
  };
  std::vector<Visit> stack{{scene.mRootNode, Eigen::Matrix4d::Identity()}};
  while (!stack.empty()) {
    const Visit visit = stack.back();
    stack.pop_back();
    const aiNode& node = *visit.node;
    const Eigen::Matrix4d transform = visit.parent_transform * to_eigen(node.mTransformation);
    for (unsigned i = 0; i < node.mNumMeshes; ++i) {
      if (node.mMeshes[i] >= scene.mNumMeshes) {
        return file_error(path,
                          "node '" + std::string(node.mName.C_Str()) + "' refers to a mesh the file does not have");
      }
      const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
      if (count_triangles(mesh) == 0) continue;  // points or lines, split off by SortByPType
      Status appended = append_part(scene, node, mesh, transform, scale, path, out);
      if (!appended.ok()) return appended;
    }
    for (unsigned c = node.mNumChildren; c-- > 0;) stack.push_back({node.mChildren[c], transform});
  }
  return {};
}

TriangleMesh to_triangle_mesh(MeshBuilder&& built) {
  TriangleMesh mesh;
  mesh.vertices.resize(3, static_cast<Eigen::Index>(built.vertices.size()));
  for (std::size_t v = 0; v < built.vertices.size(); ++v) {
    mesh.vertices.col(static_cast<Eigen::Index>(v)) = built.vertices[v];
  }
  mesh.triangles.resize(3, static_cast<Eigen::Index>(built.triangles.size()));
  for (std::size_t t = 0; t < built.triangles.size(); ++t) {
    mesh.triangles.col(static_cast<Eigen::Index>(t)) = built.triangles[t];
  }
  mesh.parts = std::move(built.parts);
  return mesh;
}

Result<TriangleMesh> read_with_assimp(const std::string& path, const LoadOptions& options, MeshFormat format);

Result<TriangleMesh> load(const std::string& path, const LoadOptions& options) {
  if (!std::isfinite(options.scale) || options.scale <= 0.0) {
    return file_error(path, "scale = " + format(options.scale) +
                                ": LoadOptions::scale [m per file unit] must be a finite number > 0 "
                                "(0.001 for a file in millimetres, 0.01 for centimetres)");
  }
  if (!std::isfinite(options.reader_seconds) || options.reader_seconds < 0.0) {
    return file_error(path, "reader_seconds = " + format(options.reader_seconds) +
                                ": LoadOptions::reader_seconds [s] must be a finite number >= 0 (0: the default)");
  }
  Status readable = check_readable(path);
  if (!readable.ok()) return readable;
  // only the formats the project checks and fuzzes reach assimp's readers (mesh_format.h)
  Result<MeshFormat> format = mesh_format_of(path);
  if (!format.ok()) return format.status();
  // what assimp's PLY and OFF readers trust is checked first (ply_file.h, off_file.h)
  Status ply = check_ply_file(path);
  if (!ply.ok()) return ply;
  Status off = check_off_file(path);
  if (!off.ok()) return off;
  // assimp's COLLADA and glTF readers trust what no check here reads first (a stride of 2^32, a
  // letter in an index list crashed or hung them): they read in a process of their own. So does
  // the PLY reader, whose file passed the check above: a 343-byte file that the check found laid
  // out as its header says made it ask for 34 GB (fuzz_load_mesh, 200,000 inputs into a run)
  if (*format == MeshFormat::kCollada || *format == MeshFormat::kGltf || *format == MeshFormat::kPly) {
    std::error_code failed;  // (it was readable a moment ago; were its size unknown, none is added)
    const std::uintmax_t size = std::filesystem::file_size(path, failed);
    const double megabytes = failed ? 0.0 : static_cast<double>(size) / 1e6;
    ChildLimits limits;
    limits.seconds = options.reader_seconds > 0.0 ? options.reader_seconds : 10.0 + 2.0 * megabytes;
    limits.memory_bytes = default_memory_limit();
    const std::string reader = *format == MeshFormat::kCollada ? "assimp's COLLADA reader"
                               : *format == MeshFormat::kGltf  ? "assimp's glTF reader"
                                                               : "assimp's PLY reader";
    return read_in_child(path, reader, limits, [&] { return read_with_assimp(path, options, *format); });
  }
  return read_with_assimp(path, options, *format);
}

// The file read by assimp's reader of its format, checked (load() has checked what it can first).
Result<TriangleMesh> read_with_assimp(const std::string& path, const LoadOptions& options, MeshFormat format) {
  // No logger is created, so assimp stays quiet (its default logger discards everything).
  Assimp::Importer importer;
  keep_only_readers_of(importer, format);
  // keep the file's coordinates: other formats have no up axis, so none is imposed
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Read first without post-processing: validation rejects a point cloud (a mesh without faces)
  // with a message that does not say so, and the triangle count below does.
  const aiScene* scene = importer.ReadFile(path, 0);
  if (scene == nullptr) {
    return file_error(path, "assimp cannot read it: " + reader_message(importer.GetErrorString()));
  }
  if (count_primitives(*scene).polygons == 0) return no_triangles_error(path, *scene);
  // Validation first (assimp runs it before the other steps): it catches faces that refer to
  // missing vertices in formats whose importers do not check (PLY).
  scene = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    return file_error(path, "assimp rejects its content: " + reader_message(importer.GetErrorString()));
  }

  MeshBuilder built;
  Status appended = append_scene(*scene, options.scale, path, built);
  if (!appended.ok()) return appended;
  if (built.triangles.empty()) {
    return file_error(path, "has no triangles: no node of its scene refers to a mesh of triangles");
  }
  // Joined across parts too: touching parts share nothing in the simulation anyway.
  TriangleMesh mesh = join_identical_vertices(to_triangle_mesh(std::move(built)));
  Status valid = validate(mesh, path);
  if (!valid.ok()) return valid;
  return mesh;
}

}  // namespace

Result<TriangleMesh> load_mesh(const std::string& path, const LoadOptions& options) {
  // assimp catches its own import errors; this keeps anything else (bad_alloc on a corrupt
  // size field) from crossing the API.
  try {
    return load(path, options);
  } catch (const std::exception& e) {
    return file_error(path, std::string("loading failed: ") + e.what());
  }
}

}  // namespace cubespring
