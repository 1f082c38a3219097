// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Measures Young's modulus of one cube through the installed library; exits 0 when it is right.
#include <cmath>
#include <cstdio>

#include <cubespring/experiments.h>

int main() {
  cubespring::ExperimentSettings settings;
  const auto result = cubespring::run_experiment(cubespring::Experiment::kElongation, settings);
  if (!result) {
    std::printf("error: %s\n", result.message().c_str());
    return 1;
  }
  std::printf("E error %g\n", *result->error.young_modulus);
  return std::abs(*result->error.young_modulus) < 1e-3 ? 0 : 1;
}
