// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The optional parts from an installed tree: a soft block settles on a Bullet floor and carries
// its weight there; a device's coupling pulls a tool; a mesh written here is loaded and voxelized.
#include <cmath>
#include <cstdio>
#include <fstream>

#include <cubespring/bullet/world.h>
#include <cubespring/haptics/virtual_coupling.h>
#include <cubespring/mesh/load_mesh.h>
#include <cubespring/voxelize.h>

int main() {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  cubespring::bullet::World world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, 0, -9.81f));
  btStaticPlaneShape plane(btVector3(0, 0, 1), 0);
  btRigidBody floor(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &plane));
  world.addRigidBody(&floor);

  cubespring::Material tissue;
  tissue.young_modulus = 1e5;
  tissue.mass_damping = 20;
  cubespring::bullet::SoftBodySettings settings;
  settings.lattice = cubespring::box_lattice({3, 3, 2}, {0.01, 0.01, 0.01}, tissue);
  auto block = cubespring::bullet::SoftBody::create(settings);
  if (!block) {
    std::puts(block.message().c_str());
    return 1;
  }
  world.addSoftBody(block->get());
  for (int i = 0; i < 60; ++i) world.stepSimulation(1.0f / 60.0f, 1, 1.0f / 60.0f);
  const double weight = (*block)->model().total_mass() * 9.81;
  const double carried = -world.getContactWrench(&floor).force.z();
  world.removeRigidBody(&floor);
  if (std::abs(carried - weight) > 0.01 * weight) {
    std::printf("floor carries %g N of a %g N block\n", carried, weight);
    return 1;
  }

  auto coupling = cubespring::haptics::VirtualCoupling::create({}, {0.02, {1e-5, 1e-5, 1e-6}, {}});
  cubespring::haptics::DeviceState device;
  device.pose.translation() = Eigen::Vector3d(0, 0, 0.001);
  if (!coupling || std::abs(coupling->on_tool(device, {}).force.z() - 1.0) > 1e-9) {
    std::puts("a 1000 N/m coupling stretched 1 mm does not pull the tool with 1 N");
    return 1;
  }

  std::ofstream("tetra.obj") << "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  auto mesh = cubespring::load_mesh("tetra.obj");
  if (!mesh) {
    std::puts(mesh.message().c_str());
    return 1;
  }
  cubespring::VoxelizeOptions options;
  options.cells_across = 20;
  auto voxels = cubespring::voxelize(*mesh, options);
  if (!voxels || std::abs(voxels->relative_volume_difference()) > 0.1) {
    std::puts(voxels ? "voxel volume off by more than 10%" : voxels.message().c_str());
    return 1;
  }
  std::printf("floor carries the block's weight (%g N); tetrahedron of %zu cells\n", carried, voxels->cells.size());
  return 0;
}
