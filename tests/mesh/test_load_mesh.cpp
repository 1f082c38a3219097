// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "cubespring/mesh/load_mesh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cubespring {
namespace {

namespace fs = std::filesystem;

/// Each test writes its files into a fresh directory of its own, removed afterwards.
class LoadMesh : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device random;
    dir_ = fs::temp_directory_path() /
           ("cubespring_test_load_mesh_" + std::string(info->name()) + "_" + std::to_string(random()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  std::string write(const std::string& name, const std::string& content) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << content;
    return path.string();
  }

  // A file load_mesh must refuse, with a short message holding `expected`.
  struct Refused {
    const char* name;
    std::string text;
    const char* expected;
  };
  void expect_each_refused(const std::vector<Refused>& files) const;

  fs::path dir_;
};

/// Sum over triangles of dot(a, cross(b, c)) / 6: the enclosed volume, > 0 when the triangles
/// are counter-clockwise seen from outside.
double signed_volume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t));
    const Eigen::Vector3d b = mesh.vertices.col(mesh.triangles(1, t));
    const Eigen::Vector3d c = mesh.vertices.col(mesh.triangles(2, t));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

using Point = std::array<double, 3>;

std::set<Point> vertex_set(const TriangleMesh& mesh) {
  std::set<Point> points;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    points.insert({mesh.vertices(0, v), mesh.vertices(1, v), mesh.vertices(2, v)});
  }
  return points;
}

/// The corners of the axis-aligned cube [low, high]^3, each coordinate multiplied by scale.
std::set<Point> cube_corners(double low, double high, double scale) {
  std::set<Point> corners;
  for (double x : {low, high}) {
    for (double y : {low, high}) {
      for (double z : {low, high}) corners.insert({x * scale, y * scale, z * scale});
    }
  }
  return corners;
}

void expect_error(const Result<TriangleMesh>& result, const std::string& path, const std::string& fragment = "") {
  ASSERT_FALSE(result.ok()) << "loaded " << result->num_triangles() << " triangles from " << path;
  EXPECT_NE(result.message().find(path), std::string::npos) << result.message();
  EXPECT_NE(result.message().find(fragment), std::string::npos)
      << "expected '" << fragment << "' in: " << result.message();
}

void LoadMesh::expect_each_refused(const std::vector<Refused>& files) const {
  for (const Refused& file : files) {
    SCOPED_TRACE(file.name);
    const std::string path = write(file.name, file.text);
    const Result<TriangleMesh> mesh = load_mesh(path);
    expect_error(mesh, path, file.expected);
    EXPECT_LT(mesh.message().size(), 300u) << mesh.message();
  }
}

// Two closed cubes of quads, counter-clockwise seen from outside: outer [0, 2]^3 and
// inner [0.5, 1.5]^3.
const char* const kTwoCubesObj = R"(mtllib two_cubes.mtl
o outer
v 0 0 0
v 2 0 0
v 2 2 0
v 0 2 0
v 0 0 2
v 2 0 2
v 2 2 2
v 0 2 2
usemtl skin
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
o inner
v 0.5 0.5 0.5
v 1.5 0.5 0.5
v 1.5 1.5 0.5
v 0.5 1.5 0.5
v 0.5 0.5 1.5
v 1.5 0.5 1.5
v 1.5 1.5 1.5
v 0.5 1.5 1.5
usemtl tumour
f 9 12 11 10
f 13 14 15 16
f 9 10 14 13
f 10 11 15 14
f 11 12 16 15
f 12 9 13 16
)";

const char* const kTwoCubesMtl = "newmtl skin\nKd 0.8 0.5 0.5\nnewmtl tumour\nKd 0.3 0.3 0.3\n";

TEST_F(LoadMesh, ObjObjectsBecomeNamedPartsWithTheirMaterials) {
  write("two_cubes.mtl", kTwoCubesMtl);
  const std::string path = write("two_cubes.obj", kTwoCubesObj);
  LoadOptions options;
  options.scale = 0.01;  // a file in centimetres
  const Result<TriangleMesh> mesh = load_mesh(path, options);
  ASSERT_TRUE(mesh.ok()) << mesh.message();

  ASSERT_EQ(mesh->parts.size(), 2u);
  EXPECT_EQ(mesh->parts[0].name, "outer");
  EXPECT_EQ(mesh->parts[0].material_name, "skin");
  EXPECT_EQ(mesh->parts[0].first_triangle, 0);
  EXPECT_EQ(mesh->parts[0].triangle_count, 12);  // 6 quads
  EXPECT_EQ(mesh->parts[1].name, "inner");
  EXPECT_EQ(mesh->parts[1].material_name, "tumour");
  EXPECT_EQ(mesh->parts[1].first_triangle, 12);
  EXPECT_EQ(mesh->parts[1].triangle_count, 12);
  EXPECT_EQ(mesh->num_triangles(), 24);
  EXPECT_EQ(mesh->num_vertices(), 16);  // the importer's per-face copies are joined

  // exact: one multiplication by the scale, no rounding through float on the way
  std::set<Point> expected = cube_corners(0.0, 2.0, 0.01);
  const std::set<Point> inner = cube_corners(0.5, 1.5, 0.01);
  expected.insert(inner.begin(), inner.end());
  EXPECT_EQ(vertex_set(*mesh), expected);
  // each part's triangles use its own cube's corners and enclose its volume (part_mesh keeps
  // all vertices, so collect the used ones)
  std::set<Point> outer_used;
  const TriangleMesh outer_mesh = part_mesh(*mesh, 0);
  for (int t = 0; t < outer_mesh.num_triangles(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const Eigen::Vector3d p = outer_mesh.vertices.col(outer_mesh.triangles(corner, t));
      outer_used.insert({p.x(), p.y(), p.z()});
    }
  }
  EXPECT_EQ(outer_used, cube_corners(0.0, 2.0, 0.01));
  EXPECT_NEAR(signed_volume(part_mesh(*mesh, 0)), 8e-6, 1e-18);
  EXPECT_NEAR(signed_volume(part_mesh(*mesh, 1)), 1e-6, 1e-18);
  EXPECT_TRUE(validate(*mesh).ok());
}

TEST_F(LoadMesh, ObjIgnoresLinesBesideTriangles) {
  const std::string path = write("mixed.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                 "f 1 3 2\nf 1 2 4\nl 1 4\nl 2 3\n");
  const Result<TriangleMesh> mesh = load_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  EXPECT_EQ(mesh->num_triangles(), 2);
  ASSERT_EQ(mesh->parts.size(), 1u);
  EXPECT_EQ(mesh->parts[0].triangle_count, 2);
  EXPECT_EQ(mesh->parts[0].material_name, "");  // assimp's "DefaultMaterial" means none
}

// A tetrahedron of volume 1/6 at the origin, counter-clockwise seen from outside.
Eigen::Matrix<double, 3, 4> tetrahedron() {
  Eigen::Matrix<double, 3, 4> corners;
  corners << 0, 1, 0, 0,  //
      0, 0, 1, 0,         //
      0, 0, 0, 1;
  return corners;
}
const Eigen::Matrix<double, 3, 4> kTetrahedron = tetrahedron();

const char* const kTetrahedronStl = R"(solid tet
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 -1 0
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0 0 1
 endloop
endfacet
facet normal -1 0 0
 outer loop
  vertex 0 0 0
  vertex 0 0 1
  vertex 0 1 0
 endloop
endfacet
facet normal 0.57735 0.57735 0.57735
 outer loop
  vertex 1 0 0
  vertex 0 1 0
  vertex 0 0 1
 endloop
endfacet
endsolid tet
)";

TEST_F(LoadMesh, StlVerticesRepeatedPerFacetAreJoined) {
  const std::string path = write("tet.stl", kTetrahedronStl);
  const Result<TriangleMesh> mesh = load_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  EXPECT_EQ(mesh->num_vertices(), 4);
  EXPECT_EQ(mesh->num_triangles(), 4);
  ASSERT_EQ(mesh->parts.size(), 1u);
  EXPECT_EQ(mesh->parts[0].name, "tet");  // the solid's name
  EXPECT_EQ(mesh->parts[0].material_name, "");
  EXPECT_EQ(vertex_set(*mesh), vertex_set(TriangleMesh{kTetrahedron, {}, {}}));
  EXPECT_DOUBLE_EQ(signed_volume(*mesh), 1.0 / 6.0);
}

TEST_F(LoadMesh, BinaryStlIsRead) {
  // 80-byte header, facet count, then per facet: normal, 3 vertices (float32) and 2 spare bytes;
  // little-endian, written as the (x86, ARM) host stores them
  std::string bytes(80, ' ');
  const auto append = [&bytes](const void* data, std::size_t size) {
    bytes.append(static_cast<const char*>(data), size);
  };
  const std::uint32_t facets = 4;
  append(&facets, sizeof facets);
  const int corners[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& facet : corners) {
    const float normal[3] = {0.0f, 0.0f, 0.0f};
    append(normal, sizeof normal);
    for (int corner : facet) {
      const float point[3] = {static_cast<float>(kTetrahedron(0, corner)), static_cast<float>(kTetrahedron(1, corner)),
                              static_cast<float>(kTetrahedron(2, corner))};
      append(point, sizeof point);
    }
    const std::uint16_t attributes = 0;
    append(&attributes, sizeof attributes);
  }
  const std::string path = write("tet_binary.stl", bytes);
  const Result<TriangleMesh> mesh = load_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  EXPECT_EQ(mesh->num_vertices(), 4);
  EXPECT_EQ(mesh->num_triangles(), 4);
  EXPECT_DOUBLE_EQ(signed_volume(*mesh), 1.0 / 6.0);
}

const char* const kTetrahedronPly = R"(ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 4
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
0 1 0
0 0 1
3 0 2 1
3 0 1 3
3 0 3 2
3 1 2 3
)";

TEST_F(LoadMesh, PlyKeepsVerticesAndTriangles) {
  const std::string path = write("tet.ply", kTetrahedronPly);
  const Result<TriangleMesh> mesh = load_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  ASSERT_EQ(mesh->num_vertices(), 4);
  EXPECT_EQ(mesh->vertices, Eigen::Matrix3Xd(kTetrahedron));
  Eigen::Matrix3Xi expected(3, 4);
  expected << 0, 0, 0, 1,  //
      2, 1, 3, 2,          //
      1, 3, 2, 3;
  EXPECT_EQ(mesh->triangles, expected);
  EXPECT_DOUBLE_EQ(signed_volume(*mesh), 1.0 / 6.0);
}

/// A COLLADA file with the tetrahedron under two nested nodes: `outer_matrix` (the parent) and
/// `inner_matrix`, each 16 numbers in COLLADA's row-major order.
std::string tetrahedron_dae(const std::string& outer_matrix, const std::string& inner_matrix,
                            const std::string& unit = "1", const std::string& up_axis = "Y_UP") {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="file unit" meter=")" +
         unit + R"("/><up_axis>)" + up_axis + R"(</up_axis></asset>
  <library_geometries>
    <geometry id="tet" name="tet">
      <mesh>
        <source id="tet-positions">
          <float_array id="tet-positions-array" count="12">0 0 0 1 0 0 0 1 0 0 0 1</float_array>
          <technique_common>
            <accessor source="#tet-positions-array" count="4" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="tet-vertices"><input semantic="POSITION" source="#tet-positions"/></vertices>
        <triangles count="4">
          <input semantic="VERTEX" source="#tet-vertices" offset="0"/>
          <p>0 2 1 0 1 3 0 3 2 1 2 3</p>
        </triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene">
      <node id="outer" name="outer">
        <matrix>)" +
         outer_matrix + R"(</matrix>
        <node id="inner" name="inner">
          <matrix>)" +
         inner_matrix + R"(</matrix>
          <instance_geometry url="#tet"/>
        </node>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
}

const char* const kIdentity = "1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1";

/// Each vertex of `mesh` matched to the one of `expected` (3 x 4) within `tolerance`.
void expect_vertices(const TriangleMesh& mesh, const Eigen::Matrix<double, 3, 4>& expected, double tolerance) {
  ASSERT_EQ(mesh.num_vertices(), 4);
  for (int e = 0; e < 4; ++e) {
    double nearest = std::numeric_limits<double>::infinity();
    for (int v = 0; v < 4; ++v) nearest = std::min(nearest, (mesh.vertices.col(v) - expected.col(e)).norm());
    EXPECT_LE(nearest, tolerance) << "expected vertex (" << expected.col(e).transpose() << ")";
  }
}

TEST_F(LoadMesh, NodeTransformsAccumulateFromTheRoot) {
  // parent: translation by (0.5, -1.25, 2); child: the rotation by 120 degrees about (1, 1, 1),
  // which maps (x, y, z) to (z, x, y). Both exact in float, so the result is exact too.
  const std::string path = write(
      "moved.dae", tetrahedron_dae("1 0 0 0.5  0 1 0 -1.25  0 0 1 2  0 0 0 1", "0 0 1 0  1 0 0 0  0 1 0 0  0 0 0 1"));
  const Result<TriangleMesh> mesh = load_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  Eigen::Matrix3d rotation;
  rotation << 0, 0, 1,  //
      1, 0, 0,          //
      0, 1, 0;
  Eigen::Matrix<double, 3, 4> expected = rotation * kTetrahedron;
  expected.colwise() += Eigen::Vector3d(0.5, -1.25, 2.0);  // parent applied after the child
  expect_vertices(*mesh, expected, 1e-12);
  ASSERT_EQ(mesh->parts.size(), 1u);
  EXPECT_EQ(mesh->parts[0].name, "tet");  // the geometry's name, not the node's
  EXPECT_NEAR(signed_volume(*mesh), 1.0 / 6.0, 1e-12);
}

TEST_F(LoadMesh, MirroringTransformKeepsTrianglesFacingOutwards) {
  // x -> -x on the parent, translation in the child: determinant -1
  const std::string path = write(
      "mirrored.dae", tetrahedron_dae("-1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1", "1 0 0 3  0 1 0 0  0 0 1 0  0 0 0 1"));
  LoadOptions options;
  options.scale = 0.5;
  const Result<TriangleMesh> mesh = load_mesh(path, options);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  Eigen::Matrix<double, 3, 4> expected = kTetrahedron;
  expected.row(0) = (-(expected.row(0).array() + 3.0)).matrix();
  expect_vertices(*mesh, 0.5 * expected, 1e-12);
  EXPECT_NEAR(signed_volume(*mesh), 0.125 / 6.0, 1e-12);  // positive: not inside-out
}

TEST_F(LoadMesh, ColladaUnitIsAppliedByAssimpAndUpAxisIgnored) {
  // assimp scales by <unit meter> itself; a Z_UP file keeps its coordinates (no rotation)
  const std::string path = write("centimetres.dae", tetrahedron_dae(kIdentity, kIdentity, "0.01", "Z_UP"));
  const Result<TriangleMesh> mesh = load_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  expect_vertices(*mesh, 0.01 * kTetrahedron, 1e-9);  // 0.01 passes through a float
  EXPECT_NEAR(signed_volume(*mesh), 1e-6 / 6.0, 1e-12);
}

// ---- errors: each names the file and the problem -----------------------------------------------

TEST_F(LoadMesh, MissingFileIsReported) {
  const std::string path = (dir_ / "no_such_file.obj").string();
  expect_error(load_mesh(path), path, "cannot open");
}

TEST_F(LoadMesh, DirectoryIsReported) {
  const std::string path = dir_.string();
  expect_error(load_mesh(path), path, "cannot open");
}

TEST_F(LoadMesh, GarbageIsReported) {
  std::mt19937 random(2026);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = static_cast<char>(random() & 0xff);
  for (const char* name :
       {"garbage.obj", "garbage.stl", "garbage.ply", "garbage.dae", "garbage.gltf", "garbage.xyz123"}) {
    SCOPED_TRACE(name);
    const std::string path = write(name, garbage);
    expect_error(load_mesh(path), path);
  }
}

// assimp's COLLADA reader crashed on a stride of 2^32 and hung on a letter in an index list (issue
// 30's mutants); it reads in a process of its own, so both are errors naming the file and the
// reader, and the file around them still reads, its parts and all, through the same process.
TEST_F(LoadMesh, ACrashOrHangOfTheColladaReaderIsAnError) {
  const std::string good = tetrahedron_dae(kIdentity, kIdentity);
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::string crash = write("stride.dae", with("stride=\"3\"", "stride=\"4294967296\""));
  LoadOptions patient;  // AddressSanitizer's report of the crash takes its time
  patient.reader_seconds = 120.0;
  const Result<TriangleMesh> crashed = load_mesh(crash, patient);
  expect_error(crashed, crash, "assimp's COLLADA reader");
  // a crash under AddressSanitizer ends the child by its report and exit code, not the signal
  EXPECT_TRUE(crashed.message().find("crashed on it") != std::string::npos ||
              crashed.message().find("stopped before it had read it") != std::string::npos)
      << crashed.message();

  const std::string hang = write("letter.dae", with("0 2 1 0 1 3", "0 2 1 0 x 3"));
  LoadOptions quick;
  quick.reader_seconds = 1.0;
  const auto started = std::chrono::steady_clock::now();
  expect_error(load_mesh(hang, quick), hang, "took more than 1 s on it and was stopped");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 20.0);

  LoadOptions forever;
  forever.reader_seconds = std::numeric_limits<double>::infinity();
  expect_error(load_mesh(hang, forever), hang, "reader_seconds = inf");

  const Result<TriangleMesh> mesh = load_mesh(write("tet.dae", good));
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  EXPECT_EQ(mesh->num_vertices(), 4);
  EXPECT_EQ(mesh->num_triangles(), 4);
  ASSERT_EQ(mesh->parts.size(), 1u);
  EXPECT_EQ(mesh->parts[0].name, "tet");
  EXPECT_DOUBLE_EQ(signed_volume(*mesh), 1.0 / 6.0);
}

// PLY reads in a process of its own too, after its check: a binary file the check passes made
// assimp's reader ask for 34 GB (found by fuzz_load_mesh); it is an error naming the file and the
// reader, and a good PLY file still reads.
TEST_F(LoadMesh, APlyFileThatPassesTheCheckButAsksForGigabytesIsAnError) {
  const std::string path = std::string(CUBESPRING_TEST_DATA_DIR) + "/mesh/ply_asks_34_gigabytes.ply";
  LoadOptions patient;  // AddressSanitizer's report of the child's failed allocation takes its time
  patient.reader_seconds = 120.0;
  const Result<TriangleMesh> read = load_mesh(path, patient);
  // under AddressSanitizer the child stops on the allocation; else assimp catches it
  expect_error(read, path);
  EXPECT_TRUE(read.message().find("more memory than it may take") != std::string::npos ||
              read.message().find("assimp's PLY reader") != std::string::npos)
      << read.message();
}

// glTF reads in a process of its own too: the tetrahedron (its buffer inline, as base64) comes
// back whole, and an accessor past its buffer is assimp's own error, passed on.
TEST_F(LoadMesh, GltfReadsThroughItsOwnProcess) {
  const std::string tetrahedron =
      R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "tet"}],)"
      R"( "meshes": [{"name": "tet", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],)"
      R"( "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)"
      R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAACAAEAAAABAAMAAAADAAIAAQACAAMA"}],)"
      R"( "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],)"
      R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0],)"
      R"( "max": [1, 1, 1]}, {"bufferView": 1, "componentType": 5123, "count": COUNT, "type": "SCALAR"}]})";
  std::string good = tetrahedron, past = tetrahedron;
  good.replace(good.find("COUNT"), 5, "12");
  past.replace(past.find("COUNT"), 5, "4000000000");
  const Result<TriangleMesh> mesh = load_mesh(write("tet.gltf", good));
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  EXPECT_EQ(mesh->num_triangles(), 4);
  ASSERT_EQ(mesh->parts.size(), 1u);
  EXPECT_EQ(mesh->parts[0].name, "tet");
  EXPECT_DOUBLE_EQ(signed_volume(*mesh), 1.0 / 6.0);
  const std::string path = write("past.gltf", past);
  expect_error(load_mesh(path), path, "out of range");
}

// assimp's ASCII STL reader quotes the rest of the file after a bad number: one bad digit in a
// 5,000-facet file gave a 700 kB message
TEST_F(LoadMesh, AReaderMessageQuotingTheFileIsCutShort) {
  std::string stl =
      "solid bad\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 x.5\n  vertex 0 1 0\n"
      " endloop\nendfacet\n";
  for (int i = 0; i < 5000; ++i)
    stl += "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n";
  stl += "endsolid bad\n";
  const std::string path = write("bad_number.stl", stl);
  const Result<TriangleMesh> mesh = load_mesh(path);
  expect_error(mesh, path, "x.5");
  EXPECT_LT(mesh.message().size(), 600u) << mesh.message().substr(0, 600);
  EXPECT_NE(mesh.message().find("more characters of assimp's message"), std::string::npos);
}

// ---- the closed list of formats (mesh_format.h) -------------------------------------------------

TEST_F(LoadMesh, AFileOfAnUnknownExtensionIsReadByAListedFormatsContent) {
  // assimp recognises some formats by their content whatever the extension (PLY by its header)
  for (const char* name : {"tet.xyz123", "tet"}) {
    SCOPED_TRACE(name);
    const Result<TriangleMesh> ply = load_mesh(write(name, kTetrahedronPly));
    ASSERT_TRUE(ply.ok()) << ply.message();
    EXPECT_EQ(ply->num_triangles(), 4);
  }
  const Result<TriangleMesh> stl = load_mesh(write("tet.xyz123", kTetrahedronStl));
  ASSERT_TRUE(stl.ok()) << stl.message();
  EXPECT_EQ(stl->num_triangles(), 4);
}

// Only the readers of the file's format see it: assimp tries every reader by content when the
// one its extension names declines, and sniffs a file of an unknown extension in its own order.
TEST_F(LoadMesh, OnlyTheReadersOfTheFilesFormatSeeIt) {
  // an FBX file named .glb: the glTF readers decline it, and assimp's FBX reader read it before
  std::string fbx = "Kaydara FBX Binary  ";
  fbx.push_back('\0');
  fbx += std::string(100, '\x1a');
  const std::string glb = write("scene.glb", fbx);
  const Result<TriangleMesh> as_glb = load_mesh(glb);
  expect_error(as_glb, glb);
  EXPECT_EQ(as_glb.message().find("FBX"), std::string::npos) << as_glb.message();
  // a file named only ".obj" is an OBJ file (assimp takes the extension from the last dot)
  const Result<TriangleMesh> dotfile = load_mesh(write(".obj",
                                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                                       "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"));
  ASSERT_TRUE(dotfile.ok()) << dotfile.message();
  EXPECT_EQ(dotfile->num_triangles(), 4);
  const std::string fbx_dotfile = write(".fbx", kTetrahedronPly);
  expect_error(load_mesh(fbx_dotfile), fbx_dotfile, "its extension is '.fbx'");
}

// A format assimp reads but the project neither checks nor fuzzes is refused before any reader
// runs, whatever the file holds; so is a file of no listed format. The message names the list.
TEST_F(LoadMesh, AFormatOffTheListIsRefusedNamingTheList) {
  const std::string list = "OBJ (.obj), STL (.stl), PLY (.ply), OFF (.off), glTF (.gltf, .glb), COLLADA (.dae)";
  const std::string named = "', a format cubespring does not read (it reads " + list;
  const std::string unknown = " and its first bytes are none of the formats cubespring reads (" + list;
  // what each message says, kept here: Refused holds pointers
  const std::string fbx = "its extension is '.fbx" + named, three_ds = "its extension is '.3ds" + named,
                    direct_x = "its extension is '.x" + named, xyz = "its extension is '.xyz123'" + unknown,
                    none = "it has no extension" + unknown;
  const std::vector<Refused> cases = {
      // assimp would take these by their extension (its FBX, 3DS and DirectX readers), a valid
      // PLY inside or not
      {"tet.fbx", kTetrahedronPly, fbx.c_str()},
      {"tet.3DS", "MM\x10", three_ds.c_str()},
      {"tet.x", "xof 0303txt 0032\n", direct_x.c_str()},
      // an OBJ has no mark of its own: its content is not enough without the extension
      {"tet.xyz123", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", xyz.c_str()},
      {"words", "these are not the coordinates you are looking for\n", none.c_str()},
      {"empty.xyz123", "", xyz.c_str()},
  };
  expect_each_refused(cases);
}

TEST_F(LoadMesh, EmptyFileIsReported) {
  const std::string path = write("empty.obj", "");
  expect_error(load_mesh(path), path);
}

TEST_F(LoadMesh, PointCloudHasNoTriangles) {
  const std::string path = write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
  expect_error(load_mesh(path), path, "no triangles");
  const Result<TriangleMesh> mesh = load_mesh(path);
  EXPECT_NE(mesh.message().find("4 points"), std::string::npos) << mesh.message();
}

TEST_F(LoadMesh, LinesHaveNoTriangles) {
  const std::string path = write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  expect_error(load_mesh(path), path, "no triangles");
}

TEST_F(LoadMesh, NonFiniteCoordinatesAreReported) {
  // assimp parses "nan" and "inf" and keeps them: the loader must catch them
  for (const char* value : {"nan", "inf", "-inf"}) {
    SCOPED_TRACE(value);
    const std::string path =
        write(std::string("bad_") + (value[0] == '-' ? "minus_inf" : value) + ".obj",
              std::string("v 0 0 0\nv ") + value + " 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    expect_error(load_mesh(path), path, "finite");
  }
}

TEST_F(LoadMesh, HugeCoordinatesThatOverflowWithTheScaleAreReported) {
  const std::string path = write("huge.obj", "v 0 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n");
  LoadOptions options;
  options.scale = 1e300;
  expect_error(load_mesh(path, options), path, "finite");
}

TEST_F(LoadMesh, ObjFaceIndexingAMissingVertexIsReported) {
  const std::string path = write("bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 99\nf 1 3 4\n");
  expect_error(load_mesh(path), path, "out of range");
}

TEST_F(LoadMesh, PlyFaceIndexingAMissingVertexIsReported) {
  // assimp's PLY importer does not check indices; its validation step does
  std::string text = kTetrahedronPly;
  text.replace(text.find("3 1 2 3"), 7, "3 1 2 99");
  const std::string path = write("bad_index.ply", text);
  expect_error(load_mesh(path), path, "out of range");
}

// A binary little-endian PLY of the tetrahedron; `end_line` ends its header.
std::string binary_tetrahedron_ply(const std::string& end_line = "end_header") {
  std::string text =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
      "property float z\nelement face 4\nproperty list uchar int vertex_indices\n" +
      end_line + "\n";
  const auto append = [&text](const auto& value) { text.append(reinterpret_cast<const char*>(&value), sizeof(value)); };
  const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& corner : corners) {
    for (const float c : corner) append(c);
  }
  const std::int32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& face : faces) {
    append(static_cast<std::uint8_t>(3));
    for (const std::int32_t i : face) append(i);
  }
  return text;
}

TEST_F(LoadMesh, BinaryPlyKeepsItsTriangles) {
  const Result<TriangleMesh> mesh = load_mesh(write("tet_binary.ply", binary_tetrahedron_ply()));
  ASSERT_TRUE(mesh.ok()) << mesh.message();
  EXPECT_EQ(mesh->num_triangles(), 4);
  EXPECT_DOUBLE_EQ(signed_volume(*mesh), 1.0 / 6.0);
}

// assimp 5.2 trusts a PLY header: without 'end_header' it read forever, with it damaged in a
// binary file it crashed (SIGSEGV), with a count larger than the file it allocated gigabytes
TEST_F(LoadMesh, APlyHeaderAssimpWouldTrustIsCheckedFirst) {
  std::string huge = kTetrahedronPly;
  huge.replace(huge.find("element vertex 4"), 16, "element vertex 4000000000");
  std::string typo = kTetrahedronPly;
  typo.replace(typo.find("property float y"), 16, "property flaot y");
  std::string long_list = binary_tetrahedron_ply();
  long_list[long_list.size() - 13] = static_cast<char>(255);  // the last face's corner count
  const std::vector<Refused> cases = {
      {"cut.ply", "ply\nformat ascii 1.0\n", "no 'end_header' line in its first 21 bytes"},
      {"damaged.ply", binary_tetrahedron_ply("end_heaxer"), "line 9: 'end_heaxer' is not a PLY header line"},
      {"huge.ply", huge, "line 3: declares 4000000000 'vertex' elements"},
      {"typo.ply", typo, "line 5: 'property flaot y': expected 'property TYPE NAME'"},
      // assimp knows a PLY by its first line, whatever the extension
      {"cut.xyz123", "ply\nformat ascii 1.0\nelement vertex 3\n", "no 'end_header'"},
      // and by its extension, whatever the first line (found by fuzzing: a crash)
      {"not_ply.ply", "ply\x9d\x9d\nformat ascii 1.0\n", "line 1: a PLY file begins with the line 'ply'"},
      // a second format line, binary then ASCII, made assimp write past its arrays (fuzzing)
      {"two_formats.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\nformat ascii 1.0\nend_header\n1\n2\n",
       "line 5: a second 'format' line"},
      // a binary face list longer than the file
      {"long_list.ply", long_list, "line 7: the file ends inside its 'face' elements"},
      // a vertical tab after 'end_header' hid it from assimp, which read forever (fuzzing)
      {"tab.ply", std::string(kTetrahedronPly).replace(std::string(kTetrahedronPly).find("end_header") + 10, 1, "\v"),
       "line 9: 'end_header?0 0 0' holds a byte that is not text"},
  };
  expect_each_refused(cases);
}

const char* const kTetrahedronOff = "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

TEST_F(LoadMesh, OffKeepsItsTriangles) {
  for (const std::string& text :
       {std::string(kTetrahedronOff), "# a comment\nOFF 4 4 6\n" + std::string(kTetrahedronOff).substr(10)}) {
    const Result<TriangleMesh> mesh = load_mesh(write("tet.off", text));
    ASSERT_TRUE(mesh.ok()) << mesh.message();
    EXPECT_EQ(mesh->num_triangles(), 4);
    EXPECT_DOUBLE_EQ(signed_volume(*mesh), 1.0 / 6.0);
  }
}

// assimp 5.2's OFF reader copies each line into 4096 bytes unchecked (a 100,000-character comment
// line crashed it, SIGSEGV) and allocates what its counts declare before reading
TEST_F(LoadMesh, AnOffFileAssimpWouldTrustIsCheckedFirst) {
  std::string long_line = kTetrahedronOff;
  long_line.insert(long_line.find("3 0 1 3"), "# " + std::string(100000, 'x') + "\n");
  const std::vector<Refused> cases = {
      {"long_line.off", long_line, "line 8: has 100002 characters"},
      {"huge.off", "OFF\n4000000000 4 6\n0 0 0\n", "line 2: declares 4000000000 vertices and 4 faces"},
      {"letters.off", "OFF\n4 four 6\n0 0 0\n", "line 2: expected the vertex, face and edge counts"},
      {"short.off", "OFF\n", "expected the vertex, face and edge counts"},
      // found by fuzzing: a face of 13 corners crashed assimp; an index past the vertices
      {"corners.off", "OFF\n4 1 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n13 0 2 1\n", "line 7: face 0 has 13 corners"},
      {"index.off", "OFF\n4 1 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 4\n",
       "face 0: corner 2 is vertex 4: expected a vertex index below 4"},
  };
  expect_each_refused(cases);
}

TEST_F(LoadMesh, ScaleMustBeAFinitePositiveNumber) {
  const std::string path = write("tet.stl", kTetrahedronStl);
  struct Case {
    double scale;
    const char* text;
  };
  for (const Case& c :
       {Case{0.0, "scale = 0"}, Case{-1.0, "scale = -1"}, Case{std::numeric_limits<double>::quiet_NaN(), "scale = nan"},
        Case{std::numeric_limits<double>::infinity(), "scale = inf"}}) {
    SCOPED_TRACE(c.text);
    LoadOptions options;
    options.scale = c.scale;
    expect_error(load_mesh(path, options), path, c.text);
    EXPECT_NE(load_mesh(path, options).message().find("> 0"), std::string::npos);
  }
  LoadOptions tiny;
  tiny.scale = 1e-3;
  EXPECT_TRUE(load_mesh(path, tiny).ok());
}

// ---- real-world meshes ------------------------------------------------------------------------

/// Triangles an OBJ file's `f` lines make once triangulated: n - 2 for a face of n corners.
int obj_triangle_count(const fs::path& path) {
  std::ifstream file(path);
  int triangles = 0;
  for (std::string line; std::getline(file, line);) {
    if (line.rfind("f ", 0) != 0) continue;
    std::istringstream words(line.substr(2));
    int corners = 0;
    for (std::string word; words >> word;) ++corners;
    triangles += corners - 2;
  }
  return triangles;
}

TEST(LoadSharedMeshes, EachLoadsAndValidates) {
  const fs::path dir = CUBESPRING_SHARED_MESHES_DIR;
  if (!fs::is_directory(dir)) GTEST_SKIP() << "no shared meshes at " << dir << " (../shared is absent)";
  int loaded = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".obj") continue;
    SCOPED_TRACE(entry.path().string());
    const Result<TriangleMesh> mesh = load_mesh(entry.path().string(), LoadOptions{0.01});
    ASSERT_TRUE(mesh.ok()) << mesh.message();
    EXPECT_GT(mesh->num_triangles(), 0);
    EXPECT_EQ(mesh->num_triangles(), obj_triangle_count(entry.path()));
    EXPECT_TRUE(validate(*mesh).ok()) << validate(*mesh).message();
    if (entry.path().filename() == "liver.obj") {
      // the file lists 181 vertices, but its faces use 139: assimp keeps only those
      EXPECT_EQ(mesh->num_vertices(), 139);
    }
    ++loaded;
  }
  EXPECT_GT(loaded, 0) << "no .obj file in " << dir;
}

}  // namespace
}  // namespace cubespring
