// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The sphere indentation of the contact issue and its CalculiX reference: a rigid frictionless
// sphere of radius 10 mm pressed 2, 5 and 10 mm (from first touch) into the centre of the top face
// of a 10 x 10 x 5 cm block of 5 kPa, nu = 0.45, its base bonded; CalculiX NLGEOM with the
// compressible neo-Hookean law cubespring's cells follow, on a quarter of the block (the model's
// choices are in indentation.cpp). The results are committed (tests/data/calculix/indentation.csv);
// test_indentation_reference (label `reference`, not in CI) re-solves them and
// tests/bullet/test_bullet_indentation_fem.cpp (label validation) compares the lattice with them;
// the assertions are those tests' (the reader here reports an unreadable line with ADD_FAILURE).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace cubespring::validation {

inline constexpr double kIndentationRadius = 0.010;    // the sphere's [m]
inline constexpr double kIndentationSide = 0.10;       // the block's, along x and y [m]
inline constexpr double kIndentationThickness = 0.05;  // the block's, along z [m]
inline constexpr double kIndentationYoung = 5e3;       // [Pa]
inline constexpr double kIndentationPoisson = 0.45;
/// From the first touch at the undeformed top face [m].
inline constexpr std::array<double, 3> kIndentationDepths{0.002, 0.005, 0.010};

/// One FE solution at one depth.
struct IndentationRow {
  double depth = 0;           ///< the sphere's travel from first touch [m]
  int mesh_level = 0;         ///< 1, 2, 3...: the block's elements near the contact are 10 mm / (level + 2)
  int elements = 0;           ///< the block's elements in the quarter model
  double force = 0;           ///< the block's push on the sphere along +z, whole block [N]
  double base_force = 0;      ///< minus the base's reaction along z, whole block [N] (the same at equilibrium)
  double contact_radius = 0;  ///< the last top-face node on y = 0 touching the sphere, at rest [m] (to a node)
  double penetration = 0;     ///< the sphere's largest overlap with the top face's nodes on y = 0 [m]
};

/// The ccx deck of the quarter model at a mesh level (>= 1); the sphere's travel is ramped over the
/// step's period 1, to the deepest depth, and results are printed at each depth's time.
std::string indentation_deck(int mesh_level);

/// Solves the three depths at a mesh level with ccx in work_dir (indentation.inp, .dat, ccx.log);
/// throws with ccx's message when it fails.
std::vector<IndentationRow> solve_indentation_with_calculix(int mesh_level, const std::string& work_dir);

/// The committed rows; a line that does not read is a test failure.
std::vector<IndentationRow> read_indentation_rows(const std::string& path);

/// Writes rows as the file read_indentation_rows() reads, with the header comment.
void write_indentation_rows(const std::vector<IndentationRow>& rows, const std::string& path);

}  // namespace cubespring::validation
