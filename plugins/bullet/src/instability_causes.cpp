// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "instability_causes.h"

#include <sstream>

#include "cubespring/material.h"

namespace cubespring::bullet {
namespace {

// A rigid body that moves more than this fraction of a cell per sub-step outruns the contact,
// which moves the surface out of it once per sub-step.
constexpr double kFastToolCells = 0.1;

}  // namespace

std::string instability_causes(const Model& model, const SubStepPlan& plan, const std::vector<RigidTrack>& tracks) {
  std::ostringstream out;
  out << "; the plugin chose the sub-step of " << plan.sub_step << " s (at most " << plan.safety
      << " of the body's stable step at rest, " << plan.rest_sub_step << " s";
  if (plan.squeezed < 1.0) out << "; cells squeezed thin now need " << plan.squeezed << " of that";
  if (plan.added_mass > 0.0) {
    out << "; nodes took " << 100.0 * plan.added_mass
        << "% of the body's mass as inertia to lengthen it (max_added_mass: try without)";
  }
  out << ")";
  if (!model.has_mass_damping) {
    out << "; the tissue has no mass damping (Material::mass_damping = 0): soft tissue needs about "
        << kSoftTissueMassDamping
        << "/s (soft_tissue()), or the vibrations that contacts and tools feed it grow unchecked";
  }
  const double cell = model.cell_size.minCoeff();
  for (const RigidTrack& track : tracks) {
    const double speed = track.linear_velocity.norm();
    const double cells_per_sub_step = speed * plan.sub_step / cell;
    if (cells_per_sub_step > kFastToolCells) {
      out << "; a rigid body near it moves at " << speed << " m/s, " << cells_per_sub_step
          << " cells per sub-step: contact follows up to " << kFastToolCells << " (slow the tool down)";
    }
  }
  return out.str();
}

}  // namespace cubespring::bullet
