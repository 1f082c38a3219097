// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A simulator outside the tree, built against the installed package. Its body is the README's
// example (keep the two in step), followed by checks: exits 0 when the results are right.
#include <cmath>
#include <cstdio>

#include <cubespring/constraints.h>
#include <cubespring/experiments.h>
#include <cubespring/integrator.h>

int main() {
  // the README's example: a soft beam, clamped, sagging under gravity with implicit steps
  cubespring::Material liver;  // SI units: Pa, -, kg/m^3
  liver.young_modulus = 5e3;
  liver.poisson_ratio = 0.45;
  auto model = cubespring::build_model(cubespring::box_lattice({16, 4, 4}, {0.01, 0.01, 0.01}, liver));
  if (!model) {
    std::puts(model.message().c_str());
    return 1;
  }  // errors name the value at fault
  cubespring::Constraints clamp(*model);
  (void)clamp.fix_box(*model, {-1, -1, -1}, {1e-9, 1, 1});  // face x = 0
  cubespring::Loads loads;
  loads.gravity = {0, 0, -9.81};
  cubespring::State state = cubespring::rest_state(*model);
  cubespring::StepSettings settings;
  settings.integrator = cubespring::Integrator::kImplicitEuler;
  settings.time_step = 1e-3;
  cubespring::Stepper stepper(*model);
  for (int i = 0; i < 1000; ++i) {
    const auto report = stepper.step(*model, clamp, loads, settings, state);
    if (!report.ok()) {
      std::puts(report.message.c_str());
      break;
    }  // unstable or CG failure
  }

  // checks: the beam moved down and stayed finite; one cube's Young's modulus is right
  const double lowest = (state.positions - model->rest_positions).row(2).minCoeff();
  std::printf("after 1 s the soft beam's lowest node moved %g m\n", lowest);
  if (!(lowest < -1e-3) || !state.positions.allFinite()) return 1;
  const auto result = cubespring::run_experiment(cubespring::Experiment::kElongation, {});
  if (!result) {
    std::printf("error: %s\n", result.message().c_str());
    return 1;
  }
  std::printf("E error %g\n", *result->error.young_modulus);
  return std::abs(*result->error.young_modulus) < 1e-3 ? 0 : 1;
}
