// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Why a soft body stepped by the plugin went unstable, in the terms of the scene that holds it:
// the plugin chose the sub-step itself, so "is the step above the stable step?" is not the
// question; the tissue's damping, the cells a contact crushed and the tools' speeds are.
#pragma once

#include <string>
#include <vector>

#include "cubespring/model.h"
#include "rigid_track.h"

namespace cubespring::bullet {

/// What the plugin knows of an unstable sub-step: its length [s] (the world step split evenly),
/// the longest it could have been at rest [s], the fraction of the body's stable step that is
/// (SoftBodySettings::time_step_safety), and the factor thin cells shortened it by
/// (SoftBody::planned_sub_step() over it), and the inertia added to lengthen it, as a fraction of the body's
/// mass (SoftBodySettings::max_added_mass; MassScaling::added_fraction).
struct SubStepPlan {
  double sub_step = 0.0;
  double rest_sub_step = 0.0;
  double safety = 0.0;
  double squeezed = 1.0;
  double added_mass = 0.0;
};

/// The causes to add to the core's message (which names the fastest node and a crushed cell), as
/// text starting with "; ": how the sub-step was chosen, a tissue without mass damping, and rigid
/// bodies near the body that move more than a tenth of a cell per sub-step.
std::string instability_causes(const Model& model, const SubStepPlan& plan, const std::vector<RigidTrack>& tracks);

}  // namespace cubespring::bullet
