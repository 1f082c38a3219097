// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// cubespring measure {elongation|shear|inflation|cantilever|self-weight|uniaxial|simple-shear|
// hydrostatic}: the paper's virtual experiments, and finite-strain ones (a block under its own
// weight, stress-strain curves against the neo-Hookean law's closed form).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "arguments.h"
#include "commands.h"
#include "cubespring/static_solver.h"
#include "cubespring/validation/experiments.h"
#include "cubespring/validation/fem_comparison.h"
#include "json_output.h"
#include "message_text.h"
#include "number_checks.h"
#ifdef CUBESPRING_HAS_RENDER
#include "cantilever_picture.h"
#endif

namespace cubespring::app {
namespace {

struct MeasureOptions {
  std::string experiment;
  double young = 1e6;
  double poisson = 0.3;
  double density = 1000.0;
  std::string cells;  // empty: the experiment's default
  std::string cell_size = "0.01";
  double strain = 1e-4;
  bool strain_given = false;  // else the finite-strain experiments take their own default
  int points = 8;
  double gravity = 9.81;
  std::string control = "displacement";
  std::string model = "baudet2007";
  std::string law = "springs";
  std::string support = "bonded";
  std::uint64_t max_memory = 0;  // 0: half this machine's memory
  ExactBendingParameters exact_bending;
  bool json = false;
  std::string png;        // empty: no picture
  std::string reference;  // empty: no finite-element reference
  int width = 1280;
  int height = 720;
  double magnify = 1;
};

// The reference's figures, or null where the lattice and the reference share too few nodes.
nlohmann::json reference_json(const std::string& file, const FemComparison& c) {
  const auto value = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); };
  return {{"file", file},
          {"lattice_nodes", c.lattice_nodes},
          {"matched_nodes", c.matched_nodes},
          {"tip_deflection", value(c.reference_tip_deflection)},
          {"tip_error", value(c.tip_error)},
          {"mean_nodal_error", value(c.mean_nodal_error)},
          {"max_nodal_error", value(c.max_nodal_error)}};
}

void reference_table(const std::string& file, const FemComparison& c) {
  std::printf("reference %s: %d of %d lattice nodes matched\n", file.c_str(), c.matched_nodes, c.lattice_nodes);
  if (!c.tip_error) {
    std::printf("  (no tip comparison: the reference lacks nodes at the lattice's tip nodes)\n");
    return;
  }
  std::printf("  %-16s %14.6e  (lattice %+.2f%%)\n", "FEM tip", *c.reference_tip_deflection, 100 * *c.tip_error);
  std::printf("  %-16s mean %.2f%%, max %.2f%% of the FEM tip deflection\n", "nodal error", 100 * *c.mean_nodal_error,
              100 * *c.max_nodal_error);
}

// Writes the cantilever picture; false (after saying why) when it cannot.
bool write_picture(const MeasureOptions& o, const ExperimentResult& result, const FemSolution* reference) {
#ifdef CUBESPRING_HAS_RENDER
  Result<CantileverPicture> picture = draw_cantilever(result, reference, {o.width, o.height, o.magnify});
  Status written = picture ? write_png(picture->image, o.png) : picture.status();
  if (!written) {
    std::cerr << "error: --png: " << written.message() << "\n";
    return false;
  }
  std::cerr << "wrote " << o.png << "\n";
  return true;
#else
  (void)result;
  (void)reference;
  std::cerr << "error: --png: this cubespring was built without the renderer (CUBESPRING_WITH_OSMESA=OFF)\n";
  return false;
#endif
}

nlohmann::json to_json(const Moduli& m) {
  nlohmann::json j = nlohmann::json::object();
  if (m.young_modulus) j["young_modulus"] = *m.young_modulus;
  if (m.poisson_ratio) j["poisson_ratio"] = *m.poisson_ratio;
  if (m.shear_modulus) j["shear_modulus"] = *m.shear_modulus;
  if (m.bulk_modulus) j["bulk_modulus"] = *m.bulk_modulus;
  return j;
}

nlohmann::json planes(const Eigen::Vector3d& v) { return {{"yz", v[0]}, {"xz", v[1]}, {"xy", v[2]}}; }

// (measured - expected) / |expected|; 0 when both are 0.
double relative_difference(double measured, double expected) {
  return expected == 0.0 ? (measured == 0.0 ? 0.0 : measured) : (measured - expected) / std::abs(expected);
}

// The largest |relative difference| along a curve.
double largest_curve_error(const std::vector<CurvePoint>& curve) {
  double largest = 0.0;
  for (const CurvePoint& point : curve) {
    largest = std::max(largest, std::abs(relative_difference(point.stress, point.expected)));
  }
  return largest;
}

nlohmann::json report_json(const ExperimentResult& r) {
  const ExperimentSettings& s = r.settings;
  nlohmann::json j;
  j["experiment"] = experiment_name(r.experiment);
  j["inputs"] = {{"young_modulus", s.material.young_modulus},
                 {"poisson_ratio", s.material.poisson_ratio},
                 {"density", s.material.density},
                 {"cells", {s.cells.x(), s.cells.y(), s.cells.z()}},
                 {"cell_size", {s.cell_size.x(), s.cell_size.y(), s.cell_size.z()}},
                 {"strain", s.strain},
                 {"gravity", s.gravity},
                 {"model", cell_model_name(s.model)},
                 {"law", cell_law_name(s.law)}};
  if (r.experiment == Experiment::kShear) j["inputs"]["control"] = shear_control_name(s.shear_control);
  if (r.experiment == Experiment::kSelfWeight) j["inputs"]["support"] = support_name(s.support);
  if (s.model == CellModel::kExactBending) {
    j["inputs"]["edge_fraction"] = s.exact_bending.edge_fraction;
    j["inputs"]["twist_factor"] = s.exact_bending.twist_factor;
  }
  j["measured"] = to_json(r.measured);
  j["expected"] = to_json(r.expected);
  j["error"] = to_json(r.error);
  if (r.shear_moduli) {
    j["measured"]["shear_moduli"] = planes(*r.shear_moduli);
    j["expected"]["shear_moduli"] = planes(*r.expected_shear_moduli);
  }
  if (r.tip_deflection) {
    j["tip_deflection"] = *r.tip_deflection;
    j["measured"]["tip_deflection"] = *r.tip_deflection;
    j["expected"]["euler_bernoulli"] = *r.euler_bernoulli;
    j["expected"]["timoshenko"] = *r.timoshenko;
    j["error"]["euler_bernoulli"] = *r.tip_deflection / *r.euler_bernoulli - 1.0;
    j["error"]["timoshenko"] = *r.tip_deflection / *r.timoshenko - 1.0;
    nlohmann::json nodes = nlohmann::json::array();
    for (int n = 0; n < r.model.num_nodes(); ++n) {
      const Eigen::Vector3d rest = r.model.rest_positions.col(n);
      const Eigen::Vector3d u = r.state.positions.col(n) - rest;
      nodes.push_back({{"rest", {rest.x(), rest.y(), rest.z()}}, {"displacement", {u.x(), u.y(), u.z()}}});
    }
    j["nodes"] = std::move(nodes);
  }
  if (r.platen_force) {  // no closed form: the curve's stress alone
    nlohmann::json curve = nlohmann::json::array();
    for (const CurvePoint& point : r.curve) curve.push_back({{"strain", point.strain}, {"stress", point.stress}});
    j["curve"] = std::move(curve);
    j["inputs"]["points"] = s.curve_points;
    j["measured"]["stress"] = r.curve.back().stress;
    j["measured"]["platen_force"] = *r.platen_force;
    j["measured"]["bulge"] = *r.bulge;
    j["measured"]["volume_change"] = *r.volume_change;
    j["measured"]["least_cell_volume_ratio"] = *r.least_cell_volume_ratio;
  } else if (!r.curve.empty()) {
    nlohmann::json curve = nlohmann::json::array();
    for (const CurvePoint& point : r.curve) {
      curve.push_back({{"strain", point.strain},
                       {"stress", point.stress},
                       {"expected", point.expected},
                       {"error", relative_difference(point.stress, point.expected)}});
    }
    j["curve"] = std::move(curve);
    j["inputs"]["points"] = s.curve_points;
    j["measured"]["stress"] = r.curve.back().stress;
    j["expected"]["stress"] = r.curve.back().expected;
    j["error"]["stress"] = relative_difference(r.curve.back().stress, r.curve.back().expected);
    j["error"]["largest_stress"] = largest_curve_error(r.curve);
  }
  if (r.top_centre_uz) {
    j["measured"]["top_centre_uz"] = *r.top_centre_uz;
    j["measured"]["volume_change"] = *r.volume_change;
    j["measured"]["least_cell_volume_ratio"] = *r.least_cell_volume_ratio;
  }
  j["solver"] = {{"load_steps", r.load_steps}, {"newton_iterations", r.newton_iterations}};
  return j;
}

void print_row(const char* name, const std::optional<double>& measured, const std::optional<double>& expected,
               const std::optional<double>& error, const char* unit, bool relative) {
  if (!measured) return;
  std::printf("  %-16s %14.6g %14.6g %12.3e%s  %s\n", name, *measured, expected.value_or(0.0), error.value_or(0.0),
              relative ? " (rel)" : " (abs)", unit);
}

void report_table(const ExperimentResult& r) {
  const ExperimentSettings& s = r.settings;
  std::printf("%s: E = %g Pa, nu = %g, rho = %g kg/m^3, %d x %d x %d cells of %g x %g x %g m, model %s, law %s\n",
              experiment_name(r.experiment), s.material.young_modulus, s.material.poisson_ratio, s.material.density,
              s.cells.x(), s.cells.y(), s.cells.z(), s.cell_size.x(), s.cell_size.y(), s.cell_size.z(),
              cell_model_name(s.model), cell_law_name(s.law));
  if (r.experiment == Experiment::kShear) std::printf("shear control: %s\n", shear_control_name(s.shear_control));
  if (r.experiment == Experiment::kSelfWeight) std::printf("support: %s\n", support_name(s.support));
  if (r.tip_deflection) {
    std::printf("  %-16s %14s\n", "", "tip [m]");
    std::printf("  %-16s %14.6e\n", "lattice", *r.tip_deflection);
    std::printf("  %-16s %14.6e  (lattice %+.2f%%)\n", "Euler-Bernoulli", *r.euler_bernoulli,
                100 * (*r.tip_deflection / *r.euler_bernoulli - 1));
    std::printf("  %-16s %14.6e  (lattice %+.2f%%)\n", "Timoshenko", *r.timoshenko,
                100 * (*r.tip_deflection / *r.timoshenko - 1));
    return;
  }
  if (r.platen_force) {
    std::printf("  %12s %16s\n", "stretch - 1", "P_zz [Pa]");
    for (const CurvePoint& point : r.curve) std::printf("  %12.4f %16.6g\n", point.strain, point.stress);
    std::printf("  %-24s %14.6g N\n", "platen force", *r.platen_force);
    std::printf("  %-24s %14.6e m\n", "bulge (x = L centre)", *r.bulge);
    std::printf("  %-24s %+14.4f %%\n", "volume change", 100 * *r.volume_change);
    std::printf("  %-24s %14.4f\n", "least cell volume ratio", *r.least_cell_volume_ratio);
    return;
  }
  if (!r.curve.empty()) {
    const char* stress = r.experiment == Experiment::kSimpleShear ? "P_xz [Pa]" : "P_xx [Pa]";
    const char* strain = r.experiment == Experiment::kUniaxial      ? "stretch - 1"
                         : r.experiment == Experiment::kSimpleShear ? "gamma"
                                                                    : "J - 1";
    std::printf("  %12s %16s %16s %10s\n", strain, stress, "neo-Hookean", "error");
    for (const CurvePoint& point : r.curve) {
      std::printf("  %12.4f %16.6g %16.6g %+9.3f%%\n", point.strain, point.stress, point.expected,
                  100 * relative_difference(point.stress, point.expected));
    }
    std::printf("  largest error %.3f%% of the closed form\n", 100 * largest_curve_error(r.curve));
    return;
  }
  if (r.top_centre_uz) {
    std::printf("  %-24s %14.6e m\n", "top centre uz", *r.top_centre_uz);
    std::printf("  %-24s %+14.4f %%\n", "volume change", 100 * *r.volume_change);
    std::printf("  %-24s %14.4f\n", "least cell volume ratio", *r.least_cell_volume_ratio);
    return;
  }
  std::printf("  %-16s %14s %14s %12s\n", "quantity", "measured", "expected", "error");
  print_row("young_modulus", r.measured.young_modulus, r.expected.young_modulus, r.error.young_modulus, "Pa", true);
  print_row("poisson_ratio", r.measured.poisson_ratio, r.expected.poisson_ratio, r.error.poisson_ratio, "", false);
  print_row("shear_modulus", r.measured.shear_modulus, r.expected.shear_modulus, r.error.shear_modulus, "Pa", true);
  print_row("bulk_modulus", r.measured.bulk_modulus, r.expected.bulk_modulus, r.error.bulk_modulus, "Pa", true);
  if (r.shear_moduli) {
    const char* names[] = {"G_yz", "G_xz", "G_xy"};
    for (int p = 0; p < 3; ++p) {
      const double expected = (*r.expected_shear_moduli)[p];
      print_row(names[p], (*r.shear_moduli)[p], expected, (*r.shear_moduli)[p] / expected - 1, "Pa", true);
    }
  }
}

// Names the flag behind a library validation message.
std::string with_flag(const std::string& message) {
  const std::pair<const char*, const char*> flags[] = {{"young_modulus", "--young"},
                                                       {"poisson_ratio", "--poisson"},
                                                       {"density", "--density"},
                                                       {"strain", "--strain"},
                                                       {"gravity", "--gravity"},
                                                       {"cell size", "--cell-size"},
                                                       {"edge_fraction", "--edge-fraction"},
                                                       {"twist_factor", "--twist-factor"},
                                                       {"cells = ", "--cells"},
                                                       {"cell_size", "--cell-size"}};
  for (const auto& [field, flag] : flags) {
    if (message.find(field) != std::string::npos) return std::string(flag) + ": " + message;
  }
  return message;
}

// Operations a second of the static solver's dense fronts on one core of the machine we
// measured (a 24^3 elongation: three factorisations of 4e10 operations, 12 s for the whole run).
constexpr double kFactorisationOperationsPerSecond = 1e10;

// Says on stderr, before it starts, what a block's static solves will take when one
// factorisation would take more than a few seconds (a large --cells otherwise ran for minutes
// with no word), and then a line at each Newton iteration (each one factorisation).
void announce_long_solves(ExperimentSettings& settings) {
  const Eigen::Vector3i& cells = settings.cells;
  const FactorisationCost cost = estimate_block_factorisation(cells);
  const double seconds = cost.operations / kFactorisationOperationsPerSecond;
  if (seconds < 5.0) return;
  settings.progress = [start = std::chrono::steady_clock::now()](const StaticProgress& at) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "measure: %.0f%% of the load done, %d Newton iterations", 100.0 * at.load_fraction,
                 at.newton_iterations);
    if (at.newton_iterations > 0) std::fprintf(stderr, ", residual %.3g N", at.residual);
    std::fprintf(stderr, ", %.0f s so far\n", elapsed);
  };
  std::fprintf(stderr,
               "measure: %d x %d x %d cells: each factorisation of the stiffness (one a Newton iteration) "
               "takes about %.2g GB and %.0f s (%.2g operations at about 1e10 a second)\n",
               cells.x(), cells.y(), cells.z(), cost.peak_bytes / 1e9, seconds, cost.operations);
}

// What the flags ask for, checked as far as they can be before the experiment starts and
// before any file is read: the experiment and its settings, or the message of the first flag at
// fault (printed after "error: ", exit 2). The command line's fuzz target calls it alone.
struct MeasurePlan {
  Experiment experiment = Experiment::kElongation;
  ExperimentSettings settings;
};

// The finite-element reference named by --reference, or its reader's message with the file's
// name shown short (message_text.h) as every argument is.
Result<FemSolution> read_reference(const std::string& path) {
  Result<FemSolution> read = read_calculix_frd(path);
  if (read) return read;
  std::string message = read.message();
  if (message.rfind(path, 0) == 0) message = shown_argument(path) + message.substr(path.size());
  return Status::error("--reference: " + message);
}

Result<MeasurePlan> plan_measure(const MeasureOptions& o) {
  Result<Experiment> experiment = parse_experiment(o.experiment);
  if (!experiment) return experiment.status();
  MeasurePlan plan;
  plan.experiment = experiment.value();
  ExperimentSettings& settings = plan.settings;
  settings.material.young_modulus = o.young;
  settings.material.poisson_ratio = o.poisson;
  settings.material.density = o.density;
  settings.strain = o.strain;
  settings.curve_points = o.points;
  settings.gravity = o.gravity;
  settings.shear_control = o.control == "force" ? ShearControl::kForce : ShearControl::kDisplacement;
  settings.model = parse_cell_model(o.model).value();  // CLI11 checked the name
  settings.exact_bending = o.exact_bending;
  settings.law = parse_cell_law(o.law).value();  // CLI11 checked the name
  settings.support = parse_support(o.support).value();
  const Experiment chosen = experiment.value();
  const std::string default_cells =
      chosen == Experiment::kCantilever          ? "16,4,4"
      : chosen == Experiment::kSelfWeight        ? "12,12,12"
      : chosen == Experiment::kBondedCompression ? "8,8,8"
      : chosen == Experiment::kUniaxial || chosen == Experiment::kSimpleShear || chosen == Experiment::kHydrostatic
          ? "4,4,4"
          : "1,1,1";
  if (!o.strain_given) {  // what tissue sees: 40% compression, a shear of 0.5, a tenth of its volume
    if (chosen == Experiment::kUniaxial) settings.strain = -0.4;
    if (chosen == Experiment::kSimpleShear) settings.strain = 0.5;
    if (chosen == Experiment::kHydrostatic) settings.strain = -0.1;
    if (chosen == Experiment::kBondedCompression) settings.strain = -0.1825;  // the silicone experiment's
  }
  Result<Eigen::Vector3i> cells = parse_counts("--cells", o.cells.empty() ? default_cells : o.cells);
  if (!cells) return cells.status();
  Result<Eigen::Vector3d> cell_size = parse_sizes("--cell-size", o.cell_size);
  if (!cell_size) return cell_size.status();
  settings.cells = cells.value();
  settings.cell_size = cell_size.value();
  if ((!o.png.empty() || !o.reference.empty()) && chosen != Experiment::kCantilever) {
    return Status::error(std::string(o.png.empty() ? "--reference" : "--png") +
                         ": only the cantilever has a picture and a finite-element reference, not " + o.experiment);
  }
  settings.max_memory_bytes = o.max_memory;
  if (Status checked = check_experiment(chosen, settings); !checked) {
    const bool memory = checked.message().find("memory limit") != std::string::npos;
    return Status::error(with_flag(checked.message()) +
                         (memory ? "; give fewer --cells or a larger --max-memory" : ""));
  }
  return plan;
}

int run_measure(const MeasureOptions& o) {
  Result<MeasurePlan> planned = plan_measure(o);
  if (!planned) {
    std::cerr << "error: " << planned.message() << "\n";
    return 2;
  }
  MeasurePlan& plan = planned.value();
  ExperimentSettings& settings = plan.settings;
  std::optional<FemSolution> reference;
  if (!o.reference.empty()) {
    Result<FemSolution> read = read_reference(o.reference);
    if (!read) {
      std::cerr << "error: " << read.message() << "\n";
      return 2;
    }
    reference = std::move(read).value();
  }
  announce_long_solves(settings);
  Result<ExperimentResult> result = run_experiment(plan.experiment, settings);
  if (!result) {
    std::cerr << "error: " << with_flag(result.message()) << "\n";
    return 2;
  }
  nlohmann::json report = report_json(result.value());
  if (const std::optional<NonFinite> bad = first_non_finite(report)) {
    std::cerr << "error: the result " << bad->path << " = " << bad->value
              << " is not finite: the inputs (E = " << o.young << " Pa, nu = " << o.poisson << ", rho = " << o.density
              << " kg/m^3, strain " << settings.strain << ", gravity " << o.gravity
              << " m/s^2) are beyond what this experiment resolves\n";
    return 1;
  }
  if (!o.png.empty() && !write_picture(o, result.value(), reference ? &*reference : nullptr)) return 1;
  std::optional<FemComparison> comparison;
  if (reference) comparison = compare_cantilever_with_fem(result.value(), *reference);
  if (comparison && comparison->matched_nodes == 0) {
    std::cerr << "warning: --reference: no node of " << o.reference << " sits at a lattice node; is it the same "
              << "beam, in metres?\n";
  }
  if (o.json) {
    if (comparison) report["reference"] = reference_json(o.reference, *comparison);
    if (!o.png.empty()) report["png"] = o.png;
    std::cout << json_text(report) << "\n";
  } else {
    report_table(result.value());
    if (comparison) reference_table(o.reference, *comparison);
  }
  return 0;
}

}  // namespace

CheckedCommand add_checked_measure_command(CLI::App& app) {
  auto options = std::make_shared<MeasureOptions>();
  CLI::App* cmd = app.add_subcommand("measure",
                                     "Run one of the paper's virtual experiments and measure E, nu, G, B "
                                     "or the cantilever's tip deflection; at finite strain, a block's sag "
                                     "under its own weight or a stress-strain curve against the "
                                     "neo-Hookean law");
  cmd->add_option("experiment", options->experiment,
                  "elongation, shear, inflation, cantilever or self-weight; finite-strain curves: uniaxial, "
                  "simple-shear, hydrostatic or bonded-compression")
      ->required()
      ->check(CLI::IsMember({"elongation", "shear", "inflation", "cantilever", "self-weight", "uniaxial",
                             "simple-shear", "hydrostatic", "bonded-compression"}));
  cmd->add_option("--young", options->young, "Young's modulus E [Pa]")->check(finite_number())->capture_default_str();
  cmd->add_option("--poisson", options->poisson, "Poisson's ratio nu, in (-0.25, 0.5)")
      ->check(finite_number())
      ->capture_default_str();
  cmd->add_option("--density", options->density, "density [kg/m^3]")->check(finite_number())->capture_default_str();
  cmd->add_option("--max-memory", options->max_memory,
                  "refuse blocks whose estimate (the body and its static solver's factorisation) exceeds BYTES "
                  "(default: half of this machine's memory)")
      ->check(byte_count());
  cmd->add_option("--cells", options->cells,
                  "block size NX,NY,NZ in cells (default 1,1,1; cantilever 16,4,4; self-weight 12,12,12; the curves "
                  "4,4,4; bonded-compression 8,8,8)");
  cmd->add_option("--cell-size", options->cell_size, "cell size H or HX,HY,HZ [m]")->capture_default_str();
  CLI::Option* strain = cmd->add_option("--strain", options->strain,
                                        "load as the continuum strain it causes (small deformation); the curves' "
                                        "end: uniaxial stretch - 1 (default -0.4), simple-shear gamma (0.5), "
                                        "hydrostatic J - 1 (-0.1), bonded-compression stretch - 1 along z (-0.1825)")
                            ->check(finite_number())
                            ->capture_default_str();
  cmd->add_option("--points", options->points, "the curves (uniaxial .. bonded-compression): points on the curve")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--gravity", options->gravity, "cantilever and self-weight: gravity along -z [m/s^2]")
      ->check(finite_number())
      ->capture_default_str();
  cmd->add_option("--control", options->control,
                  "shear: displacement (affine, every boundary node) or force (the paper's tractions)")
      ->check(CLI::IsMember({"displacement", "force"}))
      ->capture_default_str();
  cmd->add_option("--support", options->support,
                  "self-weight: the base bonded, or on a frictionless floor (held along z only)")
      ->check(CLI::IsMember({"bonded", "floor"}))
      ->capture_default_str();
  CLI::Option* model = cmd->add_option("--model", options->model,
                                       "cell model: baudet2007 (the paper; the default with the springs law) or "
                                       "exact-bending (the default with the neo-Hookean law)")
                           ->check(CLI::IsMember({"baudet2007", "exact-bending"}));
  cmd->add_option("--law", options->law,
                  "large-strain law of the cells: springs (the cell model as calibrated) or neo-hookean "
                  "(docs/model-neo-hookean.md)")
      ->check(CLI::IsMember({"springs", "neo-hookean"}))
      ->capture_default_str();
  cmd->add_option("--edge-fraction", options->exact_bending.edge_fraction,
                  "exact-bending: edge stiffness as a fraction beta of E h")
      ->check(finite_number())
      ->capture_default_str();
  cmd->add_option("--twist-factor", options->exact_bending.twist_factor,
                  "exact-bending: twist stiffness as a fraction zeta of G")
      ->check(finite_number())
      ->capture_default_str();
  cmd->add_flag("--json", options->json, "print one JSON object on stdout");
  cmd->add_option("--png", options->png, "cantilever: draw the deformed lattice coloured by displacement into FILE");
  cmd->add_option("--reference", options->reference,
                  "cantilever: a CalculiX result (.frd) of the same beam in metres: compare node by node, and draw "
                  "the lattice as a wire over the reference's colours");
  cmd->add_option("--width", options->width, "--png: image width [pixels]")
      ->check(CLI::Range(16, 4096))
      ->capture_default_str();
  cmd->add_option("--height", options->height, "--png: image height [pixels]")
      ->check(CLI::Range(16, 4096))
      ->capture_default_str();
  cmd->add_option("--magnify", options->magnify,
                  "--png: draw displacements this many times their size (colours stay true)")
      ->check(finite_positive_number())
      ->capture_default_str();
  // what the flags given decide for the rest
  const auto complete = [options, strain, model] {
    options->strain_given = strain->count() > 0;
    // the neo-Hookean law's cells are exact-bending by default, as in scenes and the Bullet plugin
    // (the paper's cells have zero-energy modes that frictionless supports set free)
    if (model->count() == 0) options->model = options->law == "neo-hookean" ? "exact-bending" : "baudet2007";
  };
  return {[options, complete] {
            complete();
            return plan_measure(*options).status();
          },
          [options, complete] {
            complete();
            return run_measure(*options);
          }};
}

Command add_measure_command(CLI::App& app) { return add_checked_measure_command(app).run; }

}  // namespace cubespring::app
