// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "self_weight_cube.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "calculix_beam.h"
#include "cubespring/lattice.h"
#include "cubespring/strain.h"

namespace cubespring::validation {

double fe_volume_change(const BeamReference& reference) {
  const Eigen::Vector3i n = reference.elements;
  const Eigen::Vector3d h = reference.size.cwiseQuotient(n.cast<double>());
  Result<Model> grid = build_model(box_lattice(n, h, Material{}));
  if (!grid) throw std::runtime_error(grid.message());
  const Model& model = grid.value();
  Eigen::Matrix3Xd deformed = model.rest_positions;
  for (int node = 0; node < model.num_nodes(); ++node) {
    const Eigen::Vector3d rest = model.rest_positions.col(node) - model.origin;
    deformed.col(node) += reference.displacement_at(rest).value();
  }
  return body_volume(model, deformed) / body_volume(model, model.rest_positions) - 1.0;
}

std::vector<SelfWeightRow> read_self_weight_rows(const std::string& path) {
  std::ifstream in(path);
  std::vector<SelfWeightRow> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("young", 0) == 0) continue;
    // young_modulus_Pa,support,elements_per_side,top_centre_uz_m,volume_change
    std::istringstream fields(line);
    SelfWeightRow row;
    std::string support;
    char comma = 0;
    fields >> row.young_modulus >> comma;
    std::getline(fields, support, ',');
    row.floor = support == "floor";
    fields >> row.elements >> comma >> row.top_centre_uz >> comma >> row.volume_change;
    if (!fields || (support != "floor" && support != "bonded")) {
      ADD_FAILURE() << path << ": cannot read the line '" << line << "'";
      continue;
    }
    rows.push_back(row);
  }
  return rows;
}

SelfWeightRow solve_self_weight_with_calculix(double young_modulus, bool floor, int elements,
                                              const std::string& work_dir) {
  BeamReferenceSpec spec;
  spec.size = Eigen::Vector3d::Constant(kCubeSide);
  spec.elements = Eigen::Vector3i::Constant(elements);
  spec.young_modulus = young_modulus;
  spec.poisson_ratio = kCubePoisson;
  spec.density = kCubeDensity;
  spec.gravity = kCubeGravity;
  spec.nonlinear = true;
  spec.neo_hookean = true;
  spec.clamped_axis = 2;
  spec.sliding = floor;
  spec.work_dir = work_dir;
  const BeamResult result = compute_beam_reference(spec);
  if (!result.reference) throw std::runtime_error(result.error);
  SelfWeightRow row;
  row.young_modulus = young_modulus;
  row.floor = floor;
  row.elements = elements;
  row.top_centre_uz = result.reference->displacement_at({kCubeSide / 2, kCubeSide / 2, kCubeSide}).value().z();
  row.volume_change = fe_volume_change(*result.reference);
  return row;
}

}  // namespace cubespring::validation
