// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The implicit step's linear solver: conjugate gradients whose threads share the rows and whose
// result does not depend on how many there are.
#pragma once

#include <Eigen/Core>

#include "cubespring/stiffness.h"

namespace cubespring {

struct ConjugateGradientResult {
  int iterations = 0;              ///< products with the matrix
  double relative_residual = 0.0;  ///< |r| / |b| at the end, r the residual as CG updates it
                                   ///< (b - A x to rounding); 0 for b = 0
  bool converged = false;          ///< relative_residual <= the tolerance
};

/// Solves A x = b, A symmetric positive definite with both triangles stored, by conjugate
/// gradients with a Jacobi (diagonal) preconditioner, starting from x, until |b - A x| <=
/// tolerance |b| or max_iterations products with A. `threads` share the rows: each row's product
/// is summed in one thread, and every dot product is a sum over fixed blocks of rows taken in
/// block order, so 1, 2 or more threads give the same bits. A residual that turns NaN stops it
/// (not converged).
ConjugateGradientResult conjugate_gradient(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                           double tolerance, int max_iterations, int threads);

}  // namespace cubespring
