// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
#include "rigid_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include <BulletCollision/CollisionShapes/btPolyhedralConvexShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>

#include "cubespring/bullet/conversions.h"
#include "hull_planes.h"
#include "surface_distance.h"

namespace cubespring::bullet {

namespace {

std::optional<Eigen::Vector3d> plane_push(const btStaticPlaneShape& plane, const btTransform& transform,
                                          const Eigen::Vector3d& point, const ContactReach& reach) {
  const Eigen::Vector3d normal = to_eigen(transform.getBasis() * plane.getPlaneNormal());
  const Eigen::Vector3d on_plane = to_eigen(transform * (plane.getPlaneNormal() * plane.getPlaneConstant()));
  const double height = (point - on_plane).dot(normal) - reach.offset;
  if (height > 0.0) return std::nullopt;
  return Eigen::Vector3d(std::max(-height, 0.0) * normal);
}

// A way out of a flat-faced shape: through the face of outward normal `normal`, `room` away [m].
struct Exit {
  double room;
  Eigen::Vector3d normal;
};

// The move out through one of `exits` (all the faces of a convex shape, in its frame). Inside a
// face the shortest way out is right, but at an edge it can be a side the tissue only brushes: a
// box sliding over tissue it has sunk into meets the next row of vertices with its leading face,
// and pushing them forward makes a wall of them. Which face presses on the tissue is told by the
// tissue's outward normal `surface_normal` there: the face through which that normal, followed
// inward, leaves the shape (least room / cos of the angle between the face normal and -normal).
// The move stays perpendicular to that face. Without a usable normal, the shortest way out.
// Only faces at most `max_detour` [m] farther than the nearest are taken: an edge pressed into
// the tissue has both its faces near, while a farther face is no edge this point is at, and the
// normal that names it may be a fold's (a tissue's side wall grazing a table's top, its normal
// tilted up, was thrown through the far side of the table; a node under a dropped box's bottom,
// the surface crumpled around it, was thrown out through the box's side, two cells away).
// The exits are [first, last): a box's six fit on the stack (a vector's allocation, once per
// vertex near a box and sub-step, cost more than the test).
// `local_normal()` gives the tissue's normal in the shape's frame: asked for only when a second
// face is within the detour.
template <class LocalNormal>
Eigen::Vector3d push_through(const Exit* first, const Exit* last, const LocalNormal& local_normal, double max_detour) {
  const Exit* shortest = first;
  for (const Exit* exit = first; exit != last; ++exit) {
    if (exit->room < shortest->room) shortest = exit;
  }
  int near_faces = 0;
  for (const Exit* exit = first; exit != last; ++exit) near_faces += exit->room <= shortest->room + max_detour ? 1 : 0;
  if (near_faces < 2) return shortest->room * shortest->normal;
  const Eigen::Vector3d surface_normal = local_normal();
  const Exit* pressed = nullptr;
  double pressed_reach = std::numeric_limits<double>::infinity();
  for (const Exit* exit_at = first; exit_at != last; ++exit_at) {
    const Exit& exit = *exit_at;
    const double cosine = -exit.normal.dot(surface_normal);
    if (cosine > 0.0 && exit.room <= shortest->room + max_detour && exit.room < pressed_reach * cosine) {
      pressed = &exit;
      pressed_reach = exit.room / cosine;
    }
  }
  const Exit& chosen = pressed != nullptr ? *pressed : *shortest;
  return chosen.room * chosen.normal;
}

// Out of a box centred at the origin (local frame), or nothing when outside.
template <class LocalNormal>
std::optional<Eigen::Vector3d> box_push(const Eigen::Vector3d& half, const Eigen::Vector3d& p,
                                        const LocalNormal& surface_normal, double max_detour) {
  const Eigen::Vector3d room = half - p.cwiseAbs();
  if ((room.array() <= 0.0).any()) return std::nullopt;
  std::array<Exit, 6> exits;
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? -1.0 : 1.0;
      exits[static_cast<std::size_t>(2 * axis + side)] = {half[axis] - sign * p[axis],
                                                          sign * Eigen::Vector3d::Unit(axis)};
    }
  }
  return push_through(exits.data(), exits.data() + exits.size(), surface_normal, max_detour);
}

// A cylinder about an axis: out through an end or the side, whose face here is its tangent plane.
template <class LocalNormal>
std::optional<Eigen::Vector3d> cylinder_push(double radius, double half_height, int axis, const Eigen::Vector3d& p,
                                             const LocalNormal& surface_normal, double max_detour) {
  Eigen::Vector3d radial = p;
  radial[axis] = 0.0;
  const double r = radial.norm();
  if (r >= radius || std::abs(p[axis]) >= half_height) return std::nullopt;
  const std::array<Exit, 3> exits{{{half_height - p[axis], Eigen::Vector3d::Unit(axis)},
                                   {half_height + p[axis], -Eigen::Vector3d::Unit(axis)},
                                   {radius - r, r > 0.0 ? Eigen::Vector3d(radial / r) : Eigen::Vector3d::Zero()}}};
  // on the axis the side has no direction
  return push_through(exits.data(), exits.data() + (r > 0.0 ? 3 : 2), surface_normal, max_detour);
}

std::optional<Eigen::Vector3d> capsule_push(double radius, double half_height, int axis, const Eigen::Vector3d& p) {
  Eigen::Vector3d nearest = Eigen::Vector3d::Zero();
  nearest[axis] = std::clamp(p[axis], -half_height, half_height);
  const Eigen::Vector3d away = p - nearest;
  const double distance = away.norm();
  if (distance >= radius) return std::nullopt;
  if (distance == 0.0) {
    Eigen::Vector3d push = Eigen::Vector3d::Zero();
    push[(axis + 1) % 3] = radius;
    return push;
  }
  return Eigen::Vector3d(away / distance * (radius - distance));
}

// A convex polyhedron by its hull's planes; any other convex shape by the hull of its support
// points. Hulls are asked once per vertex and sub-step: their planes are kept per shape, per
// thread, and rebuilt when the shape no longer has the support points it had (changed, or
// another shape at the same address).
template <class LocalNormal>
std::optional<Eigen::Vector3d> hull_push(const btConvexShape& shape, const Eigen::Vector3d& p,
                                         const LocalNormal& surface_normal, double offset, double max_detour) {
  struct Entry {
    Eigen::Matrix3d fingerprint = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
    std::vector<Eigen::Vector4d> planes;
  };
  thread_local std::map<const btConvexShape*, Entry> cache;
  Eigen::Matrix3d fingerprint;
  for (int axis = 0; axis < 3; ++axis) {
    btVector3 direction(0, 0, 0);
    direction[axis] = 1;
    fingerprint.col(axis) = to_eigen(shape.localGetSupportingVertex(direction));
  }
  Entry& entry = cache[&shape];
  if (entry.fingerprint != fingerprint) {
    std::vector<btVector3> points;
    if (shape.isPolyhedral()) {
      const auto& polyhedron = static_cast<const btPolyhedralConvexShape&>(shape);
      points.resize(static_cast<std::size_t>(polyhedron.getNumVertices()));
      for (int i = 0; i < polyhedron.getNumVertices(); ++i)
        polyhedron.getVertex(i, points[static_cast<std::size_t>(i)]);
    } else {
      points = support_points(shape);
    }
    entry = {fingerprint, hull_planes(points)};
  }
  if (entry.planes.empty()) return std::nullopt;
  std::vector<Exit> exits;
  for (const Eigen::Vector4d& plane : entry.planes) {
    const double room = plane.w() + offset - plane.head<3>().dot(p);
    if (room <= 0.0) return std::nullopt;
    exits.push_back({room, plane.head<3>()});
  }
  return push_through(exits.data(), exits.data() + exits.size(), surface_normal, max_detour);
}

// Each shape's own test on its dimensions grown by the offset.
std::optional<Eigen::Vector3d> convex_push(const btConvexShape& convex, const btTransform& transform,
                                           const Eigen::Vector3d& point, const SurfaceNormal& surface_normal,
                                           const ContactReach& reach) {
  const double offset = reach.offset;
  // exact inside tests in the shape's frame: Bullet's GJK signed distance is unreliable for
  // points deep inside a shape, which is where a projection needs it most
  const Eigen::Vector3d p = to_eigen(transform.invXform(to_bt(point)));
  const auto n = [&] { return to_eigen(transform.getBasis().transpose() * to_bt(surface_normal.get())); };
  std::optional<Eigen::Vector3d> push;
  switch (convex.getShapeType()) {
    case SPHERE_SHAPE_PROXYTYPE:
      push =
          capsule_push(static_cast<double>(static_cast<const btSphereShape&>(convex).getRadius()) + offset, 0.0, 2, p);
      break;
    case BOX_SHAPE_PROXYTYPE:
      push = box_push(to_eigen(static_cast<const btBoxShape&>(convex).getHalfExtentsWithMargin()).array() + offset, p,
                      n, reach.detour);
      break;
    case CAPSULE_SHAPE_PROXYTYPE: {
      const auto& capsule = static_cast<const btCapsuleShape&>(convex);
      push = capsule_push(static_cast<double>(capsule.getRadius()) + offset,
                          static_cast<double>(capsule.getHalfHeight()), capsule.getUpAxis(), p);
      break;
    }
    case CYLINDER_SHAPE_PROXYTYPE: {
      const auto& cylinder = static_cast<const btCylinderShape&>(convex);
      const int axis = cylinder.getUpAxis();
      const Eigen::Vector3d half = to_eigen(cylinder.getHalfExtentsWithMargin());
      push = cylinder_push(static_cast<double>(cylinder.getRadius()) + offset, half[axis] + offset, axis, p, n,
                           reach.detour);
      break;
    }
    default:  // convex hulls, cones, multi-spheres, scaled and user shapes
      push = hull_push(convex, p, n, offset, reach.detour);
      break;
  }
  if (!push) return std::nullopt;
  return Eigen::Vector3d(to_eigen(transform.getBasis() * to_bt(*push)));
}

// The nearest triangle of a concave mesh around a point, in the mesh's own frame.
class NearestTriangle : public btTriangleCallback {
 public:
  explicit NearestTriangle(const Eigen::Vector3d& point) : point_(point) {}
  void processTriangle(btVector3* corners, int, int) override {
    const Eigen::Vector3d a = to_eigen(corners[0]), b = to_eigen(corners[1]), c = to_eigen(corners[2]);
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.squaredNorm() == 0.0) return;
    const Eigen::Vector3d w = closest_barycentric(point_, a, b, c);
    const Eigen::Vector3d closest = w[0] * a + w[1] * b + w[2] * c;
    const double distance = (closest - point_).squaredNorm();
    if (distance >= best_distance_) return;
    best_distance_ = distance;
    closest_ = closest;
    normal_ = normal.normalized();
  }
  bool found() const { return best_distance_ < std::numeric_limits<double>::infinity(); }
  const Eigen::Vector3d& closest() const { return closest_; }
  const Eigen::Vector3d& normal() const { return normal_; }

 private:
  Eigen::Vector3d point_;
  double best_distance_ = std::numeric_limits<double>::infinity();
  Eigen::Vector3d closest_{0, 0, 0};
  Eigen::Vector3d normal_{0, 0, 1};
};

std::optional<Eigen::Vector3d> concave_push(const btConcaveShape& concave, const btTransform& transform,
                                            const Eigen::Vector3d& point, const ContactReach& reach) {
  const btTransform inverse = transform.inverse();
  const Eigen::Vector3d local = to_eigen(inverse * to_bt(point));
  NearestTriangle nearest(local);
  const double box = std::max(reach.thickness, reach.offset);
  concave.processAllTriangles(&nearest, to_bt(local - Eigen::Vector3d::Constant(box)),
                              to_bt(local + Eigen::Vector3d::Constant(box)));
  if (!nearest.found()) return std::nullopt;
  const double height = (local - nearest.closest()).dot(nearest.normal());
  if (height > reach.offset || height < -reach.thickness) return std::nullopt;
  if (height >= reach.offset) return Eigen::Vector3d::Zero();
  // to the offset surface: the nearest point, then out along its triangle's normal
  const Eigen::Vector3d target = nearest.closest() + reach.offset * nearest.normal();
  return Eigen::Vector3d(to_eigen(transform.getBasis() * to_bt(target - local)));
}

// Barycentric coordinates of a point of the triangle's plane.
Eigen::Vector3d barycentric_in_plane(const Eigen::Vector3d& point, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c, const Eigen::Vector3d& normal, double twice_area) {
  const double u = (c - b).cross(point - b).dot(normal) / twice_area;
  const double v = (a - c).cross(point - c).dot(normal) / twice_area;
  return {u, v, 1.0 - u - v};
}

// The deepest point of segment [p, q] behind the plane of triangle (a, b, c) (unit outward normal
// `normal`) among its points over the triangle: the segment clipped to the triangle's prism, whose
// depth is deepest at one end of what is left. Its depth and its foot on the plane.
std::optional<std::pair<double, Eigen::Vector3d>> segment_behind_triangle(const Eigen::Vector3d& p,
                                                                          const Eigen::Vector3d& q,
                                                                          const Eigen::Vector3d (&corners)[3],
                                                                          const Eigen::Vector3d& normal) {
  double first = 0.0, last = 1.0;
  const Eigen::Vector3d along = q - p;
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d& from = corners[e];
    const Eigen::Vector3d inward = normal.cross(corners[(e + 1) % 3] - from);  // towards the third corner
    const double at_p = inward.dot(p - from);
    const double rate = inward.dot(along);
    if (rate == 0.0) {
      if (at_p < 0.0) return std::nullopt;
      continue;
    }
    const double crossing = -at_p / rate;
    if (rate > 0.0) {
      first = std::max(first, crossing);
    } else {
      last = std::min(last, crossing);
    }
  }
  if (first > last) return std::nullopt;
  const Eigen::Vector3d at_first = p + first * along, at_last = p + last * along;
  const double depth_first = (corners[0] - at_first).dot(normal), depth_last = (corners[0] - at_last).dot(normal);
  const bool first_deeper = depth_first >= depth_last;
  const double depth = first_deeper ? depth_first : depth_last;
  return std::make_pair(depth, Eigen::Vector3d((first_deeper ? at_first : at_last) + depth * normal));
}

}  // namespace

double push_reach_beyond_bounds(const btCollisionShape& shape, const ContactReach& reach) {
  if (shape.isCompound()) {
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    double beyond = reach.offset;
    for (int child = 0; child < compound.getNumChildShapes(); ++child) {
      beyond = std::max(beyond, push_reach_beyond_bounds(*compound.getChildShape(child), reach));
    }
    return beyond;
  }
  return shape.isConvex() ? reach.offset : reach.offset + reach.thickness;
}

std::optional<Eigen::Vector3d> penetration_push(const btCollisionShape& shape, const btTransform& transform,
                                                const Eigen::Vector3d& point, const SurfaceNormal& surface_normal,
                                                const ContactReach& reach) {
  if (shape.getShapeType() == STATIC_PLANE_PROXYTYPE) {
    return plane_push(static_cast<const btStaticPlaneShape&>(shape), transform, point, reach);
  }
  if (shape.isCompound()) {
    // the deepest child decides; a point inside two children leaves the second one next sub-step
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    std::optional<Eigen::Vector3d> deepest;
    for (int child = 0; child < compound.getNumChildShapes(); ++child) {
      const std::optional<Eigen::Vector3d> push = penetration_push(
          *compound.getChildShape(child), transform * compound.getChildTransform(child), point, surface_normal, reach);
      if (push && (!deepest || push->squaredNorm() > deepest->squaredNorm())) deepest = push;
    }
    return deepest;
  }
  if (shape.isConvex()) {
    return convex_push(static_cast<const btConvexShape&>(shape), transform, point, surface_normal, reach);
  }
  if (shape.isConcave()) return concave_push(static_cast<const btConcaveShape&>(shape), transform, point, reach);
  return std::nullopt;
}

std::optional<FacePenetration> face_penetration(const btCollisionShape& shape, const btTransform& transform,
                                                const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                const Eigen::Vector3d& c, const ContactReach& reach) {
  if (shape.isCompound()) {
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    std::optional<FacePenetration> deepest;
    for (int child = 0; child < compound.getNumChildShapes(); ++child) {
      const std::optional<FacePenetration> found = face_penetration(
          *compound.getChildShape(child), transform * compound.getChildTransform(child), a, b, c, reach);
      if (found && (!deepest || found->depth > deepest->depth)) deepest = found;
    }
    return deepest;
  }
  if (!shape.isConvex()) return std::nullopt;
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  const double twice_area = cross.norm();
  if (twice_area == 0.0) return std::nullopt;
  const Eigen::Vector3d normal = cross / twice_area;
  // the shape's support point against the outward normal: its deepest point behind the plane
  const btVector3 local_direction = transform.getBasis().transpose() * to_bt(-normal);
  const Eigen::Vector3d deepest =
      to_eigen(transform * static_cast<const btConvexShape&>(shape).localGetSupportingVertex(local_direction));
  const double depth_of_shape = (a - deepest).dot(normal);
  const double depth = depth_of_shape + reach.offset;  // the grown shape reaches that much deeper
  if (depth <= 0.0 || depth > reach.thickness) return std::nullopt;
  // its foot on the plane must lie inside the triangle
  const Eigen::Vector3d foot = deepest + depth_of_shape * normal;
  const Eigen::Vector3d barycentric = barycentric_in_plane(foot, a, b, c, normal, twice_area);
  if ((barycentric.array() < 0.0).any()) return std::nullopt;
  return FacePenetration{barycentric, depth};
}

std::optional<std::vector<Eigen::Vector3d>> face_penetration_points(const btCollisionShape& shape,
                                                                    const btTransform& transform) {
  if (shape.getShapeType() != BOX_SHAPE_PROXYTYPE) return std::nullopt;
  // a box's support point is always one of its corners
  const Eigen::Vector3d half = to_eigen(static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin());
  std::vector<Eigen::Vector3d> corners;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d local((corner & 1) != 0 ? half.x() : -half.x(), (corner & 2) != 0 ? half.y() : -half.y(),
                                (corner & 4) != 0 ? half.z() : -half.z());
    corners.push_back(to_eigen(transform * to_bt(local)));
  }
  return corners;
}

std::vector<RigidEdge> box_edges(const btCollisionShape& shape, const btTransform& transform, double offset) {
  std::vector<RigidEdge> edges;
  if (shape.isCompound()) {
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    for (int child = 0; child < compound.getNumChildShapes(); ++child) {
      const std::vector<RigidEdge> more =
          box_edges(*compound.getChildShape(child), transform * compound.getChildTransform(child), offset);
      edges.insert(edges.end(), more.begin(), more.end());
    }
    return edges;
  }
  if (shape.getShapeType() != BOX_SHAPE_PROXYTYPE) return edges;
  const Eigen::Vector3d half =
      to_eigen(static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin()).array() + offset;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 4; ++side) {  // the four edges along the axis
      Eigen::Vector3d from;
      from[axis] = -half[axis];
      from[u] = (side & 1) != 0 ? half[u] : -half[u];
      from[v] = (side & 2) != 0 ? half[v] : -half[v];
      Eigen::Vector3d to = from;
      to[axis] = half[axis];
      edges.push_back({to_eigen(transform * to_bt(from)), to_eigen(transform * to_bt(to))});
    }
  }
  return edges;
}

std::optional<FacePenetration> edge_penetration(const RigidEdge& edge, const Eigen::Vector3d& a,
                                                const Eigen::Vector3d& b, const Eigen::Vector3d& c, double thickness) {
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  const double twice_area = cross.norm();
  if (twice_area == 0.0) return std::nullopt;
  const Eigen::Vector3d normal = cross / twice_area;
  const Eigen::Vector3d corners[3] = {a, b, c};
  const auto deepest = segment_behind_triangle(edge.from, edge.to, corners, normal);
  if (!deepest || !(deepest->first > 0.0 && deepest->first <= thickness)) return std::nullopt;  // NaN too
  return FacePenetration{barycentric_in_plane(deepest->second, a, b, c, normal, twice_area), deepest->first};
}

}  // namespace cubespring::bullet
