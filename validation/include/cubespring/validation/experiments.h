// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "cubespring/lattice.h"
#include "cubespring/model.h"
#include "cubespring/result.h"
#include "cubespring/state.h"
#include "cubespring/static_solver.h"

/// Units are SI throughout the API: metres, kilograms, seconds, newtons, pascals.
namespace cubespring {

/// The paper's virtual experiments on a block [0, nx hx] x [0, ny hy] x [0, nz hz].
enum class Experiment {
  kElongation,  ///< uniaxial traction on the x faces, lateral faces free: E and nu
  kShear,       ///< shear: G in the xz plane (and, displacement controlled, in all three planes)
  kInflation,   ///< pressure on every face: B
  kCantilever,  ///< face x = 0 clamped, gravity along -z: tip deflection
  /// A block under its own weight at finite strain, its base (z = 0) bonded or on a frictionless
  /// floor (Support), gravity along -z: the top face's centre displacement and the volume change.
  kSelfWeight,
  /// Finite strain, as stress-strain curves against the neo-Hookean law's closed form (below):
  /// uniaxial tension or compression between frictionless platens on the x faces, lateral faces
  /// free (strain: the nominal strain, stretch - 1);
  kUniaxial,
  /// simple shear u_x = gamma z imposed on every boundary node (strain: gamma);
  kSimpleShear,
  /// a uniform dilatation imposed on every boundary node (strain: the volume change, J - 1);
  kHydrostatic,
  /// compression (or tension) between two rigid plates bonded to the faces z = 0 and z = H, the
  /// top one moved along z by strain H (strain: the nominal strain; the curve's stress is the
  /// plate's force over the rest area, P_zz, with no closed form: `expected` is NaN); also the
  /// volume change, the cells' least volume ratio and the bulge.
  kBondedCompression,
};
const char* experiment_name(Experiment experiment);
Result<Experiment> parse_experiment(const std::string& name);

enum class ShearControl {
  kDisplacement,  ///< affine shear u_x = gamma z imposed on every boundary node
  kForce,         ///< the paper's way: opposite tangential tractions, body free
};
const char* shear_control_name(ShearControl control);

/// How the self-weight block stands.
enum class Support {
  kBonded,  ///< its base bonded: every base node held
  kFloor,   ///< on a frictionless floor: the base nodes held along z only (two of them also in the
            ///< plane, against sliding and turning: those take no force)
};
const char* support_name(Support support);
Result<Support> parse_support(const std::string& name);

struct ExperimentSettings {
  Material material;
  CellModel model = CellModel::kBaudet2007;
  ExactBendingParameters exact_bending;         ///< used when model is kExactBending
  CellLaw law = CellLaw::kSprings;              ///< the cells' large-strain law (cell_law.h)
  Eigen::Vector3i cells{1, 1, 1};               ///< block size in cells
  Eigen::Vector3d cell_size{0.01, 0.01, 0.01};  ///< [m]
  /// Load size as the continuum strain it causes [-]: sigma = E S (elongation), gamma = S (shear),
  /// each side shrinks by S (inflation, P = 3 B S). Not used by the cantilever and self-weight.
  /// The finite-strain experiments take it as their end point (Experiment), in [-0.6, 1], not 0.
  double strain = 1e-4;
  /// Finite-strain experiments: the curve's points, equally spaced from 0 to strain (>= 1), each
  /// solved from the one before.
  int curve_points = 8;
  double gravity = 9.81;  ///< cantilever and self-weight [m/s^2], along -z
  ShearControl shear_control = ShearControl::kDisplacement;
  Support support = Support::kBonded;  ///< self-weight only
  /// Refuse a block whose static solve would take more memory than this [bytes]
  /// (estimate_block_factorisation, static_solver.h); 0: half this machine's memory.
  std::uint64_t max_memory_bytes = 0;
  /// Called at each Newton iteration of the experiment's static solves (StaticSettings::progress).
  std::function<void(const StaticProgress&)> progress;
};

/// One point of a finite-strain experiment's curve: the strain, the lattice's nominal (first
/// Piola-Kirchhoff) stress [Pa] and the closed form's: P_xx for uniaxial and hydrostatic, P_xz for
/// simple shear (the force on the face over its rest area).
struct CurvePoint {
  double strain = 0.0;
  double stress = 0.0;
  double expected = 0.0;
};

/// Continuum values and what the lattice gave; a quantity the experiment does not measure is empty.
struct Moduli {
  std::optional<double> young_modulus;  ///< [Pa]
  std::optional<double> poisson_ratio;  ///< [-]
  std::optional<double> shear_modulus;  ///< [Pa]
  std::optional<double> bulk_modulus;   ///< [Pa]
};

struct ExperimentResult {
  Experiment experiment = Experiment::kElongation;
  ExperimentSettings settings;
  Moduli measured;
  Moduli expected;
  /// Relative errors for moduli, absolute for the Poisson ratio.
  Moduli error;
  /// Cantilever: mean z displacement of the nodes of face x = L [m] (negative when it sags), and
  /// the Euler-Bernoulli and Timoshenko (Cowper's shear coefficient) predictions.
  std::optional<double> tip_deflection;
  std::optional<double> euler_bernoulli;
  std::optional<double> timoshenko;
  /// Displacement-controlled shear: the lattice's shear moduli in the yz, xz and xy planes [Pa],
  /// and what the cell shape gives for them (all equal to G for cubic cells).
  std::optional<Eigen::Vector3d> shear_moduli;
  std::optional<Eigen::Vector3d> expected_shear_moduli;
  /// Self-weight: the z displacement of the top face's centre [m] (negative when it sags; the
  /// mean of the 1, 2 or 4 top nodes nearest the centre, the bilinear value there), the body's
  /// volume change, deformed / rest - 1 (body_volume, strain.h), and its cells' least volume
  /// ratio (the signed volume of their mean edge vectors over the rest volume).
  std::optional<double> top_centre_uz;
  std::optional<double> volume_change;
  std::optional<double> least_cell_volume_ratio;
  /// Bonded compression: the force of the top plate on the block along z [N] (negative when it
  /// compresses), and the bulge: the x displacement of the centre of the face x = L [m] (the mean
  /// of the 1, 2 or 4 nodes nearest it).
  std::optional<double> platen_force;
  std::optional<double> bulge;
  /// Finite-strain experiments: the curve (state holds its last point).
  std::vector<CurvePoint> curve;
  Model model;
  State state;  ///< the static equilibrium
  int load_steps = 0;
  int newton_iterations = 0;
};

/// Builds the block, applies the experiment's loads and constraints, solves for static equilibrium
/// and measures. Errors name the invalid setting or the failed solve.
Result<ExperimentResult> run_experiment(Experiment experiment, const ExperimentSettings& settings);

/// The settings' checks of run_experiment alone (ranges, the block's size and memory), without
/// building anything: a caller can say what a long run will take before it starts it.
Status check_experiment(Experiment experiment, const ExperimentSettings& settings);

/// The compressible neo-Hookean law of docs/model-neo-hookean.md (with its inversion barrier; J
/// above 0.05) in closed form: nominal stresses [Pa] of a material's E and nu.
/// Uniaxial stress, the lateral faces free (their stretch solved for zero lateral stress):
double neo_hookean_uniaxial_stress(const Material& material, double stretch);
/// and that lateral stretch [-].
double neo_hookean_uniaxial_lateral_stretch(const Material& material, double stretch);
/// Simple shear F = I + gamma e_x e_z^T: P_xz = G gamma (J = 1, any gamma).
double neo_hookean_simple_shear_stress(const Material& material, double gamma);
/// Uniform dilatation to the volume ratio J: P = J^(2/3) dU/dJ.
double neo_hookean_hydrostatic_stress(const Material& material, double volume_ratio);

}  // namespace cubespring
