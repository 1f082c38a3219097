// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT

#include "calculix_beam.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <utility>

#include "calculix_common.h"

namespace cubespring::validation {
namespace {

constexpr const char* kJobName = "beam";
// above this many unknowns ccx uses its iterative solver (see build_deck)
constexpr double kIterativeAboveEquations = 100000;
constexpr double kIterativeMaxPoisson = 0.4;

// Node ids on the doubled grid (2n+1 points per axis). Corner nodes (all
// indices even) get ids 1..corner_count in BeamReference order, so the
// corner node set is one GENERATE range and parsing needs no lookup table;
// mid-edge nodes (exactly one odd index) follow. Other points (face and
// body centres) are not nodes of a 20-node brick and keep id 0.
struct NodeGrid {
  Eigen::Vector3i n;     // elements per axis
  Eigen::Vector3i fine;  // 2n+1 points per axis
  std::vector<int> id;   // (fine.x * fine.y * fine.z), 0 = no node
  int corner_count = 0;
  int node_count = 0;

  explicit NodeGrid(const Eigen::Vector3i& elements) : n(elements) {
    fine = 2 * n + Eigen::Vector3i::Ones();
    id.assign(static_cast<std::size_t>(fine.x()) * fine.y() * fine.z(), 0);
    corner_count = (n.x() + 1) * (n.y() + 1) * (n.z() + 1);
    int next_mid = corner_count + 1;
    for (int c = 0; c < fine.z(); ++c) {
      for (int b = 0; b < fine.y(); ++b) {
        for (int a = 0; a < fine.x(); ++a) {
          const int odd = (a & 1) + (b & 1) + (c & 1);
          if (odd == 0) {
            id[index(a, b, c)] = 1 + a / 2 + (n.x() + 1) * (b / 2 + (n.y() + 1) * (c / 2));
          } else if (odd == 1) {
            id[index(a, b, c)] = next_mid++;
          }
        }
      }
    }
    node_count = next_mid - 1;
  }

  std::size_t index(int a, int b, int c) const {
    return static_cast<std::size_t>(a) +
           static_cast<std::size_t>(fine.x()) * (static_cast<std::size_t>(b) + static_cast<std::size_t>(fine.y()) * c);
  }
};

std::string check_spec(const BeamReferenceSpec& spec) {
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(spec.size[axis]) || spec.size[axis] <= 0) {
      return "beam size must be finite and > 0 on every axis, got " + format_double(spec.size[axis]) + " on axis " +
             std::to_string(axis);
    }
    if (spec.elements[axis] < 1 || spec.elements[axis] > 4096) {
      return "elements must be in [1, 4096] on every axis, got " + std::to_string(spec.elements[axis]) + " on axis " +
             std::to_string(axis);
    }
  }
  // keep ids well inside ccx's 32-bit integers and the deck of sane size
  const double corner_estimate = (spec.elements.cast<double>() + Eigen::Vector3d::Ones()).prod();
  if (corner_estimate * 4 > 5e7) {
    return "mesh too large: " + std::to_string(spec.elements.x()) + "x" + std::to_string(spec.elements.y()) + "x" +
           std::to_string(spec.elements.z()) + " elements";
  }
  if (!std::isfinite(spec.young_modulus) || spec.young_modulus <= 0) {
    return "young_modulus must be finite and > 0 Pa, got " + format_double(spec.young_modulus);
  }
  if (!std::isfinite(spec.poisson_ratio) || spec.poisson_ratio <= -1 || spec.poisson_ratio >= 0.5) {
    return "poisson_ratio must be in (-1, 0.5), got " + format_double(spec.poisson_ratio);
  }
  if (!std::isfinite(spec.density) || spec.density <= 0) {
    return "density must be finite and > 0 kg/m^3, got " + format_double(spec.density);
  }
  if (!std::isfinite(spec.gravity)) {
    return "gravity must be finite, got " + format_double(spec.gravity);
  }
  if (spec.clamped_axis < 0 || spec.clamped_axis > 2) {
    return "clamped_axis must be 0, 1 or 2, got " + std::to_string(spec.clamped_axis);
  }
  if (!std::isfinite(spec.platen_travel) || spec.platen_travel < 0 ||
      spec.platen_travel >= spec.size[std::clamp(spec.clamped_axis, 0, 2)]) {
    return "platen_travel must be in [0, the size along clamped_axis) m, got " + format_double(spec.platen_travel);
  }
  if (spec.work_dir.empty()) {
    return "work_dir is empty; give a folder for the CalculiX deck and output";
  }
  return {};
}

// An *NSET of the nodes (corner and mid-edge) on the doubled grid's face at index `at` along
// `axis`, 16 to a line (ccx reads no more).
std::string face_node_set(const char* name, const NodeGrid& grid, int axis, int at) {
  std::string set = std::string("*NSET, NSET=") + name + "\n";
  int on_line = 0;
  for (int c = 0; c < grid.fine.z(); ++c) {
    for (int b = 0; b < grid.fine.y(); ++b) {
      for (int a = 0; a < grid.fine.x(); ++a) {
        if (Eigen::Vector3i(a, b, c)[axis] != at) continue;
        const int node = grid.id[grid.index(a, b, c)];
        if (node == 0) continue;
        set += std::to_string(node);
        set += ++on_line == 16 ? ",\n" : ",";
        if (on_line == 16) on_line = 0;
      }
    }
  }
  if (on_line != 0) set += '\n';
  return set;
}

std::string build_deck(const BeamReferenceSpec& spec, const NodeGrid& grid) {
  std::string deck;
  deck.reserve(static_cast<std::size_t>(grid.node_count) * 64 + static_cast<std::size_t>(spec.elements.prod()) * 140);
  deck += "** box clamped on one face under gravity, written by cubespring calculix_beam.cpp\n";
  deck += "*HEADING\ncubespring box under gravity, clamped where coordinate " + std::to_string(spec.clamped_axis) +
          " is 0\n";

  // nodes at (a, b, c) * h / 2 on the doubled grid
  const Eigen::Vector3d half_step = spec.size.cwiseQuotient(spec.elements.cast<double>()) / 2;
  deck += "*NODE, NSET=NALL\n";
  for (int c = 0; c < grid.fine.z(); ++c) {
    for (int b = 0; b < grid.fine.y(); ++b) {
      for (int a = 0; a < grid.fine.x(); ++a) {
        const int node = grid.id[grid.index(a, b, c)];
        if (node == 0) continue;
        // end points exactly on the faces, no rounding drift from a*h
        const double x = a == grid.fine.x() - 1 ? spec.size.x() : a * half_step.x();
        const double y = b == grid.fine.y() - 1 ? spec.size.y() : b * half_step.y();
        const double z = c == grid.fine.z() - 1 ? spec.size.z() : c * half_step.z();
        deck += std::to_string(node) + "," + deck_number(x) + "," + deck_number(y) + "," + deck_number(z) + "\n";
      }
    }
  }

  // ccx reads at most 16 entries per line: element id and 15 nodes, then the
  // remaining 5 nodes on a continuation line
  deck += "*ELEMENT, TYPE=C3D20R, ELSET=EALL\n";
  int element = 0;
  for (int k = 0; k < spec.elements.z(); ++k) {
    for (int j = 0; j < spec.elements.y(); ++j) {
      for (int i = 0; i < spec.elements.x(); ++i) {
        deck += std::to_string(++element);
        for (std::size_t local = 0; local < kBrickNodes.size(); ++local) {
          const auto& offset = kBrickNodes[local];
          const int node = grid.id[grid.index(2 * i + offset[0], 2 * j + offset[1], 2 * k + offset[2])];
          deck += local == 15 ? ",\n" : ",";
          deck += std::to_string(node);
        }
        deck += '\n';
      }
    }
  }

  deck += "*NSET, NSET=NCORNER, GENERATE\n1," + std::to_string(grid.corner_count) + ",1\n";

  // every node of the clamped face, corner and mid-edge alike
  deck += face_node_set("NFIX", grid, spec.clamped_axis, 0);
  if (!spec.sliding) {
    deck += "*BOUNDARY\nNFIX,1,3\n";
  } else {
    // the face's own axis for every node; the centre node and the end of its row hold the rest
    const int normal = spec.clamped_axis, first = (normal + 1) % 3, second = (normal + 2) % 3;
    const int p = std::min(first, second), q = std::max(first, second);
    Eigen::Vector3i centre = Eigen::Vector3i::Zero();
    centre[p] = spec.elements[p];
    centre[q] = spec.elements[q];
    Eigen::Vector3i row_end = centre;
    row_end[p] = 2 * spec.elements[p];
    const int centre_node = grid.id[grid.index(centre.x(), centre.y(), centre.z())];
    const int row_end_node = grid.id[grid.index(row_end.x(), row_end.y(), row_end.z())];
    if (centre_node == 0 || row_end_node == 0) {
      throw std::invalid_argument("sliding: no node at the centre of the clamped face (odd element counts)");
    }
    const std::string n = std::to_string(normal + 1), a = std::to_string(p + 1), b = std::to_string(q + 1);
    deck += "*BOUNDARY\nNFIX," + n + "," + n + "\n";
    deck += std::to_string(centre_node) + "," + a + "," + a + "\n";
    deck += std::to_string(centre_node) + "," + b + "," + b + "\n";
    deck += std::to_string(row_end_node) + "," + b + "," + b + "\n";
  }

  if (spec.platen_travel > 0) {
    // the opposite face, corner and mid-edge nodes, bonded to the platen
    const int axis = spec.clamped_axis;
    deck += face_node_set("NPLATEN", grid, axis, grid.fine[axis] - 1);
    const std::string n = std::to_string(axis + 1);
    const std::string a = std::to_string((axis + 1) % 3 + 1), b = std::to_string((axis + 2) % 3 + 1);
    deck += "*BOUNDARY\nNPLATEN," + a + "," + a + "\nNPLATEN," + b + "," + b + "\n";
    deck += "NPLATEN," + n + "," + n + "," + deck_number(-spec.platen_travel) + "\n";
  }

  deck += "*MATERIAL, NAME=BEAM_MATERIAL\n";
  const double e = spec.young_modulus;
  const double nu = spec.poisson_ratio;
  if (spec.nonlinear && spec.neo_hookean) {
    // compressible neo-Hookean matching the small-strain E and nu
    const double shear_modulus = e / (2 * (1 + nu));
    const double bulk_modulus = e / (3 * (1 - 2 * nu));
    deck += "*HYPERELASTIC, NEO HOOKE\n" + deck_number(shear_modulus / 2) + "," + deck_number(2 / bulk_modulus) + "\n";
  } else {
    deck += "*ELASTIC\n" + deck_number(e) + "," + deck_number(nu) + "\n";
  }
  deck += "*DENSITY\n" + deck_number(spec.density) + "\n";
  deck += "*SOLID SECTION, ELSET=EALL, MATERIAL=BEAM_MATERIAL\n";

  // Debian's ccx has SPOOLES (direct) and ccx's own conjugate-gradient
  // solvers, no PARDISO or PaStiX. Timed on two cores (linear step):
  //   32x8x8 (29k equations):    SPOOLES 3.4 s, ITERATIVE SCALING 3.8 s
  //   64x16x16 (215k equations): SPOOLES 90 s and 5.7 GB,
  //                              ITERATIVE SCALING 57 s and 0.4 GB
  // (ITERATIVE CHOLESKY was slower than both). The iterative answers match
  // SPOOLES to the 7 digits of the .dat output in the sag; so direct for
  // small meshes, where it is as fast and exact, iterative for large ones.
  // Near incompressibility the conjugate gradients crawl (194 s at
  // 64x16x16, nu = 0.49) while the direct solver's cost does not change.
  const double equations = 3.0 * grid.node_count;
  const bool iterative = equations > kIterativeAboveEquations && nu <= kIterativeMaxPoisson;
  const char* solver = iterative ? "ITERATIVE SCALING" : "SPOOLES";
  if (spec.nonlinear) {
    // initial increment, period, minimum and maximum increment: ccx grows or
    // cuts the increment from the convergence of each Newton solve; 0.25 took
    // 11 iterations at E = 1e5 Pa where 0.1 (max 0.25) took 16
    deck += "*STEP, NLGEOM, INC=1000\n*STATIC, SOLVER=" + std::string(solver) + "\n0.25,1.,1e-6,1.\n";
  } else {
    deck += "*STEP\n*STATIC, SOLVER=" + std::string(solver) + "\n";
  }
  if (spec.gravity != 0) deck += "*DLOAD\nEALL,GRAV," + deck_number(spec.gravity) + ",0.,0.,-1.\n";
  // .dat output: one fixed-format block per converged increment
  deck += "*NODE PRINT, NSET=NCORNER\nU\n";
  if (spec.platen_travel > 0) deck += "*NODE PRINT, NSET=NPLATEN, TOTALS=ONLY\nRF\n";
  // beam.frd: every node and the solid's surface, for `cubespring measure cantilever --reference`
  deck += "*NODE FILE\nU\n";
  deck += "*END STEP\n";
  return deck;
}

BeamResult fail(std::string message) {
  BeamResult result;
  result.error = std::move(message);
  return result;
}

BeamResult compute(const BeamReferenceSpec& spec) {
  if (std::string problem = check_spec(spec); !problem.empty()) return fail("calculix beam: " + problem);
  if (!calculix_available()) {
    return fail("calculix beam: ccx not found on PATH (install Debian's calculix-ccx)");
  }

  const NodeGrid grid(spec.elements);
  CcxResult run = run_ccx(spec.work_dir, kJobName, build_deck(spec, grid), grid.corner_count,
                          spec.platen_travel > 0 ? "NPLATEN" : "");
  if (!run.error.empty()) return fail("calculix beam: " + run.error);
  BeamReference reference;
  reference.elements = spec.elements;
  reference.size = spec.size;
  reference.corner_displacement = std::move(run.corner_displacement);
  if (spec.platen_travel > 0) reference.platen_force = run.total_force;
  BeamResult result;
  result.reference = std::move(reference);
  return result;
}

}  // namespace

std::optional<Eigen::Vector3d> BeamReference::displacement_at(const Eigen::Vector3d& rest_point) const {
  const Eigen::Vector3i n = elements;
  if ((n.array() < 1).any() || !size.allFinite() || (size.array() <= 0).any()) return std::nullopt;
  if (corner_displacement.size() != static_cast<std::size_t>((n.x() + 1) * (n.y() + 1) * (n.z() + 1))) {
    return std::nullopt;
  }
  if (!rest_point.allFinite()) return std::nullopt;
  const double tolerance = 1e-9 * size.maxCoeff();
  std::array<int, 3> index{};
  for (int axis = 0; axis < 3; ++axis) {
    const double step = size[axis] / n[axis];
    const double nearest = std::round(rest_point[axis] / step);
    if (nearest < 0 || nearest > n[axis]) return std::nullopt;
    const double snapped = nearest == n[axis] ? size[axis] : nearest * step;
    if (std::abs(rest_point[axis] - snapped) > tolerance) return std::nullopt;
    index[axis] = static_cast<int>(nearest);
  }
  return corner_displacement[index[0] + (n.x() + 1) * (index[1] + (n.y() + 1) * index[2])];
}

double BeamReference::tip_deflection() const {
  const Eigen::Vector3i n = elements;
  if ((n.array() < 1).any() ||
      corner_displacement.size() != static_cast<std::size_t>((n.x() + 1) * (n.y() + 1) * (n.z() + 1))) {
    return NAN;
  }
  double sum = 0;
  for (int k = 0; k <= n.z(); ++k) {
    for (int j = 0; j <= n.y(); ++j) {
      sum += corner_displacement[n.x() + (n.x() + 1) * (j + (n.y() + 1) * k)].z();
    }
  }
  return sum / ((n.y() + 1) * (n.z() + 1));
}

BeamResult compute_beam_reference(const BeamReferenceSpec& spec) {
  // filesystem and allocation failures must come back as messages too
  try {
    return compute(spec);
  } catch (const std::exception& error) {
    return fail(std::string("calculix beam: unexpected failure: ") + error.what());
  } catch (...) {
    return fail("calculix beam: unexpected failure");
  }
}

}  // namespace cubespring::validation
