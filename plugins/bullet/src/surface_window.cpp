// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "surface_window.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace cubespring::bullet {

namespace {

// The vertices and triangles of the surface within `region` (a vertex in it, or a triangle whose
// bounds meet it), with the triangles around each vertex taken and around each
// corner of a taken triangle (normals read them), and every corner of those; ascending.
void take_near(const Eigen::Matrix3Xd& vertices, const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology,
               const Eigen::AlignedBox3d& region, std::vector<int>& vertices_taken, std::vector<int>& triangles_taken) {
  const auto near = [&](const Eigen::AlignedBox3d& bounds) { return region.intersects(bounds); };
  std::vector<char> vertex_in(static_cast<std::size_t>(vertices.cols()), 0);
  std::vector<char> triangle_in(static_cast<std::size_t>(triangles.cols()), 0);
  const auto take_triangles_around = [&](int v) {
    for (int k = topology.vertex_offset[static_cast<std::size_t>(v)];
         k < topology.vertex_offset[static_cast<std::size_t>(v) + 1]; ++k) {
      triangle_in[static_cast<std::size_t>(topology.vertex_triangle[static_cast<std::size_t>(k)])] = 1;
    }
  };
  for (Eigen::Index v = 0; v < vertices.cols(); ++v) {
    const Eigen::Vector3d x = vertices.col(v);
    if (!near(Eigen::AlignedBox3d(x, x))) continue;
    vertex_in[static_cast<std::size_t>(v)] = 1;
    take_triangles_around(static_cast<int>(v));
  }
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    Eigen::AlignedBox3d bounds(vertices.col(triangles(0, t)));
    bounds.extend(vertices.col(triangles(1, t))).extend(vertices.col(triangles(2, t)));
    if (!near(bounds)) continue;
    triangle_in[static_cast<std::size_t>(t)] = 1;
    for (int k = 0; k < 3; ++k) take_triangles_around(triangles(k, t));
  }
  triangles_taken.clear();
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    if (!triangle_in[static_cast<std::size_t>(t)]) continue;
    triangles_taken.push_back(static_cast<int>(t));
    for (int k = 0; k < 3; ++k) vertex_in[static_cast<std::size_t>(triangles(k, t))] = 1;
  }
  vertices_taken.clear();
  for (Eigen::Index v = 0; v < vertices.cols(); ++v) {
    if (vertex_in[static_cast<std::size_t>(v)]) vertices_taken.push_back(static_cast<int>(v));
  }
}

}  // namespace

void SurfaceWindow::choose(const Eigen::Matrix3Xd& nodes, const Eigen::Matrix3Xd& vertices,
                           const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology,
                           const std::vector<ContactBox>& boxes) {
  std::vector<Eigen::AlignedBox3d> regions;
  for (const ContactBox& box : boxes) {
    const Eigen::Vector3d grow = Eigen::Vector3d::Constant(box.reach + margin_);
    regions.emplace_back(box.box.min() - grow, box.box.max() + grow);
  }
  // each box's part, then the whole window as their union (what take_near would take from all
  // the regions at once: each of its rules takes what any one region takes)
  box_vertices_.resize(boxes.size());
  box_triangles_.resize(boxes.size());
  box_bounds_.assign(boxes.size(), Eigen::AlignedBox3d());
  vertices_.clear();
  triangles_.clear();
  std::vector<int> merged;
  for (std::size_t b = 0; b < boxes.size(); ++b) {
    take_near(vertices, triangles, topology, regions[b], box_vertices_[b], box_triangles_[b]);
    for (const int v : box_vertices_[b]) box_bounds_[b].extend(vertices.col(v));
    merged.clear();
    std::set_union(vertices_.begin(), vertices_.end(), box_vertices_[b].begin(), box_vertices_[b].end(),
                   std::back_inserter(merged));
    vertices_.swap(merged);
    merged.clear();
    std::set_union(triangles_.begin(), triangles_.end(), box_triangles_[b].begin(), box_triangles_[b].end(),
                   std::back_inserter(merged));
    triangles_.swap(merged);
  }
  chosen_nodes_ = nodes;
  chosen_vertices_ = vertices;
  boxes_ = boxes;
  moved_ = 0.0;
  chosen_ = true;
}

const std::vector<int>& SurfaceWindow::vertices_near(const void* object) const {
  static const std::vector<int> none;
  const std::size_t b = box_of(object);
  return b < boxes_.size() ? box_vertices_[b] : none;
}

const std::vector<int>& SurfaceWindow::triangles_near(const void* object) const {
  static const std::vector<int> none;
  const std::size_t b = box_of(object);
  return b < boxes_.size() ? box_triangles_[b] : none;
}

Eigen::AlignedBox3d SurfaceWindow::bounds_near(const void* object) const {
  const std::size_t b = box_of(object);
  if (b == boxes_.size() || box_bounds_[b].isEmpty()) return {};
  const Eigen::Vector3d travel = Eigen::Vector3d::Constant(vertex_travel());
  return {box_bounds_[b].min() - travel, box_bounds_[b].max() + travel};
}

std::size_t SurfaceWindow::box_of(const void* object) const {
  const auto found =
      std::find_if(boxes_.begin(), boxes_.end(), [&](const ContactBox& box) { return box.object == object; });
  return static_cast<std::size_t>(found - boxes_.begin());
}

void SurfaceWindow::note_moved(const Eigen::Matrix3Xd& nodes) {
  if (!chosen_) return;
  moved_ = std::max(moved_, std::sqrt((nodes - chosen_nodes_).colwise().squaredNorm().maxCoeff()));
}

void SurfaceWindow::note_moved(const Eigen::Matrix3Xd& nodes, const std::vector<int>& which) {
  if (!chosen_) return;
  for (const int n : which) moved_ = std::max(moved_, (nodes.col(n) - chosen_nodes_.col(n)).norm());
}

bool SurfaceWindow::holds(const std::vector<ContactBox>& boxes) const {
  if (!chosen_) return false;
  // how far any box reaches past where its chosen one reached
  double grown = 0.0;
  for (const ContactBox& box : boxes) {
    const auto then = std::find_if(boxes_.begin(), boxes_.end(),
                                   [&](const ContactBox& chosen) { return chosen.object == box.object; });
    // a body whose kind of contact changed (its shape swapped) is read another way
    if (then == boxes_.end() || then->read_whole != box.read_whole) return false;
    const Eigen::Vector3d low = (then->box.min().array() - then->reach) - (box.box.min().array() - box.reach);
    const Eigen::Vector3d high = (box.box.max().array() + box.reach) - (then->box.max().array() + then->reach);
    grown = std::max({grown, low.maxCoeff(), high.maxCoeff()});
  }
  return spread_ * moved_ + grown < margin_;
}

}  // namespace cubespring::bullet
