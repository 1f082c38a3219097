// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The paper's correction (docs/model-baudet2007.md section 3) of one cell, written once: the mean
// strain of its edges along each axis and the tension the correction puts on them. The spring
// lists' cell pass and energy (forces.cpp) and the grid's cell pass (forces/grid/grid_forces.cpp)
// call these, so they agree to the bit.
#pragma once

namespace cubespring {

/// The mean strain of a cell's 4 edges along one axis: their summed lengths [m] times
/// `inverse_edge_sum`, 1 / (4 a0) [1/m] for the cell's side a0 along it, less 1.
[[gnu::always_inline]] inline double mean_edge_strain(double length_sum, double inverse_edge_sum) {
  return length_sum * inverse_edge_sum - 1.0;
}

/// The same strain with stiffness damping: plus beta [s] times the mean strain rate, their summed
/// length rates [m/s] times `inverse_edge_sum`.
[[gnu::always_inline]] inline double damped_edge_strain(double strain, double beta, double rate_sum,
                                                        double inverse_edge_sum) {
  return strain + beta * (rate_sum * inverse_edge_sum);
}

/// The correction tension [N] on each of a cell's 4 edges along axis a:
/// T_a = V0 (D eps)_a / (4 a0_a), given `tension_per_stress` = V0 / (4 a0_a) [m^2], the row a of
/// the cell's correction D [Pa] (d_x, d_y, d_z) and the mean edge strains (e_x, e_y, e_z).
[[gnu::always_inline]] inline double correction_tension(double tension_per_stress, double d_x, double d_y, double d_z,
                                                        double e_x, double e_y, double e_z) {
  return tension_per_stress * (d_x * e_x + d_y * e_y + d_z * e_z);
}

}  // namespace cubespring
