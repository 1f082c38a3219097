// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The bench's floor with implicit lattice connectivity: one pass of linear spring forces over a
// box of cells whose springs are found by index arithmetic, as the core-engine issue describes it
// ("a bare spring-force pass with implicit lattice connectivity, in double on one thread").
#pragma once

#include <vector>

#include <Eigen/Core>

namespace cubespring::app {

class GridSpringFloor {
 public:
  /// A box of `cells` cubes of edge h [m] at `positions` (3 x nodes, x fastest, then y, then z;
  /// a model may number them otherwise: Model::major_axis), edges of stiffness edge_k and body
  /// diagonals of diagonal_k [N/m].
  GridSpringFloor(const Eigen::Vector3i& cells, double h, const Eigen::Matrix3Xd& positions, double edge_k,
                  double diagonal_k);

  /// One pass: f = k (l - l0) d / l on both ends of every spring; one thread.
  void operator()();
  /// Springs one pass visits (the box's 3 edge directions and 4 diagonals).
  long springs() const { return springs_; }
  /// Sum of the squared forces of the last pass, so that the work is used [N^2].
  double checksum() const;

 private:
  void family(const Eigen::Vector3i& start, const Eigen::Vector3i& end, double rest, double k);

  Eigen::Vector3i cells_, nodes_;
  double h_;
  double edge_k_, diagonal_k_;
  std::vector<double> x_, y_, z_, fx_, fy_, fz_;
  std::vector<double> row_x_, row_y_, row_z_;  // one row's spring forces
  long springs_ = 0;
};

}  // namespace cubespring::app
