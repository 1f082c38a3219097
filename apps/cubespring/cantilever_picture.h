// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// The picture of `cubespring measure cantilever --png`: the paper's figures 5 and 6.
#pragma once

#include <Eigen/Geometry>

#include "cubespring/render/camera.h"
#include "cubespring/render/image.h"
#include "cubespring/validation/calculix_result.h"
#include "cubespring/validation/experiments.h"

namespace cubespring::app {

struct CantileverPicture {
  Image image;
  Camera camera;  ///< the camera it was drawn with
};

/// A camera from the front (-y), above and to the right, that just frames `box` [m] in a
/// width x height image, leaving the right edge free for the legend.
Camera cantilever_camera(const Eigen::AlignedBox3d& box, int width, int height);

struct CantileverPictureOptions {
  int width = 1280;    ///< [pixels]
  int height = 720;    ///< [pixels]
  double magnify = 1;  ///< displacements are drawn this many times their size (colours stay true), > 0
};

/// The deformed lattice's outer edges as a wire model over a surface coloured by displacement
/// magnitude: the lattice's own surface, or with a reference the finite-element solution's
/// deformed surface coloured by its displacement, the wire drawn through it (paper, figures 5
/// and 6). One colour scale for both, from 0 to the largest displacement of either.
Result<CantileverPicture> draw_cantilever(const ExperimentResult& cantilever, const FemSolution* reference,
                                          const CantileverPictureOptions& options);

}  // namespace cubespring::app
