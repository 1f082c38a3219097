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

/// z = M^-1 r for a symmetric positive definite M near A: what conjugate gradients iterate with.
/// apply() runs on one thread between the solver's barriers, so its result is the same on any
/// thread count as long as it does not depend on one itself.
class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  virtual void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) = 0;
};

/// Solves A x = b, A symmetric positive definite with both triangles stored, by conjugate
/// gradients with `preconditioner`, or a Jacobi (diagonal) one when it is null, starting from x, until |b - A x| <=
/// tolerance |b| or max_iterations products with A. `threads` share the rows: each row's product
/// is summed in one thread, and every dot product is a sum over fixed blocks of rows taken in
/// block order, so 1, 2 or more threads give the same bits. A residual that turns NaN stops it
/// (not converged).
ConjugateGradientResult conjugate_gradient(const SparseMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                           double tolerance, int max_iterations, int threads,
                                           Preconditioner* preconditioner = nullptr);

}  // namespace cubespring
