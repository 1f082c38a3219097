// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A scene file as data (cubespring::scene, the library `cubespring run` plays scenes with): an
// organ, a table, rigid tools on scripted paths, the time line and the camera. Every field has
// the default that docs/scene-format.md gives for its key. Units are SI throughout: metres,
// kilograms, seconds, pascals.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cubespring/integrator.h"
#include "cubespring/lattice.h"
#include "cubespring/material.h"
#include "cubespring/render/camera.h"
#include "cubespring/render/lights.h"
#include "cubespring/result.h"

namespace cubespring::scene {

/// Soft tissue as the scene gives it: a Material with the defaults of a soft organ, not the
/// library's (1 MPa would be rubber).
Material default_tissue();

/// An axis-aligned box [lower, upper] [m].
struct Box {
  Eigen::Vector3d lower{0, 0, 0};
  Eigen::Vector3d upper{0, 0, 0};
  int line = 0;  ///< where the scene file gives it (0: not from a file)
};

struct OrganSpec {
  std::string mesh;          ///< surface mesh file (resolved path)
  double scale = 1.0;        ///< metres per file unit
  double cell_size = 0.008;  ///< cubic cell edge [m]; used when cells_across is 0
  int cells_across = 0;      ///< when > 0: this many cells along the mesh's longest side
  CellModel model = CellModel::kExactBending;
  CellLaw law = CellLaw::kNeoHookean;  ///< the cells' large-strain law (cell_law.h)
  /// Tissue by the mesh's material name (or part name); parts not listed get default_tissue().
  std::map<std::string, Material> materials;
  std::map<std::string, int> material_lines;  ///< line of each materials entry in the scene file
  std::vector<Box> fixed_regions;             ///< nodes resting in these boxes are fixed (held in place)
  double friction = 0.3;                      ///< Coulomb mu between the tissue and every rigid body [-]
  bool face_contacts = true;                  ///< tools thinner than the surface's vertex spacing cannot slip through
  double contact_offset = 0.0;                ///< skin kept between the tissue and rigid surfaces [m]
  /// The most inertia, as a fraction of the organ's mass, that the explicit sub-step may give the
  /// nodes limiting it (a stiff tumour's) to be longer (bullet::SoftBodySettings::max_added_mass).
  double max_added_mass = 0.0;
  /// The explicit sub-step as a fraction of the stable step, in (0, 1]
  /// (bullet::SoftBodySettings::time_step_safety): lower it to see whether a scene's forces have
  /// converged in the sub-step.
  double time_step_safety = 0.9;
};

struct TableSpec {
  bool enabled = true;
  double height = 0.0;      ///< z of the table top [m]
  double half_size = 0.25;  ///< the top spans +-half_size in x and y around the origin [m]
};

/// A rigid tool's pose at a moment; poses in between are interpolated (position linearly,
/// orientation by slerp); before the first key frame and after the last the tool stands still.
struct Keyframe {
  double time = 0.0;                  ///< [s]
  Eigen::Vector3d position{0, 0, 0};  ///< of the tool's local origin [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

struct CapsuleSpec {
  double radius = 0.0025;  ///< [m]
  double length = 0.2;     ///< from the lowest point of the tip (the local origin) along +z [m]
};

/// A rigid tool: a mesh is drawn, and without a capsule its convex hull is the contact shape; a
/// capsule is the contact shape, and is drawn when there is no mesh.
/// How a tool cuts (`tools[i].cut`).
struct CutSpec {
  /// The organ's cells whose centre comes within the tool's radius plus three quarters of a cell
  /// of its capsule's axis are removed (the cautery's burn), while the force on the tool is at
  /// least this [N] (0: whenever they are within reach).
  double force_threshold = 0.0;
};

struct ToolSpec {
  std::string name;
  std::string mesh;    ///< surface mesh (resolved path), or empty
  double scale = 1.0;  ///< multiplies the mesh's and the capsule's sizes
  std::optional<CapsuleSpec> capsule;
  /// [kg]: a tool the user drives through a haptic coupling (`cubespring haptic-replay`) moves as a
  /// body of this mass, its inertia that of its contact shape; a scripted tool ignores it.
  double mass = 0.02;
  std::vector<Keyframe> keyframes;  ///< sorted by time
  /// A cautery tool (`cut: {"mode": "remove", "force_threshold": N}`): after each step it burns
  /// away the organ's cells within its reach (docs/scene-format.md); its capsule is its tip.
  std::optional<CutSpec> cut;
};

enum class ColourMode { kDisplacement, kStrain, kNone };

struct RenderSpec {
  int width = 1280;
  int height = 720;
  int supersampling = 2;
  Camera camera;
  std::vector<Light> lights = default_lights();  ///< directional lights, at most 8
  double ambient = 0.25;                         ///< fraction of a surface's colour seen without any light, in [0, 1]
  bool wireframe = false;
  ColourMode colour_map = ColourMode::kDisplacement;
  double colour_range = 0.01;  ///< displacement shown at the top of the colour scale [m]
  double strain_range = 0.2;   ///< equivalent strain shown at the top of the colour scale (colour_map "strain")
};

struct Scene {
  std::string source;  ///< the scene file, as given
  OrganSpec organ;
  TableSpec table;
  std::vector<ToolSpec> tools;
  Eigen::Vector3d gravity{0, 0, -9.81};  ///< [m/s^2]
  Integrator integrator = Integrator::kSymplecticEuler;
  double time_step = 0.004;  ///< Bullet step [s]; soft bodies sub-step inside it
  double settle_time = 1.0;  ///< simulated before t = 0 so the organ rests on the table [s]
  double duration = 0.0;     ///< simulated time [s]; the last key frame's when not given
  double frame_rate = 24.0;  ///< frames per simulated second, when `frames` is not given
  int frames = 0;            ///< frames evenly over the duration (first at 0, last at the end)
  RenderSpec render;
  std::string output = "cubespring-demo-output";  ///< relative to the current directory

  /// When each frame is taken [s]: `frames` of them evenly from 0 to the duration when given,
  /// else every 1 / frame_rate from 0 up to the duration.
  std::vector<double> frame_times() const;
};

/// Where paths in a scene are found.
struct SceneContext {
  std::string source;    ///< name for messages (the file as the user gave it)
  std::string base_dir;  ///< relative mesh paths are relative to this (the scene file's folder)
  std::string data_dir;  ///< cubespring's data folder: the default meshes (may be empty)
};

/// Parses a scene. Errors are "SOURCE:LINE: message" and name the key: unknown keys (with the
/// keys allowed there), wrong types, values out of range, mesh files that do not exist.
Result<Scene> parse_scene(const std::string& text, const SceneContext& context);

/// Reads and parses a scene file; relative mesh paths are relative to its folder.
Result<Scene> load_scene(const std::string& path, const std::string& data_dir);
/// The largest scene file load_scene() reads [bytes].
inline constexpr std::uintmax_t kMaxSceneBytes = 16000000;

}  // namespace cubespring::scene
