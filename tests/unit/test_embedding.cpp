// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Embedding a visual mesh in its voxelized lattice: exact at rest, and any affine motion of the
// lattice moves the mesh by the same affine map (trilinear interpolation reproduces it).
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "cubespring/embedding.h"
#include "cubespring/shapes.h"
#include "cubespring/voxelize.h"

namespace cubespring {
namespace {

struct EmbeddedSphere {
  TriangleMesh mesh;
  Model model;
  Embedding embedding;
};

// A sphere of 5 cm at 12 cells across: many of its vertices lie in empty boundary cells.
EmbeddedSphere embedded_sphere() {
  EmbeddedSphere s;
  s.mesh = sphere_mesh(0.05, 3, Eigen::Vector3d(0.2, -0.1, 0.3));
  VoxelizeOptions options;
  options.cells_across = 12;
  Result<Voxelization> voxels = voxelize(s.mesh, options);
  EXPECT_TRUE(voxels.ok()) << voxels.message();
  Result<Model> model = build_model(lattice_from_voxels(*voxels, {Material{}}));
  EXPECT_TRUE(model.ok()) << model.message();
  s.model = std::move(model).value();
  Result<Embedding> embedding = embed_mesh(s.model, s.mesh);
  EXPECT_TRUE(embedding.ok()) << embedding.message();
  s.embedding = std::move(embedding).value();
  return s;
}

TEST(Embedding, RestLatticeReproducesTheMesh) {
  const EmbeddedSphere s = embedded_sphere();
  Eigen::Matrix3Xd vertices;
  embedded_positions(s.model, s.embedding, s.model.rest_positions, vertices);
  EXPECT_LE((vertices - s.mesh.vertices).cwiseAbs().maxCoeff(), 1e-12 * 0.3);
  // some vertices are in empty cells and extrapolate from their nearest cell
  int outside = 0;
  for (int v = 0; v < s.embedding.num_vertices(); ++v) {
    const Eigen::Vector3d u = s.embedding.vertex_local.col(v);
    if ((u.array() < 0.0).any() || (u.array() > 1.0).any()) ++outside;
    EXPECT_LT(u.cwiseAbs().maxCoeff(), 2.0) << "vertex " << v << " bound far from its cell";
  }
  EXPECT_GT(outside, 0);
}

TEST(Embedding, AffineMotionsOfTheLatticeMoveTheMeshByTheSameMap) {
  const EmbeddedSphere s = embedded_sphere();
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear(0, 1) = 0.4;
  shear(2, 0) = -0.25;
  const Eigen::Matrix3d stretch = Eigen::Vector3d(1.5, 0.8, 1.1).asDiagonal();
  const struct {
    const char* name;
    Eigen::Matrix3d map;
    Eigen::Vector3d shift;
  } motions[] = {{"translation", Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.3, -1.2, 0.05)},
                 {"rotation", rotation, Eigen::Vector3d::Zero()},
                 {"stretch", stretch, Eigen::Vector3d::Zero()},
                 {"shear", shear, Eigen::Vector3d(0.01, 0.02, 0.03)},
                 {"all", rotation * shear * stretch, Eigen::Vector3d(-0.4, 0.1, 0.2)}};
  for (const auto& motion : motions) {
    const Eigen::Matrix3Xd nodes = (motion.map * s.model.rest_positions).colwise() + motion.shift;
    const Eigen::Matrix3Xd expected = (motion.map * s.mesh.vertices).colwise() + motion.shift;
    Eigen::Matrix3Xd vertices;
    embedded_positions(s.model, s.embedding, nodes, vertices);
    const double scale = expected.cwiseAbs().maxCoeff();
    EXPECT_LE((vertices - expected).cwiseAbs().maxCoeff(), 1e-12 * scale) << motion.name;
  }
}

TEST(Embedding, NodeValuesInterpolateLikePositions) {
  // trilinear weights reproduce a linear field exactly, in every cell and extrapolated outside
  const EmbeddedSphere s = embedded_sphere();
  const Eigen::Vector3d slope(2.0, -3.0, 0.5);
  const Eigen::VectorXd node_values = (s.model.rest_positions.transpose() * slope).array() + 1.5;
  Eigen::VectorXd vertex_values;
  embedded_values(s.model, s.embedding, node_values, vertex_values);
  const Eigen::VectorXd expected = (s.mesh.vertices.transpose() * slope).array() + 1.5;
  ASSERT_EQ(vertex_values.size(), expected.size());
  EXPECT_LE((vertex_values - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Embedding, NormalsPointOutAndTurnWithTheBody) {
  const EmbeddedSphere s = embedded_sphere();
  const Eigen::Vector3d centre(0.2, -0.1, 0.3);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3Xd nodes = rotation * s.model.rest_positions;
  Eigen::Matrix3Xd vertices;
  Eigen::Matrix3Xd normals;
  embedded_positions(s.model, s.embedding, nodes, vertices);
  vertex_normals(vertices, s.embedding.triangles, normals);
  for (int v = 0; v < s.embedding.num_vertices(); ++v) {
    const Eigen::Vector3d radial = (vertices.col(v) - rotation * centre).normalized();
    EXPECT_NEAR(normals.col(v).norm(), 1.0, 1e-12);
    EXPECT_GT(normals.col(v).dot(radial), 0.99) << "vertex " << v;
  }
}

TEST(Embedding, RefusesAnInvalidMeshOrAnEmptyModel) {
  const EmbeddedSphere s = embedded_sphere();
  TriangleMesh broken = s.mesh;
  broken.vertices(0, 3) = std::nan("");
  const Result<Embedding> nan = embed_mesh(s.model, broken);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.message().find("vertex 3"), std::string::npos) << nan.message();
  EXPECT_FALSE(embed_mesh(Model{}, s.mesh).ok());
}

// The same sphere given in millimetres while the lattice is in metres: its vertices lie about
// 10^4 cells out. They are refused at once, with the vertex and how far out it is (binding them
// would have searched about 10^16 cells, and they would move by extrapolation, not with the body).
// A vertex just outside still binds to its nearest cell.
TEST(Embedding, RefusesAVertexFarOutsideTheLattice) {
  const EmbeddedSphere s = embedded_sphere();
  TriangleMesh millimetres = s.mesh;
  millimetres.vertices *= 1000.0;
  const Result<Embedding> far = embed_mesh(s.model, millimetres);
  ASSERT_FALSE(far.ok());
  EXPECT_NE(far.message().find("cells outside the lattice, which is 12 cells long"), std::string::npos)
      << far.message();
  TriangleMesh near = s.mesh;
  near.vertices.col(0) += Eigen::Vector3d(0.0, 0.0, 0.05);  // a few cells above the sphere
  const Result<Embedding> bound = embed_mesh(s.model, near);
  ASSERT_TRUE(bound.ok()) << bound.message();
  EXPECT_GE(bound->vertex_cell[0], 0);
}

}  // namespace
}  // namespace cubespring
