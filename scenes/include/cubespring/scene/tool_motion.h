// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Where a scripted tool is at a moment: its key frames, interpolated.
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "cubespring/scene/scene.h"

namespace cubespring::scene {

/// The pose at time t [s]: position linear and orientation slerped between the key frames around
/// t; the first key frame's pose before it, the last one's after it; identity at the origin
/// without key frames.
Eigen::Isometry3d pose_at(const std::vector<Keyframe>& keyframes, double t);

}  // namespace cubespring::scene
