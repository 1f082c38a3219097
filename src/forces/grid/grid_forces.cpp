// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Four passes over the grid's points, each a loop over a z-layer's contiguous points (from its
// first node to its last: GridLayout::layer_spans) that the compiler vectorises (compiled with -fopenmp-simd,
// -fno-math-errno and -fno-trapping-math, src/CMakeLists.txt):
//   1. springs: length, length rate, own tension; the edges family by family, keeping their unit
//      vector; the 4 diagonals of a cell at once (no correction: their force), from its 8
//      corners, which also give the signed volume of its mean edge vectors -> crushed cells
//      (docs/model-baudet2007.md section 5);
//      neo-Hookean bodies: the law's cell term from the 8 corners (1b; docs/model-neo-hookean.md);
//   2. cells: mean edge strains -> correction tension per axis (section 3);
//   3. edges: force = (own tension + the correction of the up to 4 cells of the edge) x unit vector;
//   the exact-bending twist, by faces (below), when the body has it: its cells' coefficients in
//      pass 1 (from the corners the diagonals read), each face's difference of its two cells'
//      coefficients in pass 3a, its edge forces in pass 3b; the neo-Hookean term's edge forces
//      from the up to 4 cells of the edge (3c);
//   4. points: force = sum over families of the force of the springs that start there minus that
//      of those that end there (a gather: no two points write the same place, so threads write
//      nothing another writes, and the sums do not depend on the thread count).
// The passes run z-layer by z-layer, each as soon as its inputs are there, and keep their
// temporaries for the 3 layers they read at once only (a ring per thread), so that the
// temporaries stay in cache and only the state, forces and model stream through it.
#include "forces/grid/grid_forces.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <thread>

#include "cubespring/forces.h"
#include "forces/correction_tension.h"
#include "forces/force_passes.h"
#include "forces/grid/grid_arrays.h"
#include "forces/grid/vector_clones.h"
#include "forces/twist.h"
#include "invariant.h"
#include "model/neo_hookean_cell.h"
#include "thread_shares.h"

namespace cubespring {
namespace {

// The points a pass computes in the first `rows` y-rows of a z-layer: the layer's span of nodes
// (GridLayout::layer_spans) within them.
inline PointSpan layer_points(const GridLayout& grid, int slab, int rows) {
  const PointSpan& span = grid.layer_spans[static_cast<std::size_t>(slab)];
  return {span.begin, std::max(span.begin, std::min(span.end, rows * grid.stride_y))};
}
// A per-point array of the layout (no padding) from the first point of layer `slab`.
inline const double* from_layer(const std::vector<double>& values, const GridLayout& grid, int slab) {
  return values.data() + static_cast<std::size_t>(slab) * grid.stride_z;
}
inline Eigen::Vector3i unit(int axis) { return Eigen::Vector3i::Unit(axis); }
constexpr int kZEdges = 2;  // the family of the z-edges (grid_layout.h)
using Clock = std::chrono::steady_clock;

// Pass 1 for edge family f on one z-layer: its unit vectors (scaled to forces in pass 3),
// lengths, rates and own tensions; kKeepVector: it keeps its vectors too (twist); kUniform: a
// family whose springs have a cell's share of stiffness and damping times their number of cells
// (SpringFamily::uniform; the same bits), counted from the cells' occupancy, which the
// diagonals' loop streams anyway: a stream of per-point values spared, two with damping.
template <bool kWithRate, bool kKeepVector, bool kUniform>
CUBESPRING_VECTOR_CLONES void measure_edges(const GridLayout& grid, int f, int slab, const LayerArrays& a) {
  const SpringFamily& family = grid.families[f];
  const PointSpan points = layer_points(grid, slab, family.rows);
  const double* __restrict x = a.in(kPosition, slab);
  const double* __restrict y = a.in(kPosition + 1, slab);
  const double* __restrict z = a.in(kPosition + 2, slab);
  const double* __restrict vx = a.in(kVelocity, slab);
  const double* __restrict vy = a.in(kVelocity + 1, slab);
  const double* __restrict vz = a.in(kVelocity + 2, slab);
  double* __restrict fx = a.out(kFamilyForce + 3 * f, slab);
  double* __restrict fy = a.out(kFamilyForce + 3 * f + 1, slab);
  double* __restrict fz = a.out(kFamilyForce + 3 * f + 2, slab);
  // the cells read the lengths and rates, pass 3 the own tensions
  double* __restrict length_out = a.out(kEdgeLength + f, slab);
  double* __restrict rate_out = a.out(kEdgeRate + f, slab);
  double* __restrict own_out = a.out(kEdgeOwnTension + f, slab);
  double* __restrict vector_x = a.out(kEdgeVector + 3 * f, slab);
  double* __restrict vector_y = a.out(kEdgeVector + 3 * f + 1, slab);
  double* __restrict vector_z = a.out(kEdgeVector + 3 * f + 2, slab);
  const double* __restrict stiffness = kUniform ? nullptr : from_layer(family.stiffness, grid, slab);
  const double* __restrict damping = kWithRate && !kUniform ? from_layer(family.damping, grid, slab) : nullptr;
  // an edge's cells: the one at its first point and those a step back along b, c and both
  const double* __restrict occupied = grid.occupied_from_layer(slab);
  const int back_b = f == 0 ? grid.stride_y : 1, back_c = f == 2 ? grid.stride_y : grid.stride_z;
  const double* __restrict occupied_b = occupied - back_b;
  const double* __restrict occupied_c = occupied - back_c;
  const double* __restrict occupied_bc = occupied - back_b - back_c;
  const double cell_stiffness = family.cell_stiffness, cell_damping = family.cell_damping;
  const double rest = family.rest_length;
  const double degenerate = kDegenerateLengthFraction * rest;
  const int from = family.from, to = family.to;
#pragma omp simd
  for (int g = points.begin; g < points.end; ++g) {
    const double ex = x[g + to] - x[g + from];
    const double ey = y[g + to] - y[g + from];
    const double ez = z[g + to] - z[g + from];
    const double length = std::sqrt(ex * ex + ey * ey + ez * ez);
    const double inverse = length > degenerate ? 1.0 / length : 0.0;
    const double cells = (occupied[g] + occupied_b[g]) + (occupied_c[g] + occupied_bc[g]);
    double own = (kUniform ? cells * cell_stiffness : stiffness[g]) * (length - rest);
    if constexpr (kWithRate) {
      const double rate =
          ((vx[g + to] - vx[g + from]) * ex + (vy[g + to] - vy[g + from]) * ey + (vz[g + to] - vz[g + from]) * ez) *
          inverse;
      own += (kUniform ? cells * cell_damping : damping[g]) * rate;
      rate_out[g] = rate;
    }
    fx[g] = ex * inverse;
    fy[g] = ey * inverse;
    fz[g] = ez * inverse;
    length_out[g] = length;
    own_out[g] = own;
    if constexpr (kKeepVector) {
      vector_x[g] = ex;
      vector_y[g] = ey;
      vector_z[g] = ez;
    }
  }
}

template <bool kWithRate>
void measure_edge_family(const GridLayout& grid, int f, int slab, const LayerArrays& a) {
  if (slab >= grid.families[f].slabs) return;  // the top layer has no z-edges: their zeros stay
  const bool uniform = grid.families[f].uniform;
  if (grid.has_twist) {
    uniform ? measure_edges<kWithRate, true, true>(grid, f, slab, a)
            : measure_edges<kWithRate, true, false>(grid, f, slab, a);
  } else {
    uniform ? measure_edges<kWithRate, false, true>(grid, f, slab, a)
            : measure_edges<kWithRate, false, false>(grid, f, slab, a);
  }
}

// The 4 edges along `axis` of the cells of a layer start at the cell's corner 0 and at steps b,
// c, b + c (b < c the other axes): their sum, in that order (as in forces.cpp).
struct CellEdges {
  const double *at_0, *at_b, *at_c, *at_bc;
  CellEdges(const LayerArrays& a, int slot, int slab, int axis) {
    const Eigen::Vector3i b = unit(axis == 0 ? 1 : 0), c = unit(axis == 2 ? 1 : 2);
    at_0 = a.in(slot, slab);
    at_b = a.in(slot, slab, b);
    at_c = a.in(slot, slab, c);
    at_bc = a.in(slot, slab, b + c);
  }
};
inline double edge_sum(const CellEdges& edges, int g) {
  return (edges.at_0[g] + edges.at_b[g]) + (edges.at_c[g] + edges.at_bc[g]);
}

// The twist of the exact-bending model (docs/model-exact-bending.md section 3; the same terms as
// src/forces/twist.h, arranged by faces of the grid). A cell's two faces normal to d (in-plane axes
// a < c) have mean edge vectors a_s, c_s (s = lower, upper); w_d = (a_u . c_u - a_l . c_l) / h^2
// and Q_d = k h w_d / 2. The a-edges of a face get the force -Q_d c_l (lower face of the cell) or
// +Q_d c_u (upper face) on their lower corner, the c-edges -Q_d a_l or +Q_d a_u. A face is the
// upper face of one cell and the lower of the next along d, so an edge gets, from each face F it
// lies on, (Q_d[F - step d] - Q_d[F]) times the face's mean of its other in-plane edges.

// Q_d of a cell from 4 x its faces' dot products (measure_diagonals; twist.h's formula).
inline double twist_coefficient_of_4(double lower_4, double upper_4, double stiffness, double h) {
  return twist_coefficient(twist_shear(0.25 * lower_4, 0.25 * upper_4, h), stiffness, h);
}

// Pass 1 for the 4 diagonal families on one z-layer at once (no correction: their forces at
// once), from the cell's 8 corners, which give the cells' crushed test too: the signed volume of
// the mean edge vectors, which the diagonals give (as forces.cpp's cell pass finds them:
// sum_k s_a(k) x_k = sum over diagonals k -> 7 - k of s_a(7 - k) (x_{7-k} - x_k)); and with
// kTwist, the cells' twist coefficients (above). Returns the layer's crushed cells. kUniform:
// the diagonals' stiffness and damping, and the cells' twist, are the grid's constants times
// the occupancy (SpringFamily::uniform and GridLayout::uniform_cells, the same bits).
template <bool kWithRate, bool kTwist, bool kUniform>
CUBESPRING_VECTOR_CLONES int measure_diagonals(const GridLayout& grid, int slab, const LayerArrays& a) {
  constexpr int d0 = kEdgeFamilies;  // diagonal k is family d0 + k, from corner k to corner 7 - k
  const PointSpan points = layer_points(grid, slab, grid.cell_rows);
  const int sy = grid.stride_y, sz = grid.stride_z;
  const int step[8] = {0, 1, sy, 1 + sy, sz, 1 + sz, sy + sz, 1 + sy + sz};  // corner c at g + step[c]
  const double* position[3] = {a.in(kPosition, slab), a.in(kPosition + 1, slab), a.in(kPosition + 2, slab)};
  const double* velocity[3] = {a.in(kVelocity, slab), a.in(kVelocity + 1, slab), a.in(kVelocity + 2, slab)};
  const double* __restrict occupied = grid.occupied_from_layer(slab);
  double* out[4][3];
  const double* stiffness[4];
  const double* damping[4];
  double cell_stiffness[4], cell_damping[4], rest[4], degenerate[4];
  for (int k = 0; k < 4; ++k) {
    const SpringFamily& family = grid.families[d0 + k];
    CUBESPRING_ASSERT(family.rows == grid.cell_rows && family.slabs == grid.cell_slabs);
    CUBESPRING_ASSERT(family.from == step[k] && family.to == step[7 - k]);
    for (int c = 0; c < 3; ++c) out[k][c] = a.out(kFamilyForce + 3 * (d0 + k) + c, slab);
    stiffness[k] = kUniform ? nullptr : from_layer(family.stiffness, grid, slab);
    damping[k] = kWithRate && !kUniform ? from_layer(family.damping, grid, slab) : nullptr;
    cell_stiffness[k] = family.cell_stiffness;
    cell_damping[k] = family.cell_damping;
    rest[k] = family.rest_length;
    degenerate[k] = kDegenerateLengthFraction * family.rest_length;
  }
  const double crushed_volume_64 = 64.0 * kCrushedVolumeFraction * grid.cell_size.prod();
  const double* __restrict twist_stiffness = kTwist && !kUniform ? from_layer(grid.cell_twist, grid, slab) : nullptr;
  const double uniform_twist = grid.uniform_twist;
  double* __restrict qx = a.out(kCellTwist, slab);
  double* __restrict qy = a.out(kCellTwist + 1, slab);
  double* __restrict qz = a.out(kCellTwist + 2, slab);
  const double h = grid.cell_size.x();
  int crushed = 0;
#pragma omp simd reduction(+ : crushed)
  for (int g = points.begin; g < points.end; ++g) {
    double d[4][3];   // diagonal k's vector, corner 7 - k minus corner k
    double dv[4][3];  // and its velocity difference
    // twist: 4 x the dot products of the mean in-plane edge vectors of the faces normal to x, y,
    // z, lower and upper (twist_coefficient_of_4)
    double x_lower = 0.0, x_upper = 0.0, y_lower = 0.0, y_upper = 0.0, z_lower = 0.0, z_upper = 0.0;
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
      const double* p = position[c];
      const double p0 = p[g + step[0]], p1 = p[g + step[1]], p2 = p[g + step[2]], p3 = p[g + step[3]];
      const double p4 = p[g + step[4]], p5 = p[g + step[5]], p6 = p[g + step[6]], p7 = p[g + step[7]];
      d[0][c] = p7 - p0;
      d[1][c] = p6 - p1;
      d[2][c] = p5 - p2;
      d[3][c] = p4 - p3;
      if constexpr (kWithRate) {
        const double* v = velocity[c];
        dv[0][c] = v[g + step[7]] - v[g + step[0]];
        dv[1][c] = v[g + step[6]] - v[g + step[1]];
        dv[2][c] = v[g + step[5]] - v[g + step[2]];
        dv[3][c] = v[g + step[4]] - v[g + step[3]];
      }
      if constexpr (kTwist) {  // a face's a-edges times its c-edges (a < c its in-plane axes)
        x_lower += ((p2 - p0) + (p6 - p4)) * ((p4 - p0) + (p6 - p2));
        x_upper += ((p3 - p1) + (p7 - p5)) * ((p5 - p1) + (p7 - p3));
        y_lower += ((p1 - p0) + (p5 - p4)) * ((p4 - p0) + (p5 - p1));
        y_upper += ((p3 - p2) + (p7 - p6)) * ((p6 - p2) + (p7 - p3));
        z_lower += ((p1 - p0) + (p3 - p2)) * ((p2 - p0) + (p3 - p1));
        z_upper += ((p5 - p4) + (p7 - p6)) * ((p6 - p4) + (p7 - p5));
      }
    }
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      const double ex = d[k][0], ey = d[k][1], ez = d[k][2];
      const double length = std::sqrt(ex * ex + ey * ey + ez * ez);
      const double inverse = length > degenerate[k] ? 1.0 / length : 0.0;
      double own = (kUniform ? occupied[g] * cell_stiffness[k] : stiffness[k][g]) * (length - rest[k]);
      if constexpr (kWithRate) {
        const double rate = (dv[k][0] * ex + dv[k][1] * ey + dv[k][2] * ez) * inverse;
        own += (kUniform ? occupied[g] * cell_damping[k] : damping[k][g]) * rate;
      }
      const double q = own * inverse;
      out[k][0][g] = q * ex;
      out[k][1][g] = q * ey;
      out[k][2][g] = q * ez;
    }
    double mean[3][3];  // 4 x the mean edge vector along each axis: s_a(7 - k) is, for k = 0..3,
                        // x: + - + -, y: + + - -, z: + + + +
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
      mean[0][c] = (d[0][c] - d[1][c]) + (d[2][c] - d[3][c]);
      mean[1][c] = (d[0][c] + d[1][c]) - (d[2][c] + d[3][c]);
      mean[2][c] = (d[0][c] + d[1][c]) + (d[2][c] + d[3][c]);
    }
    const double mxx = mean[0][0], mxy = mean[0][1], mxz = mean[0][2];
    const double myx = mean[1][0], myy = mean[1][1], myz = mean[1][2];
    const double mzx = mean[2][0], mzy = mean[2][1], mzz = mean[2][2];
    const double volume = mxx * (myy * mzz - myz * mzy) + mxy * (myz * mzx - myx * mzz) + mxz * (myx * mzy - myy * mzx);
    crushed += static_cast<int>((occupied[g] > 0.0) & (volume < crushed_volume_64));
    if constexpr (kTwist) {
      const double twist = kUniform ? occupied[g] * uniform_twist : twist_stiffness[g];
      qx[g] = twist_coefficient_of_4(x_lower, x_upper, twist, h);
      qy[g] = twist_coefficient_of_4(y_lower, y_upper, twist, h);
      qz[g] = twist_coefficient_of_4(z_lower, z_upper, twist, h);
    }
  }
  return crushed;
}

// Pass 2 on one z-layer of cells: their correction tensions (their crushed test and twist
// coefficients are measure_diagonals'). kUniform: every cell has the grid's uniform coefficients
// (times its occupancy: 1 or 0, the same bits), which spares the loop 6-8 streams of per-cell
// values (its loads from memory were most of its time).
template <bool kWithRate, bool kUniform>
CUBESPRING_VECTOR_CLONES void cell_pass(const GridLayout& grid, int slab, const LayerArrays& a) {
  const PointSpan points = layer_points(grid, slab, grid.cell_rows);
  const Eigen::Array3d inverse_edge_sum = (kEdgesPerAxis * grid.cell_size.array()).inverse();
  const Eigen::Array3d tension_per_stress = grid.cell_size.prod() * inverse_edge_sum;
  const double ix = inverse_edge_sum.x(), iy = inverse_edge_sum.y(), iz = inverse_edge_sum.z();
  const double tx = tension_per_stress.x(), ty = tension_per_stress.y(), tz = tension_per_stress.z();
  const CellEdges lx(a, kEdgeLength, slab, 0), ly(a, kEdgeLength + 1, slab, 1), lz(a, kEdgeLength + 2, slab, 2);
  const CellEdges rx(a, kEdgeRate, slab, 0), ry(a, kEdgeRate + 1, slab, 1), rz(a, kEdgeRate + 2, slab, 2);
  const double* __restrict dxx = from_layer(grid.correction[0], grid, slab);
  const double* __restrict dyy = from_layer(grid.correction[1], grid, slab);
  const double* __restrict dzz = from_layer(grid.correction[2], grid, slab);
  const double* __restrict dxy = from_layer(grid.correction[3], grid, slab);
  const double* __restrict dxz = from_layer(grid.correction[4], grid, slab);
  const double* __restrict dyz = from_layer(grid.correction[5], grid, slab);
  const double* __restrict beta = kWithRate && !kUniform ? from_layer(grid.cell_beta, grid, slab) : nullptr;
  const double uxx = grid.uniform_correction[0], uyy = grid.uniform_correction[1], uzz = grid.uniform_correction[2];
  const double uxy = grid.uniform_correction[3], uxz = grid.uniform_correction[4], uyz = grid.uniform_correction[5];
  const double uniform_beta = grid.uniform_beta;
  const double* __restrict occupied = grid.occupied_from_layer(slab);
  double* __restrict tension_x = a.out(kCellTension, slab);
  double* __restrict tension_y = a.out(kCellTension + 1, slab);
  double* __restrict tension_z = a.out(kCellTension + 2, slab);
#pragma omp simd
  for (int g = points.begin; g < points.end; ++g) {
    double ex = mean_edge_strain(edge_sum(lx, g), ix);
    double ey = mean_edge_strain(edge_sum(ly, g), iy);
    double ez = mean_edge_strain(edge_sum(lz, g), iz);
    if constexpr (kWithRate) {
      const double b = kUniform ? uniform_beta : beta[g];
      ex = damped_edge_strain(ex, b, edge_sum(rx, g), ix);
      ey = damped_edge_strain(ey, b, edge_sum(ry, g), iy);
      ez = damped_edge_strain(ez, b, edge_sum(rz, g), iz);
    }
    if constexpr (kUniform) {
      const double o = occupied[g];
      tension_x[g] = o * correction_tension(tx, uxx, uxy, uxz, ex, ey, ez);
      tension_y[g] = o * correction_tension(ty, uxy, uyy, uyz, ex, ey, ez);
      tension_z[g] = o * correction_tension(tz, uxz, uyz, uzz, ex, ey, ez);
    } else {
      tension_x[g] = correction_tension(tx, dxx[g], dxy[g], dxz[g], ex, ey, ez);
      tension_y[g] = correction_tension(ty, dxy[g], dyy[g], dyz[g], ex, ey, ez);
      tension_z[g] = correction_tension(tz, dxz[g], dyz[g], dzz[g], ex, ey, ez);
    }
  }
}

// The cell at g of neo_hookean_cell_pass (a function the vectorised loop inlines). `quarter`: 1/4
// for a cell of the body, 0 for an empty one, whose term is as finite as the body's nodes (its
// corners are those nodes and the rest points around them; a select here kept the loop scalar).
template <class Constants>
[[gnu::always_inline]] inline void neo_hookean_cell_at(int g, const Constants& constants, double quarter,
                                                       const double* const (&position)[3], const int (&step)[8],
                                                       double* const (&out)[9]) {
  double m[3][3];
#pragma GCC unroll 3
  for (int c = 0; c < 3; ++c) {
    const double* p = position[c];
    const double p0 = p[g + step[0]], p1 = p[g + step[1]], p2 = p[g + step[2]], p3 = p[g + step[3]];
    const double p4 = p[g + step[4]], p5 = p[g + step[5]], p6 = p[g + step[6]], p7 = p[g + step[7]];
    m[0][c] = 0.25 * (((p1 - p0) + (p3 - p2)) + ((p5 - p4) + (p7 - p6)));
    m[1][c] = 0.25 * (((p2 - p0) + (p3 - p1)) + ((p6 - p4) + (p7 - p5)));
    m[2][c] = 0.25 * (((p4 - p0) + (p5 - p1)) + ((p6 - p2) + (p7 - p3)));
  }
  double gradient[3][3];
  (void)neo_hookean_term(constants, m, gradient);
#pragma GCC unroll 3
  for (int p = 0; p < 3; ++p) {
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) out[3 * p + c][g] = quarter * gradient[p][c];
  }
}

// Pass 1b, neo-Hookean bodies only, on one z-layer of cells: the law's term of each cell
// (neo_hookean_term, which the spring lists call too) from its 8 corners' mean edge vectors m_p;
// a quarter of dC/dm_p is what each of its 4 edges along p puts on its first end (corner_forces:
// f_k = -1/4 sum_p s_p(k) dC/dm_p). The loop over a layer vectorises, empty cells included
// (their quarter is 0): kUniform, a body of one material; else the constants that differ between
// materials are read at each point (GridLayout::law_cells; the demo's liver and tumour: cell by
// cell, skipping the empty two thirds of its box, the pass took 27% of the demo's time, and its
// elastic step 1.4 times as long).
template <bool kUniform>
CUBESPRING_VECTOR_CLONES void neo_hookean_cell_pass(const GridLayout& grid, int slab, const LayerArrays& a) {
  const PointSpan points = layer_points(grid, slab, grid.cell_rows);
  const int sy = grid.stride_y, sz = grid.stride_z;
  const int step[8] = {0, 1, sy, 1 + sy, sz, 1 + sz, sy + sz, 1 + sy + sz};  // corner c at g + step[c]
  const double* const position[3] = {a.in(kPosition, slab), a.in(kPosition + 1, slab), a.in(kPosition + 2, slab)};
  const std::size_t layer = static_cast<std::size_t>(slab) * grid.stride_z;
  const int* __restrict law = grid.cell_law.data() + layer;
  double* out[9];
  for (int i = 0; i < 9; ++i) out[i] = a.out(kCellNeoHookean + i, slab);
  if constexpr (kUniform) {
    const NeoHookeanConstants& uniform = grid.law_constants.front();
#pragma omp simd
    for (int g = points.begin; g < points.end; ++g)
      neo_hookean_cell_at(g, uniform, law[g] >= 0 ? 0.25 : 0.0, position, step, out);
  } else {
    const GridLayout::LawCells& cells = grid.law_cells;
    const double* __restrict c10 = cells.c10.data() + layer;
    const double* __restrict half_bulk = cells.half_bulk.data() + layer;
    const double* __restrict barrier = cells.barrier.data() + layer;
    const double* __restrict diagonal_stiffness = cells.diagonal_stiffness.data() + layer;
    const double* __restrict quarter = cells.quarter.data() + layer;
    const NeoHookeanConstants& first = grid.law_constants.front();
    // the fields neo_hookean_term reads, as plain numbers
    struct PointConstants {
      double cell_size[3];
      double rest_volume, c10, half_bulk, barrier, diagonal_stiffness, diagonal_length;
    };
#pragma omp simd
    for (int g = points.begin; g < points.end; ++g) {
      const PointConstants constants{{first.cell_size[0], first.cell_size[1], first.cell_size[2]},
                                     first.rest_volume,
                                     c10[g],
                                     half_bulk[g],
                                     barrier[g],
                                     diagonal_stiffness[g],
                                     first.diagonal_length};
      neo_hookean_cell_at(g, constants, quarter[g], position, step, out);
    }
  }
}

// Pass 3 for edge family f on one z-layer: the edge at g belongs to the cells at g, g - b, g - c,
// g - b - c (b, c the other two axes).
CUBESPRING_VECTOR_CLONES void edge_tension_pass(const GridLayout& grid, int f, int slab, const LayerArrays& a) {
  const SpringFamily& family = grid.families[f];
  if (slab >= family.slabs) return;
  const PointSpan points = layer_points(grid, slab, family.rows);
  const Eigen::Vector3i b = unit((f + 1) % 3), c = unit((f + 2) % 3);
  const double* __restrict at_0 = a.in(kCellTension + f, slab);
  const double* __restrict at_b = a.in(kCellTension + f, slab, -b);
  const double* __restrict at_c = a.in(kCellTension + f, slab, -c);
  const double* __restrict at_bc = a.in(kCellTension + f, slab, -b - c);
  const double* __restrict own = a.in(kEdgeOwnTension + f, slab);
  double* __restrict fx = a.out(kFamilyForce + 3 * f, slab);  // the unit vector, made the force
  double* __restrict fy = a.out(kFamilyForce + 3 * f + 1, slab);
  double* __restrict fz = a.out(kFamilyForce + 3 * f + 2, slab);
#pragma omp simd
  for (int g = points.begin; g < points.end; ++g) {
    const double total = own[g] + ((at_0[g] + at_b[g]) + (at_c[g] + at_bc[g]));
    fx[g] *= total;
    fy[g] *= total;
    fz[g] *= total;
  }
}

// Pass 3c, neo-Hookean bodies only: each edge of family f on one z-layer adds what its up to 4
// cells' term puts on its first end (neo_hookean_cell_pass).
CUBESPRING_VECTOR_CLONES void neo_hookean_edge_pass(const GridLayout& grid, int f, int slab, const LayerArrays& a) {
  const SpringFamily& family = grid.families[f];
  if (slab >= family.slabs) return;
  const PointSpan points = layer_points(grid, slab, family.rows);
  const Eigen::Vector3i b = unit((f + 1) % 3), c = unit((f + 2) % 3);
  for (int k = 0; k < 3; ++k) {
    const int slot = kCellNeoHookean + 3 * f + k;
    const double* __restrict at_0 = a.in(slot, slab);
    const double* __restrict at_b = a.in(slot, slab, -b);
    const double* __restrict at_c = a.in(slot, slab, -c);
    const double* __restrict at_bc = a.in(slot, slab, -b - c);
    double* __restrict out = a.out(kFamilyForce + 3 * f + k, slab);
#pragma omp simd
    for (int g = points.begin; g < points.end; ++g) out[g] += (at_0[g] + at_b[g]) + (at_c[g] + at_bc[g]);
  }
}

// Pass 3a, twist only: each face's difference of its two cells' twist coefficients, for the
// faces normal to x, y, z (or the first `normals` of them) at the points of one z-layer; pass 3b
// reads two of these per face normal instead of four coefficients, for each component.
CUBESPRING_VECTOR_CLONES void face_twist_pass(const GridLayout& grid, int slab, const LayerArrays& a, int normals) {
  const PointSpan points = layer_points(grid, slab, grid.points.y());
  for (int d = 0; d < normals; ++d) {
    const double* __restrict own = a.in(kCellTwist + d, slab);
    const double* __restrict behind = a.in(kCellTwist + d, slab, -unit(d));
    double* __restrict difference = a.out(kFaceTwist + d, slab);
#pragma omp simd
    for (int g = points.begin; g < points.end; ++g) difference[g] = 0.5 * (behind[g] - own[g]);
  }
}

// Pass 3b, twist only: the twist forces of the edges of family f on one z-layer, added to their
// forces. The edge along e at g lies on the faces normal to each other axis d at F = g and
// F = g - o (o the third axis); the face's mean of its o-edges starts at F and F + e.
CUBESPRING_VECTOR_CLONES void twist_edge_pass(const GridLayout& grid, int f, int slab, const LayerArrays& a) {
  const SpringFamily& family = grid.families[f];
  if (slab >= family.slabs) return;
  const PointSpan points = layer_points(grid, slab, family.rows);
  const Eigen::Vector3i e = unit(f);
  // the two faces' normals d and third axes o: (d1, d2) and (d2, d1)
  const int d1 = (f + 1) % 3, d2 = (f + 2) % 3;
  const Eigen::Vector3i s1 = unit(d1), s2 = unit(d2);
  // the faces' coefficient differences (face_twist_pass): normal d1 at g and g - s2, d2 at g and g - s1
  const double* __restrict near1_at = a.in(kFaceTwist + d1, slab);
  const double* __restrict far1_at = a.in(kFaceTwist + d1, slab, -s2);
  const double* __restrict near2_at = a.in(kFaceTwist + d2, slab);
  const double* __restrict far2_at = a.in(kFaceTwist + d2, slab, -s1);
  // the faces' o-edge vectors' x (y and z follow in the ring): o = d2 for the faces normal to d1
  const double* m1_x[4] = {a.in(kEdgeVector + 3 * d2, slab), a.in(kEdgeVector + 3 * d2, slab, e),
                           a.in(kEdgeVector + 3 * d2, slab, -s2), a.in(kEdgeVector + 3 * d2, slab, e - s2)};
  const double* m2_x[4] = {a.in(kEdgeVector + 3 * d1, slab), a.in(kEdgeVector + 3 * d1, slab, e),
                           a.in(kEdgeVector + 3 * d1, slab, -s1), a.in(kEdgeVector + 3 * d1, slab, e - s1)};
  double* const force_x = a.out(kFamilyForce + 3 * f, slab);
  for (int k = 0; k < 3; ++k) {  // a loop per component: all three at once need too many registers
    const std::size_t component = k * a.slot_stride();
    const double* __restrict m1_0 = m1_x[0] + component;   // at g
    const double* __restrict m1_e = m1_x[1] + component;   // at g + e
    const double* __restrict m1_2 = m1_x[2] + component;   // at g - s2
    const double* __restrict m1_2e = m1_x[3] + component;  // at g - s2 + e
    const double* __restrict m2_0 = m2_x[0] + component;
    const double* __restrict m2_e = m2_x[1] + component;
    const double* __restrict m2_1 = m2_x[2] + component;  // at g - s1
    const double* __restrict m2_1e = m2_x[3] + component;
    double* __restrict out = force_x + component;
#pragma omp simd
    for (int g = points.begin; g < points.end; ++g) {
      // normal d1: faces at g and g - s2; normal d2: faces at g and g - s1
      const double near1 = near1_at[g], far1 = far1_at[g], near2 = near2_at[g], far2 = far2_at[g];
      out[g] += (near1 * (m1_0[g] + m1_e[g]) + far1 * (m1_2[g] + m1_2e[g])) +
                (near2 * (m2_0[g] + m2_e[g]) + far2 * (m2_1[g] + m2_1e[g]));
    }
  }
}

// Pass 4 on one z-layer of points: each family's springs that start at g (at g - from) pull
// g towards their other end; those that end at g (at g - to) pull it back.
CUBESPRING_VECTOR_CLONES void gather_pass(const GridLayout& grid, int slab, const LayerArrays& a) {
  const PointSpan points = layer_points(grid, slab, grid.points.y());
  const double* starting_x[kSpringFamilies];
  const double* ending_x[kSpringFamilies];
  for (int f = 0; f < kSpringFamilies; ++f) {
    starting_x[f] = a.in(kFamilyForce + 3 * f, slab, -grid.families[f].from_corner);
    ending_x[f] = a.in(kFamilyForce + 3 * f, slab, -grid.families[f].to_corner);
  }
  for (int axis = 0; axis < 3; ++axis) {
    const double* starting[kSpringFamilies];
    const double* ending[kSpringFamilies];
    for (int f = 0; f < kSpringFamilies; ++f) {  // y and z follow x in the ring
      starting[f] = starting_x[f] + axis * a.slot_stride();
      ending[f] = ending_x[f] + axis * a.slot_stride();
    }
    double* __restrict force = a.out(kForce + axis, slab);
#pragma omp simd
    for (int g = points.begin; g < points.end; ++g) {
      double sum = 0.0;
#pragma GCC unroll 7
      for (int f = 0; f < kSpringFamilies; ++f) sum += starting[f][g] - ending[f][g];
      force[g] = sum;
    }
  }
}

// The passes of one z-layer each, in the order a layer's inputs become ready. Layers outside
// the grid have nothing to do.
struct LayerPasses {
  const GridLayout& grid;
  const LayerArrays& a;
  bool with_rate;

  // the first `families` families (the x- and y-edges, or all); needs the positions of slab and
  // slab + 1. Returns the layer's crushed cells when it measures the diagonals, else 0.
  int measure(int slab, int families = kSpringFamilies) const {
    if (slab < 0 || slab >= grid.points.z()) return 0;
    for (int f = 0; f < std::min(families, kEdgeFamilies); ++f) {
      if (with_rate) {
        measure_edge_family<true>(grid, f, slab, a);
      } else {
        measure_edge_family<false>(grid, f, slab, a);
      }
    }
    if (families <= kEdgeFamilies || slab >= grid.cell_slabs) return 0;  // the top layer: no diagonals
    bool uniform = !grid.has_twist || grid.uniform_cells;                // the twist's constants, and the diagonals'
    for (int f = kEdgeFamilies; f < kSpringFamilies; ++f) uniform = uniform && grid.families[f].uniform;
    const int crushed = with_rate ? diagonals_of_kind<true>(slab, uniform) : diagonals_of_kind<false>(slab, uniform);
    if (!grid.neo_hookean) return crushed;
    grid.law_constants.size() == 1 ? neo_hookean_cell_pass<true>(grid, slab, a)
                                   : neo_hookean_cell_pass<false>(grid, slab, a);
    return 0;  // the law's barrier replaces the crushed cells' recovery
  }
  template <bool kWithRate>
  int diagonals_of_kind(int slab, bool uniform) const {
    if (grid.has_twist) {
      return uniform ? measure_diagonals<kWithRate, true, true>(grid, slab, a)
                     : measure_diagonals<kWithRate, true, false>(grid, slab, a);
    }
    return uniform ? measure_diagonals<kWithRate, false, true>(grid, slab, a)
                   : measure_diagonals<kWithRate, false, false>(grid, slab, a);
  }
  // needs measure(slab) and measure(slab + 1)
  void cells(int slab) const {
    if (slab < 0 || slab >= grid.cell_slabs) return;  // the top layer of points: its zeros stay
    if (grid.uniform_cells) {
      with_rate ? cell_pass<true, true>(grid, slab, a) : cell_pass<false, true>(grid, slab, a);
    } else {
      with_rate ? cell_pass<true, false>(grid, slab, a) : cell_pass<false, false>(grid, slab, a);
    }
  }
  // edge families [first_family, end_family), each once a layer (the pass scales the unit
  // vector); needs cells(slab) and cells(slab - 1) (the z-edges cells(slab) only); the twist also
  // measure(slab - 1) and the faces of slab - 1 (x- and y-edges) or measure(slab + 1) (z-edges)
  void edge_tensions(int slab, int first_family = 0, int end_family = kEdgeFamilies) const {
    if (slab < 0) return;
    // the z-edges' twist reads the faces normal to x and y only (their Q_z would need the cells of
    // the layer below)
    if (grid.has_twist) face_twist_pass(grid, slab, a, first_family == kZEdges ? 2 : 3);
    for (int f = first_family; f < end_family; ++f) {
      edge_tension_pass(grid, f, slab, a);
      if (grid.has_twist) twist_edge_pass(grid, f, slab, a);
      if (grid.neo_hookean) neo_hookean_edge_pass(grid, f, slab, a);
    }
  }
  void gather(int slab) const { gather_pass(grid, slab, a); }  // needs tensions of slab, slab - 1
};

struct Range {
  int begin, end;
};

// The nodes whose points lie in the z-layers `layers`: a range, as point_of_node increases.
Range nodes_in_layers(const GridLayout& grid, const Range& layers) {
  const auto first_node_at = [&](int slab) {
    const auto& points = grid.point_of_node;
    return static_cast<int>(std::lower_bound(points.begin(), points.end(), slab * grid.stride_z) - points.begin());
  };
  return {first_node_at(layers.begin), first_node_at(layers.end)};
}

// Values of the nodes in `nodes` (of 3 x num_nodes) into the grid arrays slot .. slot + 2.
CUBESPRING_VECTOR_CLONES void copy_in(const GridLayout& grid, const Eigen::Matrix3Xd& values, const LayerArrays& a,
                                      int slot, const Range& nodes) {
  double* __restrict x = a.out(slot, 0);
  double* __restrict y = a.out(slot + 1, 0);
  double* __restrict z = a.out(slot + 2, 0);
  const double* __restrict from = values.data();
  const int* __restrict point_of_node = grid.point_of_node.data();
  if (nodes.begin == nodes.end) return;
  const int shift = point_of_node[nodes.begin] - nodes.begin;
  if (on_consecutive_points(point_of_node, nodes.begin, nodes.end)) {  // a sweep the compiler vectorises
#pragma omp simd
    for (int n = nodes.begin; n < nodes.end; ++n) {
      x[n + shift] = from[3 * n];
      y[n + shift] = from[3 * n + 1];
      z[n + shift] = from[3 * n + 2];
    }
    return;
  }
  for (int n = nodes.begin; n < nodes.end; ++n) {
    const int g = point_of_node[n];
    x[g] = from[3 * n];
    y[g] = from[3 * n + 1];
    z[g] = from[3 * n + 2];
  }
}

void copy_out(const GridLayout& grid, const LayerArrays& a, int slot, const Range& nodes, Eigen::Matrix3Xd& values) {
  const double* grid_values[3] = {a.in(slot, 0), a.in(slot + 1, 0), a.in(slot + 2, 0)};
  for (int n = nodes.begin; n < nodes.end; ++n) {
    const int g = grid.point_of_node[n];
    for (int axis = 0; axis < 3; ++axis) values(axis, n) = grid_values[axis][g];
  }
}

// At most this many threads share the grid passes (their results live on the stack: a step
// allocates nothing).
constexpr int kMaxGridThreads = 64;

// What the chunks share besides the arrays: their crushed cells, their nodes' fastest squared
// speed when they kick, the time each took for its own work (not waiting) [s] and the layers
// each gathered.
struct ChunkResults {
  std::array<int, kMaxGridThreads> crushed{};
  std::array<double, kMaxGridThreads> fastest_sq{};
  std::array<double, kMaxGridThreads> seconds{};
  std::array<Range, kMaxGridThreads> gathered{};
  int total_crushed() const {
    int total = 0;
    for (int c : crushed) total += c;
    return total;
  }
};

// Chunks go in pairs, chunk 2r sweeping region r's layers of points up from its first, chunk
// 2r + 1 down from its last; the last chunk of an odd count sweeps its region up alone.
int num_regions(int chunks) { return (chunks + 1) / 2; }
bool sweeps_down(int chunk) { return chunk % 2 == 1; }
int threads_in_region(int region, int chunks) { return std::min(2, chunks - 2 * region); }
Range region_layers(const std::vector<int>& first, int region, int chunks) {
  return {first[2 * region], first[std::min(2 * region + 2, chunks)]};
}

// A chunk's share: the region it sweeps and the layers whose state it copies in. A layer is
// gathered by the chunk that claims it: each claim takes one of the region's unclaimed layers
// (the next above the up-chunk's last, or below the down-chunk's), so the pair meets where their
// speeds on this call bring them; with a fixed meeting point, up to it and from it.
struct ChunkPlan {
  Range region;
  Range copied;
  bool down = false;
  std::atomic<int>* unclaimed = nullptr;  // the region's layers not yet claimed
  int fixed_meet = -1;                    // >= 0: where the pair meets, no claims

  bool claim(int layer) const {
    if (fixed_meet >= 0) return down ? layer >= fixed_meet : layer < fixed_meet;
    return unclaimed->fetch_sub(1, std::memory_order_relaxed) > 0;  // only the count is shared
  }
};

// The state's layers in the grid's arrays: each chunk copies in its own and marks them done; a
// chunk that needs a layer of another waits for every chunk's copy, once. On two threads the
// pair's threads need each other's layers only where they meet, by when the copies are long
// done: a barrier after the copies instead made the first thread wait for the second to start
// every step, time the claims let it spend on layers. (With more, a region's threads read their
// neighbour regions' layers at once, and wait as at a barrier.) A pass reads the state up to a
// point into the layer after the next (a diagonal from the last point of a layer).
class CopyWaits {
 public:
  CopyWaits(std::atomic<int>* done, int chunks, const Range& own, int layers, bool timed)
      : done_(done), chunks_(chunks), own_(own), layers_(layers), timed_(timed) {}

  void mark_done(int chunk) const { done_[chunk].store(1, std::memory_order_release); }
  /// Before a pass reads the state of layers [begin, end).
  void need(int begin, int end) {
    begin = std::max(begin, 0);
    end = std::min(end, layers_);
    if (all_done_ || begin >= end || (begin >= own_.begin && end <= own_.end)) return;
    const auto start = timed_ ? Clock::now() : Clock::time_point{};
    for (int c = 0; c < chunks_; ++c) {
      for (int spins = 0; done_[c].load(std::memory_order_acquire) == 0; ++spins) {
        if (spins > 256) std::this_thread::yield();  // the other thread may have lost its core
      }
    }
    if (timed_) waited_ = Clock::now() - start;
    all_done_ = true;
  }
  Clock::duration waited() const { return waited_; }

 private:
  std::atomic<int>* done_;
  int chunks_;
  Range own_;
  int layers_;
  bool timed_;
  bool all_done_ = false;
  Clock::duration waited_{};
};

// Sweeps up from the region's first layer while it claims layers; returns those it gathered.
// Its first gather needs the spring forces of the layer below, another chunk's: the chunk
// recomputes them (the springs and cells of that layer, its z-edges' tensions) rather than wait
// for that chunk (sharing that layer instead was no faster: docs/data-layout.md).
Range sweep_up(const LayerPasses& passes, const ChunkPlan& plan, CopyWaits& waits, int& crushed) {
  const int first = plan.region.begin;
  if (first == plan.region.end || !plan.claim(first)) return {first, first};
  waits.need(first - 1, first + 3);  // a diagonal reaches a point into the layer after next
  // the springs of the layer below that end in the first layer (nothing below the grid): its
  // z-edges and diagonals (not its crushed cells: the chunk below counts them). The z-edges'
  // tensions need the cells of that layer only; its x- and y-edges, which would need the layer
  // below it, stay as they are: no gather here reads them.
  (void)passes.measure(first - 1);
  crushed += passes.measure(first);
  passes.cells(first - 1);
  passes.edge_tensions(first - 1, kZEdges);
  int slab = first;
  for (;;) {
    waits.need(slab + 1, slab + 4);
    // of the region's next layer, only the x- and y-edges, whose lengths the cells of this
    // layer read: its z-edges and diagonals end in no point of this region
    const int crushed_above = passes.measure(slab + 1, slab + 1 == plan.region.end ? kZEdges : kSpringFamilies);
    passes.cells(slab);
    passes.edge_tensions(slab);
    passes.gather(slab);
    ++slab;
    if (slab == plan.region.end || !plan.claim(slab)) break;
    crushed += crushed_above;  // the claimer of slab + 1 counts them
  }
  return {first, slab};
}

// Sweeps down from the region's last layer while it claims layers; returns those it gathered.
// The gather of a layer reads the springs that start in it and in the layer below, and the
// x- and y-edges' tensions the cells on both sides of them: the passes of the layer below come
// first, then the x- and y-edges of this layer. The first layer's z-edges, which go up into the
// region above, and the cells they read, it computes itself.
Range sweep_down(const LayerPasses& passes, const ChunkPlan& plan, CopyWaits& waits, int& crushed) {
  int slab = plan.region.end - 1;
  if (slab < plan.region.begin || !plan.claim(slab)) return {slab + 1, slab + 1};
  waits.need(slab, slab + 3);
  (void)passes.measure(slab + 1, kZEdges);  // the x- and y-edges above, which the cells read
  crushed += passes.measure(slab);
  passes.cells(slab);
  passes.edge_tensions(slab, kZEdges);
  for (;;) {
    waits.need(slab - 1, slab + 2);
    const int crushed_below = passes.measure(slab - 1);  // the claimer of slab - 1 counts them
    passes.cells(slab - 1);
    passes.edge_tensions(slab - 1, kZEdges);
    passes.edge_tensions(slab, 0, kZEdges);
    passes.gather(slab);
    if (slab == plan.region.begin || !plan.claim(slab - 1)) break;
    --slab;
    crushed += crushed_below;
  }
  return {slab, plan.region.end};
}

// Chunk `chunk`'s share of the work (plan). Each chunk copies in the state of its layers, then
// runs the passes layer after layer in its own ring of temporaries (waiting for the other
// chunks' copies when it first reads one of their layers: copy_done). Then it finishes the nodes
// of the layers it gathered, whose forces are complete once its own gathers are: the kick when
// asked, without waiting to learn whether another chunk found a crushed cell (then the caller
// redoes the crushed cells' corners with their recovery, from the spring forces left in the
// grid), else the forces alone. (Another chunk's layers it reads, it reads after their copies;
// the nodes it kicks are of layers it read: so no chunk copies in a node another has kicked.)
// When timed, the chunk's time for its own work, not waiting, goes to results.seconds.
void run_chunk(const GridLayout& grid, const State& state, bool with_rate, const GridKick* kick,
               const GridScratch& scratch, const ChunkPlan& plan, int chunk, int chunks, bool timed,
               std::atomic<int>* copy_done, ChunkResults& results, Eigen::Matrix3Xd& forces) {
  const auto now = [timed] { return timed ? Clock::now() : Clock::time_point{}; };  // one thread: nothing to balance
  const auto start = now();
  const LayerArrays a = scratch.arrays(chunk);
  const Range copied = nodes_in_layers(grid, plan.copied);
  copy_in(grid, state.positions, a, kPosition, copied);
  if (with_rate) copy_in(grid, state.velocities, a, kVelocity, copied);
  CopyWaits waits(copy_done, chunks, plan.copied, grid.points.z(), timed);
  waits.mark_done(chunk);
  const LayerPasses passes{grid, a, with_rate};
  int crushed = 0;
  const Range gathered = plan.down ? sweep_down(passes, plan, waits, crushed) : sweep_up(passes, plan, waits, crushed);
  results.crushed[chunk] = crushed;
  results.gathered[chunk] = gathered;
  const Range nodes = nodes_in_layers(grid, gathered);
  if (kick != nullptr) {  // at once: if a cell turns out crushed, the caller redoes its corners
    const double* force[3] = {a.in(kForce, 0), a.in(kForce + 1, 0), a.in(kForce + 2, 0)};
    results.fastest_sq[chunk] =
        kick_grid_nodes(*kick, grid.point_of_node.data(), force, nodes.begin, nodes.end, forces);
  } else {
    copy_out(grid, a, kForce, nodes, forces);
  }
  results.seconds[chunk] = std::chrono::duration<double>(now() - start - waits.waited()).count();
}

// The even split for `chunks`: regions of cell layers in proportion to their threads (the last
// also takes the top layer of points, which has no cells), each pair meeting at its middle.
std::vector<int> even_split(const GridLayout& grid, int chunks) {
  std::vector<int> first(chunks + 1);
  for (int r = 0; r < num_regions(chunks); ++r) first[2 * r] = grid.cell_slabs * 2 * r / chunks;
  first[chunks] = grid.points.z();
  for (int r = 0; 2 * r + 1 < chunks; ++r) first[2 * r + 1] = (first[2 * r] + first[2 * r + 2]) / 2;
  return first;
}

// Whether `first` shares the grid's layers among `chunks`: regions of a layer of points at least
// (so each but the last a layer of cells), each pair's meeting point inside its region.
bool fits(const GridLayout& grid, const std::vector<int>& first, int chunks) {
  if (static_cast<int>(first.size()) != chunks + 1 || first.front() != 0 || first.back() != grid.points.z()) {
    return false;
  }
  for (int r = 0; r < num_regions(chunks); ++r) {
    const Range region = region_layers(first, r, chunks);
    if (region.begin >= region.end) return false;
    if (threads_in_region(r, chunks) == 2 && (first[2 * r + 1] < region.begin || first[2 * r + 1] > region.end)) {
      return false;
    }
  }
  return true;
}

// `split` if it fits, else the even split.
void prepare_split(const GridLayout& grid, int chunks, GridSplit& split) {
  const bool fitting = fits(grid, split.first_layers, chunks);
  if (fitting && static_cast<int>(split.seconds.size()) == num_regions(chunks)) return;
  if (!fitting) split.first_layers = even_split(grid, chunks);
  split.seconds.assign(num_regions(chunks), 0.0);
  split.calls = 0;
}

// Calls timed before a region's boundary may move: enough to see past a single slow step.
constexpr int kSplitCalls = 8;

// Records where each pair met (the layers its chunks copy in next); after kSplitCalls calls,
// moves the one boundary between neighbouring regions whose move by a layer (from the slower to
// the faster, a layer costing its region's time over its layers) shortens the slower of the two most; none when
// no move would (their times differ by less than about a layer's). Each region keeps a layer of
// points.
void balance_split(const ChunkResults& results, int chunks, GridSplit& split) {
  std::vector<int>& first = split.first_layers;
  for (int r = 0; 2 * r + 1 < chunks; ++r) first[2 * r + 1] = results.gathered[2 * r + 1].begin;
  const int regions = num_regions(chunks);
  // a region takes as long as the later of its threads: the two sweep it at once (a thread that
  // started late and claimed little must not make it look cheap, as their mean would)
  for (int r = 0; r < regions; ++r) {
    double seconds = 0.0;
    for (int c = 2 * r; c < 2 * r + threads_in_region(r, chunks); ++c) seconds = std::max(seconds, results.seconds[c]);
    split.seconds[r] += seconds;
  }
  if (++split.calls < kSplitCalls) return;
  int best_region = 0, best_step = 0;
  double best_gain = 0.0;
  for (int k = 0; k + 1 < regions; ++k) {
    const double lower = split.seconds[k], upper = split.seconds[k + 1];
    const Range lower_layers = region_layers(first, k, chunks), upper_layers = region_layers(first, k + 1, chunks);
    const int lower_count = lower_layers.end - lower_layers.begin, upper_count = upper_layers.end - upper_layers.begin;
    double gain = 0.0;
    int step = 0;
    if (lower > upper && lower_count > 1) {  // the lower region's top layer to the upper
      gain = lower - std::max(lower - lower / lower_count, upper + upper / upper_count);
      step = -1;
    } else if (upper > lower && upper_count > 1) {
      gain = upper - std::max(upper - upper / upper_count, lower + lower / lower_count);
      step = 1;
    }
    if (gain > best_gain) {
      best_gain = gain;
      best_region = k + 1;
      best_step = step;
    }
  }
  if (best_step != 0) {
    first[2 * best_region] += best_step;
    for (int r = best_region - 1; r <= best_region; ++r) {  // the meeting points stay in their regions
      if (threads_in_region(r, chunks) < 2) continue;
      const Range region = region_layers(first, r, chunks);
      first[2 * r + 1] = std::clamp(first[2 * r + 1], region.begin, region.end);
    }
  }
  split.seconds.assign(regions, 0.0);
  split.calls = 0;
}

}  // namespace

int grid_threads(const GridLayout& grid, int threads) {
  constexpr int kMinPointsPerThread = 1024;
  return std::max(1, std::min({threads, kMaxGridThreads, grid.cell_slabs, grid.num_points / kMinPointsPerThread}));
}

GridForces grid_spring_forces(const GridLayout& grid, const State& state, bool with_rate, int threads,
                              std::vector<double>& scratch, GridSplit& split, Eigen::Matrix3Xd& forces,
                              const GridKick* kick) {
  const int team = grid_threads(grid, threads);
  const GridScratch arrays(grid, team, scratch);
  const int num_nodes = static_cast<int>(grid.point_of_node.size());
  if (forces.cols() != num_nodes) forces.resize(3, num_nodes);
  prepare_split(grid, team, split);
  ChunkResults results;
  // shared by the chunks: each region's unclaimed layers, each chunk's copy done (set before the
  // threads start)
  std::array<std::atomic<int>, kMaxGridThreads> unclaimed, copy_done;
  for (int r = 0; r < num_regions(team); ++r) {
    const Range region = region_layers(split.first_layers, r, team);
    unclaimed[r].store(region.end - region.begin, std::memory_order_relaxed);
  }
  for (int c = 0; c < team; ++c) copy_done[c].store(0, std::memory_order_relaxed);
  bool as_planned = true;  // the runtime may give fewer threads (one without OpenMP; OMP_DYNAMIC)
  run_shares(team, [&](int chunk, int chunks, const auto&) {
    if (chunk == 0) as_planned = chunks == team;  // read after the region only
    // given fewer threads than planned: the even split for them, each pair meeting at its middle
    const std::vector<int> even = chunks == team ? std::vector<int>{} : even_split(grid, chunks);
    const std::vector<int>& first = chunks == team ? split.first_layers : even;
    const int region = chunk / 2;
    ChunkPlan plan;
    plan.region = region_layers(first, region, chunks);
    plan.copied = {first[chunk], first[chunk + 1]};
    plan.down = sweeps_down(chunk);
    if ((split.fixed || chunks != team) && threads_in_region(region, chunks) == 2) {
      plan.fixed_meet = first[2 * region + 1];
    } else if (split.fixed || chunks != team) {
      plan.fixed_meet = plan.region.end;
    } else {
      plan.unclaimed = &unclaimed[region];
    }
    run_chunk(grid, state, with_rate, kick, arrays, plan, chunk, chunks, chunks > 1, copy_done.data(), results, forces);
  });
  if (team > 1 && as_planned && !split.fixed) balance_split(results, team, split);
  GridForces out;
  out.crushed = results.total_crushed();
  for (double fastest_sq : results.fastest_sq) out.fastest_sq = faster(fastest_sq, out.fastest_sq);
  return out;
}

Eigen::Vector3d grid_spring_force(const GridLayout& grid, const std::vector<double>& scratch, int node) {
  const std::size_t point = static_cast<std::size_t>(grid.padding + grid.point_of_node[node]);
  const double* force = scratch.data() + LayerArrays::grid_stride(grid) * kForce + point;
  const std::size_t axis_stride = LayerArrays::grid_stride(grid);
  return {force[0], force[axis_stride], force[2 * axis_stride]};
}

}  // namespace cubespring
