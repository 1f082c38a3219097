// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "solve/grid_ldlt.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cubespring/static_solver.h"

namespace cubespring {
namespace {

// Parts this small are one front as they come.
constexpr std::size_t kSmallestPart = 16;

// Appends `nodes` to `order`, halves first and the plane between them last; `ends` gets where each
// front (a part too small to split, or a plane) ends.
void dissect(const Model& model, std::vector<int> nodes, std::vector<int>& order, std::vector<int>& ends) {
  const auto append = [&](const std::vector<int>& part) {
    if (part.empty()) return;
    order.insert(order.end(), part.begin(), part.end());
    ends.push_back(static_cast<int>(order.size()));
  };
  if (nodes.size() <= kSmallestPart) return append(nodes);
  Eigen::Vector3i lo = model.node_grid_index[nodes[0]], hi = lo;
  for (const int n : nodes) {
    lo = lo.cwiseMin(model.node_grid_index[n]);
    hi = hi.cwiseMax(model.node_grid_index[n]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  if (hi[axis] - lo[axis] < 2) return append(nodes);  // no plane with nodes on both sides
  // nodes are coupled only to nodes at most one index away (they share a cell), so the plane at
  // `middle` separates the two sides
  const int middle = (lo[axis] + hi[axis]) / 2;
  std::vector<int> below, plane, above;
  for (const int n : nodes) {
    const int at = model.node_grid_index[n][axis];
    (at < middle ? below : at == middle ? plane : above).push_back(n);
  }
  nodes.clear();
  nodes.shrink_to_fit();
  dissect(model, std::move(below), order, ends);
  dissect(model, std::move(above), order, ends);
  append(plane);
}

// In place, the unpivoted LDL^T of the dense symmetric block (lower triangle read): its strict
// lower part becomes L's, its diagonal D. False at a zero or non-finite pivot.
bool dense_ldlt(Eigen::Ref<Eigen::MatrixXd> a) {
  const Eigen::Index n = a.rows();
  // right-looking in panels: the panel by rank-1 steps, the rest by one matrix product
  constexpr Eigen::Index kPanel = 32;
  for (Eigen::Index k0 = 0; k0 < n; k0 += kPanel) {
    const Eigen::Index width = std::min(kPanel, n - k0);
    for (Eigen::Index k = k0; k < k0 + width; ++k) {
      const double d = a(k, k);
      if (d == 0.0 || !std::isfinite(d)) return false;
      const Eigen::Index below = n - k - 1;
      if (below == 0) break;
      // columns k+1 .. end of the panel only; the trailing matrix waits for the product below
      const Eigen::Index panel_rest = k0 + width - k - 1;
      Eigen::VectorXd column = a.col(k).tail(below);  // d l
      a.col(k).tail(below) /= d;
      for (Eigen::Index j = 0; j < panel_rest; ++j) {
        a.col(k + 1 + j).tail(below - j) -= column(j) * a.col(k).tail(below - j);
      }
    }
    const Eigen::Index rest = n - k0 - width;
    if (rest == 0) break;
    // trailing update: A22 -= L21 D L21^T (lower triangle used later; the product fills it all)
    auto l21 = a.block(k0 + width, k0, rest, width);
    const Eigen::MatrixXd scaled = l21 * a.diagonal().segment(k0, width).asDiagonal();
    a.bottomRightCorner(rest, rest).triangularView<Eigen::Lower>() -= scaled * l21.transpose();
  }
  return true;
}

// The fronts dissect() makes of a full box of nodes [lo, hi] inside the grid [0, top], with the
// cost of each: a front's own unknowns are its nodes' (3 a node), its update those of the nodes
// around its part that are eliminated later, which in a nested dissection are all the nodes one
// index outside the part (the planes that cut it off, or nothing at the grid's boundary).
void add_box_fronts(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi, const Eigen::Vector3i& top,
                    FactorisationCost& cost, double& largest_front) {
  const auto nodes = [](const Eigen::Vector3i& a, const Eigen::Vector3i& b) {
    return (b - a + Eigen::Vector3i::Ones()).cast<double>().prod();
  };
  const auto add_front = [&](double own_nodes) {
    const double around =
        nodes((lo - Eigen::Vector3i::Ones()).cwiseMax(0), (hi + Eigen::Vector3i::Ones()).cwiseMin(top)) - nodes(lo, hi);
    const double own = 3 * own_nodes, update = 3 * around, size = own + update;
    cost.factor_bytes += 8 * size * own;  // the front's columns of L, kept
    largest_front = std::max(largest_front, 8 * size * size);
    // its own block's LDL^T, the update's columns and the Schur complement
    cost.operations += own * own * own / 3 + own * own * update + own * update * update;
  };
  const double count = nodes(lo, hi);
  int axis = 0;
  const int extent = (hi - lo).maxCoeff(&axis);
  if (count <= static_cast<double>(kSmallestPart) || extent < 2) return add_front(count);
  const int middle = (lo[axis] + hi[axis]) / 2;
  Eigen::Vector3i below_hi = hi, above_lo = lo;
  below_hi[axis] = middle - 1;
  above_lo[axis] = middle + 1;
  add_box_fronts(lo, below_hi, top, cost, largest_front);
  add_box_fronts(above_lo, hi, top, cost, largest_front);
  Eigen::Vector3i plane_lo = lo, plane_hi = hi;
  plane_lo[axis] = plane_hi[axis] = middle;
  add_front(nodes(plane_lo, plane_hi));  // its part is the whole box: what surrounds the box
}

}  // namespace

std::vector<int> nested_dissection_order(const Model& model) {
  std::vector<int> nodes(model.num_nodes());
  std::iota(nodes.begin(), nodes.end(), 0);
  std::vector<int> order, ends;
  order.reserve(nodes.size());
  dissect(model, std::move(nodes), order, ends);
  return order;
}

GridLDLT::GridLDLT(const Model& model) : permutation_(3 * model.num_nodes()) {
  std::vector<int> nodes(model.num_nodes());
  std::iota(nodes.begin(), nodes.end(), 0);
  std::vector<int> order;
  order.reserve(nodes.size());
  dissect(model, std::move(nodes), order, front_ends_);
  for (std::size_t place = 0; place < order.size(); ++place) {
    for (int a = 0; a < 3; ++a) permutation_.indices()[3 * order[place] + a] = static_cast<int>(3 * place + a);
  }
}

void GridLDLT::analyse(const Eigen::SparseMatrix<double>& permuted) {
  fronts_.clear();
  int begin = 0;
  for (const int end_node : front_ends_) {
    Front front;
    front.begin = begin;
    front.end = 3 * end_node;
    begin = front.end;
    fronts_.push_back(std::move(front));
  }
  std::vector<int> front_of(permuted.rows());
  for (std::size_t f = 0; f < fronts_.size(); ++f) {
    std::fill(front_of.begin() + fronts_[f].begin, front_of.begin() + fronts_[f].end, static_cast<int>(f));
  }
  // a front's update: the later places its own columns reach, and its children's updates; its
  // parent is the front of the first of them
  std::vector<char> marked(permuted.rows(), 0);
  for (std::size_t f = 0; f < fronts_.size(); ++f) {
    Front& front = fronts_[f];
    const auto mark = [&](int place) {
      if (place >= front.end && !marked[place]) {
        marked[place] = 1;
        front.update.push_back(place);
      }
    };
    for (int col = front.begin; col < front.end; ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(permuted, col); it; ++it) mark(static_cast<int>(it.row()));
    }
    for (const int child : front.children) {
      for (const int place : fronts_[child].update) mark(place);
    }
    std::sort(front.update.begin(), front.update.end());
    for (const int place : front.update) marked[place] = 0;
    if (!front.update.empty()) fronts_[front_of[front.update.front()]].children.push_back(static_cast<int>(f));
  }
}

bool GridLDLT::factorise(const Eigen::SparseMatrix<double>& k, double shift) {
  Eigen::SparseMatrix<double> permuted;
  permuted = k.twistedBy(permutation_);
  if (!analysed_) {
    analyse(permuted);
    analysed_ = true;
  }
  pivots_.resize(permuted.rows());
  std::vector<int> local(permuted.rows(), -1);           // place -> row in the current front
  std::vector<Eigen::MatrixXd> updates(fronts_.size());  // Schur complements waiting for a parent
  for (std::size_t f = 0; f < fronts_.size(); ++f) {
    Front& front = fronts_[f];
    const int own = front.end - front.begin;
    const int size = own + static_cast<int>(front.update.size());
    for (int i = 0; i < own; ++i) local[front.begin + i] = i;
    for (std::size_t u = 0; u < front.update.size(); ++u) local[front.update[u]] = own + static_cast<int>(u);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(size, size);
    for (int col = front.begin; col < front.end; ++col) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(permuted, col); it; ++it) {
        if (it.row() >= col) dense(local[it.row()], col - front.begin) += it.value();
      }
      dense(col - front.begin, col - front.begin) += shift;
    }
    for (const int child : front.children) {  // extend-add, lower triangles
      const std::vector<int>& places = fronts_[child].update;
      const Eigen::MatrixXd& update = updates[child];
      for (std::size_t c = 0; c < places.size(); ++c) {
        for (std::size_t r = c; r < places.size(); ++r) {
          const int row = local[places[r]], column = local[places[c]];
          dense(std::max(row, column), std::min(row, column)) += update(r, c);
        }
      }
      updates[child] = Eigen::MatrixXd();
    }
    if (!dense_ldlt(dense.topLeftCorner(own, own))) return false;
    pivots_.segment(front.begin, own) = dense.diagonal().head(own);
    const int rest = size - own;
    if (rest > 0) {
      // X = A21 L11^-T; L21 = X D^-1; the update A22 - L21 D L21^T = A22 - L21 X^T
      auto a21 = dense.bottomLeftCorner(rest, own);
      dense.topLeftCorner(own, own).triangularView<Eigen::UnitLower>().transpose().solveInPlace<Eigen::OnTheRight>(a21);
      const Eigen::MatrixXd x = a21;
      a21 = x * pivots_.segment(front.begin, own).cwiseInverse().asDiagonal();
      updates[f] = dense.bottomRightCorner(rest, rest);
      updates[f].triangularView<Eigen::Lower>() -= a21 * x.transpose();
    }
    front.lower = dense.leftCols(own);
  }
  return true;
}

void GridLDLT::forward(Eigen::VectorXd& y) const {
  for (const Front& front : fronts_) {
    const int own = front.end - front.begin;
    auto head = y.segment(front.begin, own);
    front.lower.topRows(own).triangularView<Eigen::UnitLower>().solveInPlace(head);
    if (front.update.empty()) continue;
    const Eigen::VectorXd spread = front.lower.bottomRows(front.update.size()) * head;
    for (std::size_t u = 0; u < front.update.size(); ++u) y[front.update[u]] -= spread[static_cast<Eigen::Index>(u)];
  }
}

void GridLDLT::backward(Eigen::VectorXd& y) const {
  for (auto front = fronts_.rbegin(); front != fronts_.rend(); ++front) {
    const int own = front->end - front->begin;
    auto head = y.segment(front->begin, own);
    if (!front->update.empty()) {
      Eigen::VectorXd gathered(front->update.size());
      for (std::size_t u = 0; u < front->update.size(); ++u)
        gathered[static_cast<Eigen::Index>(u)] = y[front->update[u]];
      head -= front->lower.bottomRows(front->update.size()).transpose() * gathered;
    }
    front->lower.topRows(own).triangularView<Eigen::UnitLower>().transpose().solveInPlace(head);
  }
}

Eigen::VectorXd GridLDLT::solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd y = permutation_ * b;
  forward(y);
  y = y.cwiseQuotient(pivots_);
  backward(y);
  return permutation_.inverse() * y;
}

FactorisationCost estimate_block_factorisation(const Eigen::Vector3i& cells) {
  FactorisationCost cost;
  double largest_front = 0;
  add_box_fronts(Eigen::Vector3i::Zero(), cells, cells, cost, largest_front);
  cost.peak_bytes = cost.factor_bytes + largest_front;  // factorised in a square matrix of its own
  return cost;
}

double GridLDLT::factor_bytes() const {
  double bytes = 0;
  for (const Front& front : fronts_) bytes += 8.0 * static_cast<double>(front.lower.size());
  return bytes;
}

Eigen::VectorXd GridLDLT::pivot_direction(Eigen::Index i) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(pivots_.size());
  y[i] = 1.0;
  backward(y);
  return permutation_.inverse() * y;
}

}  // namespace cubespring
