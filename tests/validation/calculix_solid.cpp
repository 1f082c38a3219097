// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT

#include "calculix_solid.h"

#include <cmath>
#include <exception>
#include <set>
#include <sstream>
#include <utility>

#include "calculix_common.h"

namespace cubespring::validation {
namespace {

constexpr const char* kJobName = "solid";
constexpr int kMaxElementsPerCell = 64;
constexpr int kMaxCellIndex = 1000000;

// ---- solid mesh ----

using Index3 = std::array<int, 3>;

// Key of a node on the fine grid (pitch h/(2n)), stored as {c, b, a} so that
// std::map's lexicographic order is z-major, then y, then x (the order
// calculix_beam.cpp numbers its nodes in).
Index3 zyx_key(int a, int b, int c) { return {c, b, a}; }

struct Mesh {
  int n = 0;
  double pitch = 0;               // h / (2n)
  std::map<Index3, int> node_id;  // fine-grid {c, b, a} -> id
  int corner_count = 0;           // corners have ids 1..corner_count
  std::vector<std::array<int, 20>> elements;

  double coordinate(int fine) const { return fine * pitch; }
};

std::string check_spec(const SolidReferenceSpec& spec) {
  if (spec.cells.empty()) return "cells is empty";
  if (!std::isfinite(spec.cell_size) || spec.cell_size <= 0) {
    return "cell_size must be finite and > 0 m, got " + format_double(spec.cell_size);
  }
  if (spec.elements_per_cell < 1 || spec.elements_per_cell > kMaxElementsPerCell) {
    return "elements_per_cell must be in [1, " + std::to_string(kMaxElementsPerCell) + "], got " +
           std::to_string(spec.elements_per_cell);
  }
  for (const Eigen::Vector3i& cell : spec.cells) {
    if ((cell.array().abs() > kMaxCellIndex).any()) {
      return "cell indices must be in [-" + std::to_string(kMaxCellIndex) + ", " + std::to_string(kMaxCellIndex) +
             "], got (" + std::to_string(cell.x()) + ", " + std::to_string(cell.y()) + ", " + std::to_string(cell.z()) +
             ")";
    }
  }
  const double n = spec.elements_per_cell;
  if (static_cast<double>(spec.cells.size()) * (n + 1) * (n + 1) * (n + 1) * 4 > 5e7) {
    return "mesh too large: " + std::to_string(spec.cells.size()) + " cells of " +
           std::to_string(spec.elements_per_cell) + "^3 elements";
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
  if (!spec.gravity.allFinite()) return "gravity must be finite";
  if (spec.clamp_axis < 0 || spec.clamp_axis > 2) {
    return "clamp_axis must be 0, 1 or 2, got " + std::to_string(spec.clamp_axis);
  }
  if (!std::isfinite(spec.clamp_value)) return "clamp_value must be finite";
  if (spec.has_traction) {
    if (spec.load_axis < 0 || spec.load_axis > 2) {
      return "load_axis must be 0, 1 or 2, got " + std::to_string(spec.load_axis);
    }
    if (!std::isfinite(spec.load_value)) return "load_value must be finite";
    if (!spec.traction_constant.allFinite() || !spec.traction_gradient.allFinite()) {
      return "traction_constant and traction_gradient must be finite";
    }
  }
  if (spec.work_dir.empty()) return "work_dir is empty; give a folder for the CalculiX deck and output";
  return {};
}

// Merges the nodes of all cells' elements (one per fine-grid position) and
// numbers them: corner nodes (all fine indices even) first, then mid-edges.
std::string build_mesh(const SolidReferenceSpec& spec, Mesh& mesh) {
  mesh.n = spec.elements_per_cell;
  mesh.pitch = spec.cell_size / (2.0 * mesh.n);
  std::set<Index3> seen_cells;
  for (const Eigen::Vector3i& cell : spec.cells) {
    if (!seen_cells.insert({cell.x(), cell.y(), cell.z()}).second) {
      return "cell (" + std::to_string(cell.x()) + ", " + std::to_string(cell.y()) + ", " + std::to_string(cell.z()) +
             ") is listed twice";
    }
  }
  const int n = mesh.n;
  const auto for_each_node = [&](auto&& visit) {
    for (const Eigen::Vector3i& cell : spec.cells) {
      for (int k = 0; k < n; ++k) {
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) {
            const int a0 = 2 * (n * cell.x() + i);
            const int b0 = 2 * (n * cell.y() + j);
            const int c0 = 2 * (n * cell.z() + k);
            for (std::size_t local = 0; local < kBrickNodes.size(); ++local) {
              const auto& o = kBrickNodes[local];
              visit(local, zyx_key(a0 + o[0], b0 + o[1], c0 + o[2]));
            }
          }
        }
      }
    }
  };
  for_each_node([&](std::size_t, const Index3& key) { mesh.node_id.emplace(key, 0); });
  int next = 0;
  for (auto& [key, id] : mesh.node_id) {
    if ((key[0] & 1) == 0 && (key[1] & 1) == 0 && (key[2] & 1) == 0) id = ++next;
  }
  mesh.corner_count = next;
  for (auto& [key, id] : mesh.node_id) {
    if (id == 0) id = ++next;
  }
  mesh.elements.reserve(spec.cells.size() * static_cast<std::size_t>(n * n * n));
  for_each_node([&](std::size_t local, const Index3& key) {
    if (local == 0) mesh.elements.emplace_back();
    mesh.elements.back()[local] = mesh.node_id.at(key);
  });
  return {};
}

// Every cell must reach a cell cut by the clamp plane through shared faces:
// a floating piece, or one hanging on an edge or corner only, makes the
// system singular, and SPOOLES then returns huge displacements without a
// word (seen: 1e10 m for a detached cell, exit code 0).
std::string check_support(const SolidReferenceSpec& spec) {
  const double h = spec.cell_size;
  const double tolerance = 1e-9 * h;
  std::set<Index3> unreached;
  for (const Eigen::Vector3i& cell : spec.cells) unreached.insert({cell.x(), cell.y(), cell.z()});
  std::vector<Index3> queue;
  for (const Index3& cell : unreached) {
    const double low = cell[static_cast<std::size_t>(spec.clamp_axis)] * h;
    if (spec.clamp_value >= low - tolerance && spec.clamp_value <= low + h + tolerance) queue.push_back(cell);
  }
  for (const Index3& cell : queue) unreached.erase(cell);
  while (!queue.empty()) {
    const Index3 cell = queue.back();
    queue.pop_back();
    for (std::size_t axis = 0; axis < 3; ++axis) {
      for (int step : {-1, 1}) {
        Index3 next = cell;
        next[axis] += step;
        if (unreached.erase(next) != 0) queue.push_back(next);
      }
    }
  }
  if (unreached.empty()) return {};
  const Index3& cell = *unreached.begin();
  return std::to_string(unreached.size()) + " cell(s), e.g. (" + std::to_string(cell[0]) + ", " +
         std::to_string(cell[1]) + ", " + std::to_string(cell[2]) +
         "), are not joined by shared faces to a cell on the clamp plane (the system would be singular)";
}

// Consistent nodal forces of the traction on the 8-node faces (3x3 Gauss,
// exact for a linear traction), indexed by node id.
std::string traction_forces(const SolidReferenceSpec& spec, const Mesh& mesh, std::map<int, Eigen::Vector3d>& force) {
  const int axis = spec.load_axis;
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  const int n = mesh.n;
  const double tolerance = 1e-9 * spec.cell_size;
  std::set<Index3> occupied;
  for (const Eigen::Vector3i& cell : spec.cells) occupied.insert({cell.x(), cell.y(), cell.z()});
  const double gauss_point[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double gauss_weight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  // serendipity shape function of the face node at (xi_i, eta_i) in {-1,0,1}^2
  const auto shape = [](int xi_i, int eta_i, double xi, double eta) {
    if (xi_i != 0 && eta_i != 0) {
      return 0.25 * (1 + xi * xi_i) * (1 + eta * eta_i) * (xi * xi_i + eta * eta_i - 1);
    }
    if (xi_i == 0) return 0.5 * (1 - xi * xi) * (1 + eta * eta_i);
    return 0.5 * (1 + xi * xi_i) * (1 - eta * eta);
  };
  int faces = 0;
  for (const Eigen::Vector3i& cell : spec.cells) {
    const int top = 2 * n * (cell[axis] + 1);  // fine index of the cell's upper side
    if (std::abs(mesh.coordinate(top) - spec.load_value) > tolerance) continue;
    Index3 beyond{cell.x(), cell.y(), cell.z()};
    ++beyond[static_cast<std::size_t>(axis)];
    if (occupied.count(beyond) != 0) continue;
    ++faces;
    for (int eu = 0; eu < n; ++eu) {
      for (int ev = 0; ev < n; ++ev) {
        const int u0 = 2 * (n * cell[u] + eu);
        const int v0 = 2 * (n * cell[v] + ev);
        for (int ou = 0; ou <= 2; ++ou) {
          for (int ov = 0; ov <= 2; ++ov) {
            if (ou == 1 && ov == 1) continue;  // no face-centre node
            std::array<int, 3> fine{};
            fine[static_cast<std::size_t>(axis)] = top;
            fine[static_cast<std::size_t>(u)] = u0 + ou;
            fine[static_cast<std::size_t>(v)] = v0 + ov;
            const auto found = mesh.node_id.find(zyx_key(fine[0], fine[1], fine[2]));
            if (found == mesh.node_id.end()) return "internal error: face node missing";
            Eigen::Vector3d sum = Eigen::Vector3d::Zero();
            for (int gu = 0; gu < 3; ++gu) {
              for (int gv = 0; gv < 3; ++gv) {
                Eigen::Vector3d p;
                p[axis] = mesh.coordinate(top);
                p[u] = (u0 + 1 + gauss_point[gu]) * mesh.pitch;
                p[v] = (v0 + 1 + gauss_point[gv]) * mesh.pitch;
                const Eigen::Vector3d traction = spec.traction_constant + spec.traction_gradient * p;
                sum += gauss_weight[gu] * gauss_weight[gv] * shape(ou - 1, ov - 1, gauss_point[gu], gauss_point[gv]) *
                       traction;
              }
            }
            // dA = pitch^2 dxi deta on the element face [u0, u0+2] x [v0, v0+2]
            auto [entry, inserted] = force.emplace(found->second, Eigen::Vector3d::Zero());
            (void)inserted;
            entry->second += mesh.pitch * mesh.pitch * sum;
          }
        }
      }
    }
  }
  if (faces == 0) {
    return "no boundary cell face normal to +axis " + std::to_string(axis) + " at " + format_double(spec.load_value) +
           " m for the traction";
  }
  return {};
}

std::string build_deck(const SolidReferenceSpec& spec, const Mesh& mesh, std::string& deck) {
  deck.clear();
  deck += "** solid of grid cells, written by cubespring calculix_solid.cpp\n";
  deck += "*HEADING\ncubespring solid reference\n";
  deck += "*NODE, NSET=NALL\n";
  for (const auto& [key, id] : mesh.node_id) {
    deck += std::to_string(id) + "," + deck_number(mesh.coordinate(key[2])) + "," +
            deck_number(mesh.coordinate(key[1])) + "," + deck_number(mesh.coordinate(key[0])) + "\n";
  }
  // at most 16 entries per line: element id and 15 nodes, then 5 more
  deck += "*ELEMENT, TYPE=C3D20R, ELSET=EALL\n";
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    deck += std::to_string(e + 1);
    for (std::size_t local = 0; local < 20; ++local) {
      deck += local == 15 ? ",\n" : ",";
      deck += std::to_string(mesh.elements[e][local]);
    }
    deck += '\n';
  }
  deck += "*NSET, NSET=NCORNER, GENERATE\n1," + std::to_string(mesh.corner_count) + ",1\n";

  // every node (corner and mid-edge) on the clamp plane
  const double tolerance = 1e-9 * spec.cell_size;
  const std::size_t clamp_key = static_cast<std::size_t>(2 - spec.clamp_axis);
  deck += "*NSET, NSET=NFIX\n";
  int on_line = 0;
  int clamped = 0;
  for (const auto& [key, id] : mesh.node_id) {
    if (std::abs(mesh.coordinate(key[clamp_key]) - spec.clamp_value) > tolerance) continue;
    ++clamped;
    deck += std::to_string(id);
    deck += ++on_line == 16 ? ",\n" : ",";
    if (on_line == 16) on_line = 0;
  }
  if (on_line != 0) deck += '\n';
  if (clamped == 0) {
    return "no node on the clamp plane (axis " + std::to_string(spec.clamp_axis) + " at " +
           format_double(spec.clamp_value) + " m)";
  }
  deck += "*BOUNDARY\nNFIX,1,3\n";

  deck += "*MATERIAL, NAME=SOLID_MATERIAL\n";
  deck += "*ELASTIC\n" + deck_number(spec.young_modulus) + "," + deck_number(spec.poisson_ratio) + "\n";
  deck += "*DENSITY\n" + deck_number(spec.density) + "\n";
  deck += "*SOLID SECTION, ELSET=EALL, MATERIAL=SOLID_MATERIAL\n";
  deck += "*STEP\n*STATIC, SOLVER=SPOOLES\n";
  const double g = spec.gravity.norm();
  if (g > 0) {
    const Eigen::Vector3d direction = spec.gravity / g;
    deck += "*DLOAD\nEALL,GRAV," + deck_number(g) + "," + deck_number(direction.x()) + "," +
            deck_number(direction.y()) + "," + deck_number(direction.z()) + "\n";
  }
  if (spec.has_traction) {
    std::map<int, Eigen::Vector3d> force;
    if (std::string problem = traction_forces(spec, mesh, force); !problem.empty()) return problem;
    std::string lines;
    for (const auto& [id, f] : force) {
      for (int dof = 0; dof < 3; ++dof) {
        if (f[dof] != 0) lines += std::to_string(id) + "," + std::to_string(dof + 1) + "," + deck_number(f[dof]) + "\n";
      }
    }
    if (!lines.empty()) deck += "*CLOAD\n" + lines;
  }
  deck += "*NODE PRINT, NSET=NCORNER\nU\n";
  deck += "*END STEP\n";
  return {};
}

SolidResult fail(std::string message) {
  SolidResult result;
  result.error = "calculix solid: " + std::move(message);
  return result;
}

SolidResult compute(const SolidReferenceSpec& spec) {
  if (std::string problem = check_spec(spec); !problem.empty()) return fail(problem);
  if (!calculix_available()) return fail("ccx not found on PATH (install Debian's calculix-ccx)");

  Mesh mesh;
  if (std::string problem = build_mesh(spec, mesh); !problem.empty()) return fail(problem);
  if (std::string problem = check_support(spec); !problem.empty()) return fail(problem);
  std::string deck;
  if (std::string problem = build_deck(spec, mesh, deck); !problem.empty()) return fail(problem);

  CcxResult run = run_ccx(spec.work_dir, kJobName, deck, mesh.corner_count);
  if (!run.error.empty()) return fail(run.error);
  const std::vector<Eigen::Vector3d>& displacement = run.corner_displacement;

  SolidReference reference;
  reference.cell_size = spec.cell_size;
  reference.elements_per_cell = spec.elements_per_cell;
  for (const auto& [key, id] : mesh.node_id) {
    if (id > mesh.corner_count) continue;
    // fine index / 2 = index on the corner grid (pitch h/n)
    reference.corner_displacement.emplace(Index3{key[2] / 2, key[1] / 2, key[0] / 2},
                                          displacement[static_cast<std::size_t>(id - 1)]);
  }
  SolidResult result;
  result.reference = std::move(reference);
  return result;
}

}  // namespace

std::optional<Eigen::Vector3d> SolidReference::displacement_at(const Eigen::Vector3d& point) const {
  if (!(cell_size > 0) || !std::isfinite(cell_size) || elements_per_cell < 1 || !point.allFinite()) {
    return std::nullopt;
  }
  const double step = cell_size / elements_per_cell;
  const double tolerance = 1e-9 * cell_size;
  Index3 index{};
  for (int axis = 0; axis < 3; ++axis) {
    const double nearest = std::round(point[axis] / step);
    if (std::abs(nearest) > 1e9) return std::nullopt;
    if (std::abs(point[axis] - nearest * step) > tolerance) return std::nullopt;
    index[static_cast<std::size_t>(axis)] = static_cast<int>(nearest);
  }
  const auto found = corner_displacement.find(index);
  if (found == corner_displacement.end()) return std::nullopt;
  return found->second;
}

SolidResult compute_solid_reference(const SolidReferenceSpec& spec) {
  // filesystem and allocation failures must come back as messages too
  try {
    return compute(spec);
  } catch (const std::exception& error) {
    return fail(std::string("unexpected failure: ") + error.what());
  } catch (...) {
    return fail("unexpected failure");
  }
}

}  // namespace cubespring::validation
