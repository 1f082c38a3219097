// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The self-weight block of issue 24 and its CalculiX reference: a 12 cm cube, nu = 0.45, density
// 1060 kg/m^3, g = 9.81 m/s^2, its base (z = 0) bonded or on a frictionless floor, at 5 and 10
// kPa, solved by CalculiX NLGEOM
// with the compressible neo-Hookean law cubespring's cells follow (C3D20R). The results are
// committed (tests/data/calculix/self_weight_cube.csv): test_self_weight_reference (label
// `reference`, minutes, not in CI) re-solves them; test_self_weight_fem (label `validation`)
// compares the lattice with them.
#pragma once

#include <string>
#include <vector>

namespace cubespring::validation {

struct BeamReference;

/// The FE's volume change (deformed / rest - 1): its corner nodes as the corners of trilinear
/// cells (body_volume), which leaves out the quadratic elements' curved edges; the meshes'
/// convergence shows what that costs.
double fe_volume_change(const BeamReference& reference);

inline constexpr double kCubeSide = 0.12;  // [m]
inline constexpr double kCubePoisson = 0.45;
inline constexpr double kCubeDensity = 1060;  // [kg/m^3]
inline constexpr double kCubeGravity = 9.81;  // [m/s^2]

/// One FE solution: the top face's centre displacement along z and the volume change.
struct SelfWeightRow {
  double young_modulus = 0;  ///< [Pa]
  bool floor = false;        ///< on a frictionless floor (else bonded)
  int elements = 0;          ///< C3D20R elements along each side
  double top_centre_uz = 0;  ///< [m]
  double volume_change = 0;  ///< deformed / rest - 1
};

/// The committed rows; a line that does not read is a test failure.
std::vector<SelfWeightRow> read_self_weight_rows(const std::string& path);

/// Solves one case with ccx in work_dir; throws with ccx's message when it fails.
SelfWeightRow solve_self_weight_with_calculix(double young_modulus, bool floor, int elements,
                                              const std::string& work_dir);

}  // namespace cubespring::validation
