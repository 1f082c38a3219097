// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
//
// Finite-element reference for a cantilever beam under gravity, computed by
// CalculiX (`ccx`). Validation tests compare cubespring's soft bodies against
// it; the engine itself never depends on this file.

#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calculix_common.h"  // calculix_available()

namespace cubespring::validation {

/// What to solve: a box clamped at x = 0 (or at z = 0: clamped_axis), loaded by its own weight
/// along -z.
struct BeamReferenceSpec {
  /// Beam spans [0,Lx] x [0,Ly] x [0,Lz] (unit: metre, each > 0).
  Eigen::Vector3d size{0.16, 0.04, 0.04};
  /// Number of C3D20R elements along x, y, z (each >= 1).
  Eigen::Vector3i elements{32, 8, 8};
  /// Young's modulus (unit: Pa, > 0).
  double young_modulus = 1e6;
  /// Poisson's ratio (-, in (-1, 0.5)).
  double poisson_ratio = 0.3;
  /// Mass density (unit: kg/m^3, > 0).
  double density = 1000;
  /// Gravitational acceleration, acting along -z (unit: m/s^2, finite).
  double gravity = 9.81;
  /// The clamped face is where this coordinate is 0 (0: x = 0, the cantilever; 2: z = 0, a block
  /// bonded at its base). Every node there, corner and mid-edge, is fixed in x, y and z.
  int clamped_axis = 0;
  /// The clamped face holds its nodes along clamped_axis only (a frictionless support); the node
  /// at the face's centre is also held along the other two axes, and the node at the end of its
  /// row along the first other axis on the second, against sliding and turning (they carry no
  /// force). Needs a node at the face's centre (even element counts across it).
  bool sliding = false;
  /// When > 0 [m]: the face opposite the clamped one (coordinate = size along clamped_axis) is
  /// bonded to a rigid platen that moves this far towards the clamped face (every node there held
  /// in the face's plane and moved along clamped_axis); BeamReference::platen_force has its force.
  double platen_travel = 0.0;
  /// false: linear elastic, linear static step.
  /// true: NLGEOM with a compressible neo-Hookean material (C10 = G/2,
  /// D1 = 2/K), load ramped with automatic increments.
  bool nonlinear = false;
  /// With nonlinear: true for the neo-Hookean law above, false for St Venant-Kirchhoff (linear
  /// elastic constants on the Green-Lagrange strain, which is what *ELASTIC means under NLGEOM).
  bool neo_hookean = true;
  /// Folder for the deck (beam.inp), ccx's output and its log (ccx.log);
  /// created if missing. Files of a previous run there are overwritten.
  std::string work_dir;
};

/// Displacements of the corner nodes of the element grid.
struct BeamReference {
  /// Grid the reference was computed on: elements along x, y, z.
  Eigen::Vector3i elements = Eigen::Vector3i::Zero();
  /// Beam size (unit: metre).
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  /// Displacement (unit: metre) of the corner node at rest position
  /// (i*Lx/nx, j*Ly/ny, k*Lz/nz), indexed i + (nx+1)*(j + (ny+1)*k);
  /// ((nx+1)*(ny+1)*(nz+1) entries).
  std::vector<Eigen::Vector3d> corner_displacement;
  /// With platen_travel: the force the platen exerts on the block (its nodes' reactions) [N].
  std::optional<Eigen::Vector3d> platen_force;

  /// Displacement (unit: metre) at a rest point (unit: metre) that coincides
  /// with a corner node (within 1e-9 of the largest beam side); std::nullopt
  /// for any other point.
  std::optional<Eigen::Vector3d> displacement_at(const Eigen::Vector3d& rest_point) const;

  /// Mean z displacement (unit: metre) of the corner nodes of face x = Lx;
  /// negative when the beam sags.
  double tip_deflection() const;
};

/// Either a reference, or an error message saying what went wrong.
struct BeamResult {
  std::optional<BeamReference> reference;
  /// Empty on success.
  std::string error;
};

/// Writes <work_dir>/beam.inp, runs `ccx -i beam` in work_dir (stdout and
/// stderr to <work_dir>/ccx.log) and parses the corner displacements from
/// <work_dir>/beam.dat. Never throws: bad parameters, a missing ccx, a failed
/// run (message ends with the log's last lines) or unreadable output all come
/// back as an error.
BeamResult compute_beam_reference(const BeamReferenceSpec& spec);

}  // namespace cubespring::validation
