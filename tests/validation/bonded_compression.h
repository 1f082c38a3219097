// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The bonded-plates compression of issue 24 and its CalculiX reference: an 8 cm cube of 15.3 kPa,
// nu = 0.499 (a published silicone experiment), between two rigid plates bonded to its faces
// z = 0 and z = H, the top one moved down by 5, 12.5 and 18.25% of H; CalculiX NLGEOM with the
// compressible neo-Hookean law cubespring's cells follow (C3D20R, 8, 12 and 16 elements a side).
// The results are committed (tests/data/calculix/bonded_compression*.csv):
// test_bonded_compression_reference (label `reference`, not in CI) re-solves them;
// test_bonded_compression_fem (label `validation`) compares the lattice with them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace cubespring::validation {

inline constexpr double kPlatesSide = 0.08;     // [m]
inline constexpr double kPlatesYoung = 15.3e3;  // [Pa]
inline constexpr double kPlatesPoisson = 0.499;
inline constexpr std::array<double, 3> kPlatesStrains{-0.05, -0.125, -0.1825};  // nominal, along z
/// The grid the committed displacements are on: 1 cm, 9 points along each side.
inline constexpr int kPlatesGrid = 8;

/// One FE solution.
struct BondedCompressionRow {
  double strain = 0;         ///< nominal, along z (negative: compression)
  int elements = 0;          ///< C3D20R elements along each side
  double platen_force = 0;   ///< the top plate's force on the block along z [N]
  double volume_change = 0;  ///< deformed / rest - 1
  double bulge = 0;          ///< x displacement of the centre of the face x = L [m]
  /// Displacements [m] of the corner nodes on the kPlatesGrid grid, index i + 9 (j + 9 k); empty
  /// unless the mesh has them (elements a multiple of kPlatesGrid).
  std::vector<Eigen::Vector3d> grid_displacements;
};

/// Solves one case with ccx in work_dir; throws with ccx's message when it fails.
BondedCompressionRow solve_bonded_compression_with_calculix(double strain, int elements, const std::string& work_dir);

/// The committed rows (the summary file) with the displacements of the finest mesh (the nodes
/// file) attached; a line that does not read is a test failure.
std::vector<BondedCompressionRow> read_bonded_compression_rows(const std::string& summary_path,
                                                               const std::string& nodes_path);

/// Writes rows as the two files read_bonded_compression_rows() reads (the nodes of the rows
/// that have them).
void write_bonded_compression_rows(const std::vector<BondedCompressionRow>& rows, const std::string& summary_path,
                                   const std::string& nodes_path);

/// Checks the committed references' convergence, then runs `cubespring measure
/// bonded-compression`'s experiment on exact-bending cells with the neo-Hookean law, `cells` a
/// side (a multiple of kPlatesGrid), at each strain and expects issue 24's targets: the mean
/// interior displacement error within 5% of the platen travel, the volume within 1% of the FE's,
/// the platen force within 5% (a stable static solution: the solver reports no other converged).
/// Prints the figures. data_dir holds calculix/bonded_compression{,_nodes}.csv.
void expect_lattice_follows_calculix(int cells, const std::string& data_dir);

}  // namespace cubespring::validation
