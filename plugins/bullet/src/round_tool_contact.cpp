// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "round_tool_contact.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "cubespring/bullet/conversions.h"

namespace cubespring::bullet {
namespace {

// Two surface points this close [of the tool's radius] are one.
constexpr double kSamePoint = 1e-6;

Eigen::Vector3d surface_position(const Eigen::Matrix3Xd& positions, const Eigen::Matrix3Xi& triangles,
                                 const SurfacePoint& at) {
  return at.barycentric[0] * positions.col(triangles(0, at.triangle)) +
         at.barycentric[1] * positions.col(triangles(1, at.triangle)) +
         at.barycentric[2] * positions.col(triangles(2, at.triangle));
}

// The signed distance of x from the surface as seen from the surface point `at` nearest to it.
CoreContact signed_contact(const Eigen::Vector3d& x, const SurfacePoint& at, const Eigen::Matrix3Xd& positions,
                           const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology) {
  CoreContact contact;
  contact.surface = at;
  contact.core_point = x;
  const Eigen::Vector3d offset = x - surface_position(positions, triangles, at);
  const Eigen::Vector3d outward = pseudonormal(positions, triangles, topology, at);
  const double distance = offset.norm();
  const bool inside = offset.dot(outward) < 0.0;
  contact.signed_distance = inside ? -distance : distance;
  // on the surface the offset has no direction: the pseudonormal gives it
  contact.normal = distance > 0.0 ? Eigen::Vector3d((inside ? -offset : offset) / distance) : outward;
  return contact;
}

// A core that crosses the surface: its deepest point inside, among its ends and points between
// (a tool's tip is an end).
CoreContact deepest_inside(const RoundCore& core, const std::vector<int>& candidates, const Eigen::Matrix3Xd& positions,
                           const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology) {
  constexpr int kSamples = 8;
  std::optional<CoreContact> deepest;
  for (int i = 0; i <= kSamples; ++i) {
    const Eigen::Vector3d x = core.from + (static_cast<double>(i) / kSamples) * (core.to - core.from);
    SurfacePoint at;
    double distance = std::numeric_limits<double>::infinity();
    for (const int t : candidates) {
      const Eigen::Vector3d a = positions.col(triangles(0, t)), b = positions.col(triangles(1, t)),
                            c = positions.col(triangles(2, t));
      const Eigen::Vector3d w = closest_barycentric(x, a, b, c);
      const double d = (w[0] * a + w[1] * b + w[2] * c - x).norm();
      if (d < distance) {
        distance = d;
        at = {t, w};
      }
    }
    const CoreContact contact = signed_contact(x, at, positions, triangles, topology);
    if (!deepest || contact.signed_distance < deepest->signed_distance) deepest = contact;
  }
  return *deepest;
}

}  // namespace

std::optional<RoundCore> round_core(const btCollisionShape& shape, const btTransform& transform) {
  const Eigen::Vector3d centre = to_eigen(transform.getOrigin());
  if (shape.getShapeType() == SPHERE_SHAPE_PROXYTYPE) {
    const auto& sphere = static_cast<const btSphereShape&>(shape);
    return RoundCore{centre, centre, static_cast<double>(sphere.getRadius())};
  }
  if (shape.getShapeType() == CAPSULE_SHAPE_PROXYTYPE) {
    const auto& capsule = static_cast<const btCapsuleShape&>(shape);
    const Eigen::Vector3d axis = to_eigen(transform.getBasis().getColumn(capsule.getUpAxis()));
    const double half = capsule.getHalfHeight();
    return RoundCore{centre - half * axis, centre + half * axis, static_cast<double>(capsule.getRadius())};
  }
  return std::nullopt;
}

std::vector<int> outer_triangles_near(const RoundCore& core, const Eigen::Matrix3Xd& positions,
                                      const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology, double reach,
                                      const std::vector<int>* among) {
  const Eigen::Array3d lower = core.from.cwiseMin(core.to).array() - reach;
  const Eigen::Array3d upper = core.from.cwiseMax(core.to).array() + reach;
  std::vector<int> near;
  const auto consider = [&](int t) {
    if (!topology.outer[static_cast<std::size_t>(t)]) return;
    const Eigen::Vector3d a = positions.col(triangles(0, t)), b = positions.col(triangles(1, t)),
                          c = positions.col(triangles(2, t));
    if ((a.cwiseMax(b).cwiseMax(c).array() < lower).any() || (a.cwiseMin(b).cwiseMin(c).array() > upper).any()) {
      return;
    }
    near.push_back(t);
  };
  if (among != nullptr) {
    for (const int t : *among) consider(t);
  } else {
    for (Eigen::Index t = 0; t < triangles.cols(); ++t) consider(static_cast<int>(t));
  }
  return near;
}

std::vector<CoreContact> core_contacts(const RoundCore& core, const Eigen::Matrix3Xd& positions,
                                       const Eigen::Matrix3Xi& triangles, const SurfaceTopology& topology,
                                       const std::vector<int>& candidates, double reach, double believed_depth) {
  if (candidates.empty()) return {};

  // each candidate's nearest points to the core; the nearest of all tells whether the core is
  // outside the tissue
  std::vector<SegmentTriangleClosest> closest(candidates.size());
  std::size_t nearest = 0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const int t = candidates[i];
    closest[i] = closest_segment_triangle(core.from, core.to, positions.col(triangles(0, t)),
                                          positions.col(triangles(1, t)), positions.col(triangles(2, t)));
    if (closest[i].distance < closest[nearest].distance) nearest = i;
  }
  const auto contact_of = [&](std::size_t i) {
    return signed_contact(core.from + closest[i].along * (core.to - core.from), {candidates[i], closest[i].barycentric},
                          positions, triangles, topology);
  };
  const auto believed = [&](const CoreContact& contact) { return -contact.signed_distance <= believed_depth; };
  if (closest[nearest].distance == 0.0) {
    const CoreContact deepest = deepest_inside(core, candidates, positions, triangles, topology);
    if (deepest.signed_distance >= 0.0) return {contact_of(nearest)};
    if (believed(deepest)) return {deepest};
  }
  const CoreContact first = contact_of(nearest);
  if (first.signed_distance < 0.0 && believed(first)) return {first};
  if (!(first.signed_distance < reach)) return {first};

  // outside: every other part of the surface within reach that faces the core (the two walls of
  // a groove the tool sits in, say), each surface point once: neighbouring triangles find the same
  // point where it lies on the edge or corner they share
  // (an inside verdict not believed leaves the nearest point out: it is on the wrong side of a
  // fold, and the points around it that face the core hold it)
  // a surface point seen from behind (a fold's, or the far side of a part thinner than the tool)
  // within reach of a core outside the tissue is in the tool all the same: it leaves it away from
  // the core
  const auto away_from_core = [](CoreContact contact) {
    if (contact.signed_distance < 0.0) {
      contact.signed_distance = -contact.signed_distance;
      contact.normal = -contact.normal;
    }
    return contact;
  };
  const bool first_faces = first.signed_distance > 0.0;
  std::vector<CoreContact> contacts;
  std::vector<Eigen::Vector3d> found;
  if (first_faces) {
    contacts.push_back(first);
    found.push_back(surface_position(positions, triangles, first.surface));
  }
  const double same = kSamePoint * core.radius;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if ((first_faces && i == nearest) || !(closest[i].distance < reach)) continue;
    if (closest[i].distance == 0.0) continue;  // on the core: no way away from it
    const CoreContact contact = away_from_core(contact_of(i));
    const Eigen::Vector3d at = surface_position(positions, triangles, contact.surface);
    if (std::any_of(found.begin(), found.end(), [&](const Eigen::Vector3d& x) { return (x - at).norm() <= same; })) {
      continue;
    }
    found.push_back(at);
    contacts.push_back(contact);
  }
  return contacts;
}

}  // namespace cubespring::bullet
