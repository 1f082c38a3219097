// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// Four passes over the grid's points, each a loop over whole z-layers of contiguous points that
// the compiler vectorises (compiled with -fopenmp-simd, -fno-math-errno and
// -fno-trapping-math, src/CMakeLists.txt):
//   1. springs, family by family: length, length rate, own tension; the diagonals (no
//      correction) their force at once, the edges their unit vector;
//   2. cells: mean edge strains -> correction tension per axis (docs/model-baudet2007.md
//      section 3); signed volume of the mean edge vectors -> crushed cells (section 5);
//   3. edges: force = (own tension + the correction of the up to 4 cells of the edge) x unit vector;
//   the exact-bending twist, by faces (below), when the body has it: its cells' coefficients in
//      pass 2 (from the corner positions the crushed test reads), its edge forces in pass 3b;
//   4. points: force = sum over families of the force of the springs that start there minus that
//      of those that end there (a gather: no two points write the same place, so threads share
//      nothing and the sums do not depend on the thread count).
// The passes run z-layer by z-layer, each as soon as its inputs are there, so that the arrays of
// a few layers are all the cache holds (all layers at once spill out of L2 from 32x8x8 on).
#include "grid_forces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "cubespring/forces.h"
#include "force_passes.h"
#include "thread_shares.h"
#include "vector_clones.h"

namespace cubespring {
namespace {

// Scratch arrays, each padded by grid.padding points on both sides.
enum Slot : int {
  kPosition = 0,                       // x, y, z
  kVelocity = 3,                       // x, y, z
  kForce = 6,                          // x, y, z
  kCellTension = 9,                    // x, y, z
  // per family x, y, z: the spring's force on its first end (edges: the unit vector until pass 3)
  kFamilyForce = 12,
  kEdgeLength = kFamilyForce + 3 * kSpringFamilies,
  kEdgeRate = kEdgeLength + kEdgeFamilies,
  kEdgeOwnTension = kEdgeRate + kEdgeFamilies,
  kEdgeVector = kEdgeOwnTension + kEdgeFamilies,  // x, y, z per edge family (twist only)
  kCellTwist = kEdgeVector + 3 * kEdgeFamilies,   // Q per face normal x, y, z (twist only)
  kSlots = kCellTwist + 3
};

class Arrays {
 public:
  Arrays(const GridLayout& grid, std::vector<double>& scratch)
      : stride_(static_cast<std::size_t>(grid.num_points + 2 * grid.padding)), padding_(grid.padding) {
    const std::size_t size = stride_ * kSlots;
    if (scratch.size() != size) {
      scratch.assign(size, 0.0);  // the padding and the points outside the body stay as set here
      base_ = scratch.data();
      for (int axis = 0; axis < 3; ++axis) {
        double* position = (*this)[kPosition + axis];
        for (int p = 0; p < grid.num_points; ++p) position[p] = grid.rest_points(axis, p);
      }
    }
    base_ = scratch.data();
  }
  double* operator[](int slot) const { return base_ + stride_ * static_cast<std::size_t>(slot) + padding_; }

 private:
  std::size_t stride_;
  int padding_;
  double* base_ = nullptr;
};

// The points of z-layer `slab` whose first `rows` y-rows a loop covers.
struct Range {
  int begin, end;
};
inline Range layer_range(const GridLayout& grid, int slab, int rows) {
  const int begin = slab * grid.stride_z;
  return {begin, begin + rows * grid.stride_y};
}

// Pass 1 for family f on one z-layer; kKeepVector: an edge family keeps its vectors (twist).
template <bool kWithRate, bool kDiagonal, bool kKeepVector>
CUBESPRING_VECTOR_CLONES void measure_family(const GridLayout& grid, int f, int slab, const Arrays& a) {
  const SpringFamily& family = grid.families[f];
  const Range range = layer_range(grid, slab, family.rows);
  const double* __restrict x = a[kPosition];
  const double* __restrict y = a[kPosition + 1];
  const double* __restrict z = a[kPosition + 2];
  const double* __restrict vx = a[kVelocity];
  const double* __restrict vy = a[kVelocity + 1];
  const double* __restrict vz = a[kVelocity + 2];
  double* __restrict fx = a[kFamilyForce + 3 * f];
  double* __restrict fy = a[kFamilyForce + 3 * f + 1];
  double* __restrict fz = a[kFamilyForce + 3 * f + 2];
  // edges keep their length, rate and own tension for the cells
  const int e = kDiagonal ? 0 : f;
  double* __restrict length_out = a[kEdgeLength + e];
  double* __restrict rate_out = a[kEdgeRate + e];
  double* __restrict own_out = a[kEdgeOwnTension + e];
  double* __restrict vector_x = a[kEdgeVector + 3 * e];
  double* __restrict vector_y = a[kEdgeVector + 3 * e + 1];
  double* __restrict vector_z = a[kEdgeVector + 3 * e + 2];
  const double* __restrict stiffness = family.stiffness.data();
  const double* __restrict damping = kWithRate ? family.damping.data() : nullptr;
  const double rest = family.rest_length;
  const double degenerate = kDegenerateLengthFraction * rest;
  const int from = family.from, to = family.to;
#pragma omp simd
  for (int g = range.begin; g < range.end; ++g) {
    const double ex = x[g + to] - x[g + from];
    const double ey = y[g + to] - y[g + from];
    const double ez = z[g + to] - z[g + from];
    const double length = std::sqrt(ex * ex + ey * ey + ez * ez);
    const double inverse = length > degenerate ? 1.0 / length : 0.0;
    double own = stiffness[g] * (length - rest);
    if constexpr (kWithRate) {
      const double rate = ((vx[g + to] - vx[g + from]) * ex + (vy[g + to] - vy[g + from]) * ey +
                           (vz[g + to] - vz[g + from]) * ez) * inverse;
      own += damping[g] * rate;
      if constexpr (!kDiagonal) rate_out[g] = rate;
    }
    if constexpr (kDiagonal) {
      const double q = own * inverse;
      fx[g] = q * ex;
      fy[g] = q * ey;
      fz[g] = q * ez;
    } else {
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
}

template <bool kWithRate>
void measure_springs(const GridLayout& grid, int f, int slab, const Arrays& a) {
  if (slab >= grid.families[f].slabs) return;
  if (f >= kEdgeFamilies) {
    measure_family<kWithRate, true, false>(grid, f, slab, a);
  } else if (grid.has_twist) {
    measure_family<kWithRate, false, true>(grid, f, slab, a);
  } else {
    measure_family<kWithRate, false, false>(grid, f, slab, a);
  }
}

// Sum over the 4 a-edges of the cell at g of values v of the edge family a: the a-edges start
// at corners 0, (1 << b), (1 << c), both (b, c the other axes), in that order (as in forces.cpp).
inline double edge_sum(const double* v, int g, int step_b, int step_c) {
  return (v[g] + v[g + step_b]) + (v[g + step_c] + v[g + step_b + step_c]);
}

// The twist of the exact-bending model (docs/model-exact-bending.md section 3; the same terms as
// src/twist.h, arranged by faces of the grid). A cell's two faces normal to d (in-plane axes
// a < c) have mean edge vectors a_s, c_s (s = lower, upper); w_d = (a_u . c_u - a_l . c_l) / h^2
// and Q_d = k h w_d / 2. The a-edges of a face get the force -Q_d c_l (lower face of the cell) or
// +Q_d c_u (upper face) on their lower corner, the c-edges -Q_d a_l or +Q_d a_u. A face is the
// upper face of one cell and the lower of the next along d, so an edge gets, from each face F it
// lies on, (Q_d[F - step d] - Q_d[F]) times the face's mean of its other in-plane edges.

// Q_d of a cell from 4 x its faces' dot products (cell_pass).
inline double twist_coefficient(double lower_4, double upper_4, double stiffness, double h) {
  const double lower = 0.25 * lower_4, upper = 0.25 * upper_4;
  return 0.5 * stiffness * h * ((upper - lower) / (h * h));
}

// Pass 2 on one z-layer of cells; returns its crushed cells. With kTwist, also the cells' twist
// coefficients (above), from the corner positions the crushed test reads anyway.
template <bool kWithRate, bool kTwist>
CUBESPRING_VECTOR_CLONES int cell_pass(const GridLayout& grid, int slab, const Arrays& a) {
  const Range range = layer_range(grid, slab, grid.cell_rows);
  const Eigen::Array3d inverse_edge_sum = (kEdgesPerAxis * grid.cell_size.array()).inverse();
  const Eigen::Array3d tension_per_stress = grid.cell_size.prod() * inverse_edge_sum;
  const double ix = inverse_edge_sum.x(), iy = inverse_edge_sum.y(), iz = inverse_edge_sum.z();
  const double tx = tension_per_stress.x(), ty = tension_per_stress.y(), tz = tension_per_stress.z();
  const double crushed_volume_64 = 64.0 * kCrushedVolumeFraction * grid.cell_size.prod();
  const int sy = grid.stride_y, sz = grid.stride_z;
  const double* __restrict lx = a[kEdgeLength];
  const double* __restrict ly = a[kEdgeLength + 1];
  const double* __restrict lz = a[kEdgeLength + 2];
  const double* __restrict rx = a[kEdgeRate];
  const double* __restrict ry = a[kEdgeRate + 1];
  const double* __restrict rz = a[kEdgeRate + 2];
  const double* __restrict dxx = grid.correction[0].data();
  const double* __restrict dyy = grid.correction[1].data();
  const double* __restrict dzz = grid.correction[2].data();
  const double* __restrict dxy = grid.correction[3].data();
  const double* __restrict dxz = grid.correction[4].data();
  const double* __restrict dyz = grid.correction[5].data();
  const double* __restrict beta = kWithRate ? grid.cell_beta.data() : nullptr;
  const double* __restrict occupied = grid.cell_occupied.data();
  double* __restrict tension_x = a[kCellTension];
  double* __restrict tension_y = a[kCellTension + 1];
  double* __restrict tension_z = a[kCellTension + 2];
  // the corners' positions, corner c at g + step(c) (model.h)
  const double* position[3] = {a[kPosition], a[kPosition + 1], a[kPosition + 2]};
  const int step[8] = {0, 1, sy, 1 + sy, sz, 1 + sz, sy + sz, 1 + sy + sz};
  int crushed = 0;
#pragma omp simd
  for (int g = range.begin; g < range.end; ++g) {
    double ex = edge_sum(lx, g, sy, sz) * ix - 1.0;
    double ey = edge_sum(ly, g, 1, sz) * iy - 1.0;
    double ez = edge_sum(lz, g, 1, sy) * iz - 1.0;
    if constexpr (kWithRate) {
      ex += beta[g] * (edge_sum(rx, g, sy, sz) * ix);
      ey += beta[g] * (edge_sum(ry, g, 1, sz) * iy);
      ez += beta[g] * (edge_sum(rz, g, 1, sy) * iz);
    }
    tension_x[g] = tx * (dxx[g] * ex + dxy[g] * ey + dxz[g] * ez);
    tension_y[g] = ty * (dxy[g] * ex + dyy[g] * ey + dyz[g] * ez);
    tension_z[g] = tz * (dxz[g] * ex + dyz[g] * ey + dzz[g] * ez);
  }
  // a loop of its own: together, the two need more vector registers than there are
  const double* __restrict twist_stiffness = kTwist ? grid.cell_twist.data() : nullptr;
  double* __restrict qx = a[kCellTwist];
  double* __restrict qy = a[kCellTwist + 1];
  double* __restrict qz = a[kCellTwist + 2];
  const double h = grid.cell_size.x();
#pragma omp simd reduction(+ : crushed)
  for (int g = range.begin; g < range.end; ++g) {
    // 4 x each mean edge vector: the sum of the cell's 4 edges along that axis
    double mean[3][3];  // [edge axis][component]
    // 4 x the dot products of the mean in-plane edge vectors of the faces normal to x, y, z,
    // lower and upper (twist_coefficient)
    double x_lower = 0.0, x_upper = 0.0, y_lower = 0.0, y_upper = 0.0, z_lower = 0.0, z_upper = 0.0;
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
      const double* p = position[c];
      const double p0 = p[g + step[0]], p1 = p[g + step[1]], p2 = p[g + step[2]], p3 = p[g + step[3]];
      const double p4 = p[g + step[4]], p5 = p[g + step[5]], p6 = p[g + step[6]], p7 = p[g + step[7]];
      mean[0][c] = ((p1 - p0) + (p3 - p2)) + ((p5 - p4) + (p7 - p6));
      mean[1][c] = ((p2 - p0) + (p3 - p1)) + ((p6 - p4) + (p7 - p5));
      mean[2][c] = ((p4 - p0) + (p5 - p1)) + ((p6 - p2) + (p7 - p3));
      if constexpr (kTwist) {  // a face's a-edges times its c-edges (a < c its in-plane axes)
        x_lower += ((p2 - p0) + (p6 - p4)) * ((p4 - p0) + (p6 - p2));
        x_upper += ((p3 - p1) + (p7 - p5)) * ((p5 - p1) + (p7 - p3));
        y_lower += ((p1 - p0) + (p5 - p4)) * ((p4 - p0) + (p5 - p1));
        y_upper += ((p3 - p2) + (p7 - p6)) * ((p6 - p2) + (p7 - p3));
        z_lower += ((p1 - p0) + (p3 - p2)) * ((p2 - p0) + (p3 - p1));
        z_upper += ((p5 - p4) + (p7 - p6)) * ((p6 - p4) + (p7 - p5));
      }
    }
    const double mxx = mean[0][0], mxy = mean[0][1], mxz = mean[0][2];
    const double myx = mean[1][0], myy = mean[1][1], myz = mean[1][2];
    const double mzx = mean[2][0], mzy = mean[2][1], mzz = mean[2][2];
    const double volume = mxx * (myy * mzz - myz * mzy) + mxy * (myz * mzx - myx * mzz) + mxz * (myx * mzy - myy * mzx);
    crushed += static_cast<int>((occupied[g] > 0.0) & (volume < crushed_volume_64));
    if constexpr (kTwist) {
      qx[g] = twist_coefficient(x_lower, x_upper, twist_stiffness[g], h);
      qy[g] = twist_coefficient(y_lower, y_upper, twist_stiffness[g], h);
      qz[g] = twist_coefficient(z_lower, z_upper, twist_stiffness[g], h);
    }
  }
  return crushed;
}

// Pass 3 for edge family f on one z-layer: the edge at g belongs to the cells at g, g - b, g - c,
// g - b - c (b, c the steps of the other two axes).
CUBESPRING_VECTOR_CLONES void edge_tension_pass(const GridLayout& grid, int f, int slab, const Arrays& a) {
  const SpringFamily& family = grid.families[f];
  if (slab >= family.slabs) return;
  const Range range = layer_range(grid, slab, family.rows);
  const int steps[3] = {1, grid.stride_y, grid.stride_z};
  const int b = steps[(f + 1) % 3], c = steps[(f + 2) % 3];
  const double* __restrict tension = a[kCellTension + f];
  const double* __restrict own = a[kEdgeOwnTension + f];
  double* __restrict fx = a[kFamilyForce + 3 * f];  // the unit vector, made the force
  double* __restrict fy = a[kFamilyForce + 3 * f + 1];
  double* __restrict fz = a[kFamilyForce + 3 * f + 2];
#pragma omp simd
  for (int g = range.begin; g < range.end; ++g) {
    const double total = own[g] + ((tension[g] + tension[g - b]) + (tension[g - c] + tension[g - b - c]));
    fx[g] *= total;
    fy[g] *= total;
    fz[g] *= total;
  }
}

// Pass 3b, twist only: the twist forces of the edges of family f on one z-layer, added to their
// forces. The edge along e at g lies on the faces normal to each other axis d at F = g and
// F = g - step o (o the third axis); the face's mean of its o-edges starts at F and F + step e.
CUBESPRING_VECTOR_CLONES void twist_edge_pass(const GridLayout& grid, int f, int slab, const Arrays& a) {
  const SpringFamily& family = grid.families[f];
  if (slab >= family.slabs) return;
  const Range range = layer_range(grid, slab, family.rows);
  const int steps[3] = {1, grid.stride_y, grid.stride_z};
  const int se = steps[f];
  // the two faces' normals d and third axes o: (f + 1, f + 2) and (f + 2, f + 1)
  const int d1 = (f + 1) % 3, d2 = (f + 2) % 3;
  const int s1 = steps[d1], s2 = steps[d2];
  const double* __restrict q1 = a[kCellTwist + d1];
  const double* __restrict q2 = a[kCellTwist + d2];
  const double* __restrict m1x = a[kEdgeVector + 3 * d2];  // o = d2 for the faces normal to d1
  const double* __restrict m1y = a[kEdgeVector + 3 * d2 + 1];
  const double* __restrict m1z = a[kEdgeVector + 3 * d2 + 2];
  const double* __restrict m2x = a[kEdgeVector + 3 * d1];
  const double* __restrict m2y = a[kEdgeVector + 3 * d1 + 1];
  const double* __restrict m2z = a[kEdgeVector + 3 * d1 + 2];
  double* __restrict fx = a[kFamilyForce + 3 * f];
  double* __restrict fy = a[kFamilyForce + 3 * f + 1];
  double* __restrict fz = a[kFamilyForce + 3 * f + 2];
#pragma omp simd
  for (int g = range.begin; g < range.end; ++g) {
    // normal d1: faces at g and g - s2; normal d2: faces at g and g - s1
    const double near1 = 0.5 * (q1[g - s1] - q1[g]), far1 = 0.5 * (q1[g - s2 - s1] - q1[g - s2]);
    const double near2 = 0.5 * (q2[g - s2] - q2[g]), far2 = 0.5 * (q2[g - s1 - s2] - q2[g - s1]);
    const int f1 = g - s2, f2 = g - s1;
    fx[g] += (near1 * (m1x[g] + m1x[g + se]) + far1 * (m1x[f1] + m1x[f1 + se])) +
             (near2 * (m2x[g] + m2x[g + se]) + far2 * (m2x[f2] + m2x[f2 + se]));
    fy[g] += (near1 * (m1y[g] + m1y[g + se]) + far1 * (m1y[f1] + m1y[f1 + se])) +
             (near2 * (m2y[g] + m2y[g + se]) + far2 * (m2y[f2] + m2y[f2 + se]));
    fz[g] += (near1 * (m1z[g] + m1z[g + se]) + far1 * (m1z[f1] + m1z[f1 + se])) +
             (near2 * (m2z[g] + m2z[g + se]) + far2 * (m2z[f2] + m2z[f2 + se]));
  }
}

// Pass 4 on one z-layer of points: each family's springs that start at g (at g - from) pull
// g towards their other end; those that end at g (at g - to) pull it back.
CUBESPRING_VECTOR_CLONES void gather_pass(const GridLayout& grid, int slab, const Arrays& a) {
  const Range range = layer_range(grid, slab, grid.points.y());
  int from[kSpringFamilies], to[kSpringFamilies];
  for (int f = 0; f < kSpringFamilies; ++f) {
    from[f] = grid.families[f].from;
    to[f] = grid.families[f].to;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const double* spring_force[kSpringFamilies];
    for (int f = 0; f < kSpringFamilies; ++f) spring_force[f] = a[kFamilyForce + 3 * f + axis];
    double* __restrict force = a[kForce + axis];
#pragma omp simd
    for (int g = range.begin; g < range.end; ++g) {
      double sum = 0.0;
#pragma GCC unroll 7
      for (int f = 0; f < kSpringFamilies; ++f) sum += spring_force[f][g - from[f]] - spring_force[f][g - to[f]];
      force[g] = sum;
    }
  }
}

// The passes of one z-layer each, in the order a layer's inputs become ready.
struct LayerPasses {
  const GridLayout& grid;
  const Arrays& a;
  bool with_rate;

  void measure(int slab) const {
    for (int f = 0; f < kSpringFamilies; ++f) {
      if (with_rate) {
        measure_springs<true>(grid, f, slab, a);
      } else {
        measure_springs<false>(grid, f, slab, a);
      }
    }
  }
  int cells(int slab) const {  // needs measure(slab) and measure(slab + 1)
    if (slab >= grid.cell_slabs) return 0;
    if (grid.has_twist) return with_rate ? cell_pass<true, true>(grid, slab, a) : cell_pass<false, true>(grid, slab, a);
    return with_rate ? cell_pass<true, false>(grid, slab, a) : cell_pass<false, false>(grid, slab, a);
  }
  void edge_tensions(int slab) const {  // needs cells(slab) and cells(slab - 1), measure(slab + 1)
    for (int f = 0; f < kEdgeFamilies; ++f) {
      edge_tension_pass(grid, f, slab, a);
      if (grid.has_twist) twist_edge_pass(grid, f, slab, a);
    }
  }
  void gather(int slab) const { gather_pass(grid, slab, a); }  // needs tensions of slab, slab - 1
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
void copy_in(const GridLayout& grid, const Eigen::Matrix3Xd& values, const Arrays& a, int slot, const Range& nodes) {
  for (int n = nodes.begin; n < nodes.end; ++n) {
    const int g = grid.point_of_node[n];
    for (int axis = 0; axis < 3; ++axis) a[slot + axis][g] = values(axis, n);
  }
}

void copy_out(const GridLayout& grid, const Arrays& a, int slot, const Range& nodes, Eigen::Matrix3Xd& values) {
  for (int n = nodes.begin; n < nodes.end; ++n) {
    const int g = grid.point_of_node[n];
    for (int axis = 0; axis < 3; ++axis) values(axis, n) = a[slot + axis][g];
  }
}

// At most this many threads share the grid passes (their results live on the stack: a step
// allocates nothing).
constexpr int kMaxGridThreads = 64;

// What the chunks share besides the arrays: their crushed cells, and their nodes' fastest
// squared speed when they kick.
struct ChunkResults {
  std::array<int, kMaxGridThreads> crushed{};
  std::array<double, kMaxGridThreads> fastest_sq{};
  int total_crushed() const {
    int total = 0;
    for (int c : crushed) total += c;
    return total;
  }
};

// Chunk `chunk` of `chunks` of the work; barrier() waits for every chunk. Each chunk takes a
// share of the z-layers and runs the passes layer after layer, so that a layer is still in
// cache when the next pass reads it. A chunk's first layer needs the layer before it (another
// chunk's last) for its edge tensions: they wait for the barrier after the layer loop. Its first
// two layers' gathers need those tensions, and those of the layer before, which is the previous
// chunk's first when that chunk has one layer: they wait for the barrier after the deferred
// tensions. Then each chunk finishes the nodes of its layers, whose forces are complete once its
// own gathers are, without waiting for the others: the kick when asked and no cell of the body
// is crushed (their recovery comes first, on the caller's side), else the forces alone.
template <typename Barrier>
void run_chunk(const GridLayout& grid, const State& state, bool with_rate, const GridKick* kick, const Arrays& a,
               int chunk, int chunks, const Barrier& barrier, ChunkResults& results, Eigen::Matrix3Xd& forces) {
  // chunks of equal cell layers (the top point layer has none, so the last chunk's is light);
  // the earlier chunks take the odd layer: the later ones have their first layers' deferred work
  const auto boundary = [&](int k) {
    return k == chunks ? grid.points.z() : (grid.cell_slabs * k + chunks - 1) / chunks;
  };
  const Range layers{boundary(chunk), boundary(chunk + 1)};
  const Range nodes = nodes_in_layers(grid, layers);
  copy_in(grid, state.positions, a, kPosition, nodes);
  if (with_rate) copy_in(grid, state.velocities, a, kVelocity, nodes);
  barrier();
  const LayerPasses passes{grid, a, with_rate};
  const bool first_chunk = chunk == 0;
  int crushed = 0;
  passes.measure(layers.begin);
  barrier();
  for (int slab = layers.begin; slab < layers.end; ++slab) {
    if (slab + 1 < layers.end) passes.measure(slab + 1);
    crushed += passes.cells(slab);
    if (first_chunk || slab > layers.begin) passes.edge_tensions(slab);
    if (first_chunk || slab > layers.begin + 1) passes.gather(slab);
  }
  results.crushed[chunk] = crushed;
  barrier();
  if (!first_chunk) passes.edge_tensions(layers.begin);
  barrier();
  if (!first_chunk) {
    passes.gather(layers.begin);
    if (layers.begin + 1 < layers.end) passes.gather(layers.begin + 1);
  }
  if (kick != nullptr && results.total_crushed() == 0) {
    const double* force[3] = {a[kForce], a[kForce + 1], a[kForce + 2]};
    results.fastest_sq[chunk] =
        kick_grid_nodes(*kick, grid.point_of_node.data(), force, nodes.begin, nodes.end, forces);
  } else {
    copy_out(grid, a, kForce, nodes, forces);
  }
}

}  // namespace

int grid_threads(const GridLayout& grid, int threads) {
  constexpr int kMinPointsPerThread = 4096;
  return std::max(1, std::min({threads, kMaxGridThreads, grid.cell_slabs, grid.num_points / kMinPointsPerThread}));
}

GridForces grid_spring_forces(const GridLayout& grid, const State& state, bool with_rate, int threads,
                              std::vector<double>& scratch, Eigen::Matrix3Xd& forces, const GridKick* kick) {
  const Arrays a(grid, scratch);
  const int num_nodes = static_cast<int>(grid.point_of_node.size());
  if (forces.cols() != num_nodes) forces.resize(3, num_nodes);
  const int team = grid_threads(grid, threads);
  ChunkResults results;
  run_shares(team, [&](int chunk, int chunks, const auto& barrier) {
    run_chunk(grid, state, with_rate, kick, a, chunk, chunks, barrier, results, forces);
  });
  GridForces out;
  out.crushed = results.total_crushed();
  out.kicked = kick != nullptr && out.crushed == 0;
  for (double fastest_sq : results.fastest_sq) out.fastest_sq = faster(fastest_sq, out.fastest_sq);
  return out;
}

}  // namespace cubespring
