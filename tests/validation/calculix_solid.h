// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
//
// Finite-element reference for a solid made of grid cells (any shape: boxes,
// L-shapes, ...), clamped on one plane and loaded by gravity and/or a surface
// traction, computed by CalculiX (`ccx`, C3D20R, linear elastic, linear
// static). Validation tests compare cubespring's soft bodies against it; the
// engine itself never depends on this file. Link with calculix_beam.cpp
// (calculix_available() lives there).

#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace cubespring::validation {

/// A solid made of axis-aligned grid cells of size h (metres), each cell split
/// into n x n x n C3D20R elements.
struct SolidReferenceSpec {
  /// Occupied cells (grid indices, each in [-1e6, 1e6], no duplicates); cell
  /// i spans [i h, (i+1) h] per axis. Cells touching by a face, an edge or a
  /// corner share their nodes there. Every cell must be joined through shared
  /// faces to a cell cut by (or touching) the clamp plane, else an error: the
  /// system would be singular and SPOOLES would not say so.
  std::vector<Eigen::Vector3i> cells;
  /// h (unit: metre, > 0).
  double cell_size = 0.01;
  /// n (in [1, 64]).
  int elements_per_cell = 2;
  /// Linear elastic, linear static step (Pa, -).
  double young_modulus = 1e6, poisson_ratio = 0.3;
  /// Mass density (unit: kg/m^3, > 0).
  double density = 1000;
  /// Body force per unit mass (unit: m/s^2; may be zero, then no *DLOAD).
  Eigen::Vector3d gravity{0, 0, 0};
  /// Clamped: every FE node (corner and mid-edge) whose coordinate along
  /// clamp_axis (0, 1, 2) equals clamp_value (metre, within 1e-9 h) is fixed
  /// in x, y, z. At least one node must match.
  int clamp_axis = 0;
  double clamp_value = 0.0;
  /// Surface traction on the boundary faces normal to +load_axis at
  /// coordinate load_value (the faces of cells whose upper side along
  /// load_axis lies there and that have no neighbour cell beyond):
  /// traction(p) [Pa] = traction_constant + traction_gradient * p (p: position
  /// in metres). Applied as consistent nodal forces of the 8-node element
  /// faces (*CLOAD). With has_traction at least one face must match.
  bool has_traction = false;
  int load_axis = 0;
  double load_value = 0.0;
  Eigen::Vector3d traction_constant = Eigen::Vector3d::Zero();
  Eigen::Matrix3d traction_gradient = Eigen::Matrix3d::Zero();
  /// Folder for the deck (solid.inp), ccx's output and its log (ccx.log);
  /// created if missing. Files of a previous run there are overwritten.
  std::string work_dir;
};

/// Displacements of the FE corner nodes (the nodes at multiples of h/n).
struct SolidReference {
  /// h and n of the spec the reference was computed for.
  double cell_size = 0;
  int elements_per_cell = 0;
  /// Displacement (unit: metre) of the corner node at rest position
  /// index * h / n, keyed by that integer index (one entry per corner node).
  std::map<std::array<int, 3>, Eigen::Vector3d> corner_displacement;

  /// Displacement (unit: metre) at a rest point (unit: metre) that coincides
  /// with an FE corner node (within 1e-9 h); std::nullopt for any other point.
  std::optional<Eigen::Vector3d> displacement_at(const Eigen::Vector3d& point) const;
};

/// Either a reference, or an error message saying what went wrong.
struct SolidResult {
  std::optional<SolidReference> reference;
  /// Empty on success.
  std::string error;
};

/// Writes <work_dir>/solid.inp, runs `ccx -i solid` in work_dir (SPOOLES, two
/// threads; stdout and stderr to <work_dir>/ccx.log) and parses the corner
/// displacements from <work_dir>/solid.dat. Never throws: bad parameters, a
/// missing ccx, a failed run (message ends with the log's last lines) or
/// unreadable output all come back as an error.
SolidResult compute_solid_reference(const SolidReferenceSpec& spec);

}  // namespace cubespring::validation
