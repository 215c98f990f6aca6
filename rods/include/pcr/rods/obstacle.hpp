#pragma once
// Rigid obstacles a rod may touch (docs/contact.md) and their gap functions for a rod of contact radius r
// (tube approximation: the rod's surface is the set of points within r of the centerline, exact for an
// unshearable rod with a circular section). For a centerline point p (world frame):
//   half-space {x: nu . (x - x0) <= 0}:  g = nu . (p - x0) - r,                nu the unit outward normal;
//   sphere (centre x0, radius R):         g = |p - x0| - R - r,                 nu = (p - x0) / |p - x0|;
//   capsule (segment x0 x1, radius R):    g = |p - x(t*)| - R - r, x(t*) the point of the segment
//                                         nearest to p, t* = clamp((p - x0) . e / |e|^2, 0, 1), e = x1 - x0;
//   cylinder (infinite, axis a through x0, radius R; a roller):  g = |(I - a a^T)(p - x0)| - R - r;
//   edge (sharp, radius 0): the line through x0 along a (g as the cylinder with R = 0), or with an end
//                           x1 the segment x0 x1 (g as the capsule with R = 0);
//   point (sharp, radius 0): g = |p - x0| - r;
//   roller (a finite cylinder with flat ends: centre x0, unit axis a, radius R, length W): with the radial
//                           and axial distances d_r = |(I - a a^T)(p - x0)| - R, d_a = |a . (p - x0)| - W /
//                           2: g = d_r - r beside the side (d_a <= 0), d_a - r beside an end face (d_r <= 0),
//                           sqrt(d_r^2 + d_a^2) - r from the rim (both > 0), max(d_r, d_a) - r inside.
// Sharp obstacles (edge, point) touch the rod at one section with a concentrated force (rod_contact.hpp).
// nu is the unit normal of the obstacle's surface at the contact, pointing from the obstacle to the rod;
// a frictionless contact force on the rod is lambda nu with lambda >= 0 (O'Reilly, "On steady motions of
// an elastic rod with application to contact problems", Int. J. Solids Struct. 34 (1997), §5-6).
#include <string>

#include "pcr/core/types.hpp"

namespace pcr {

enum class ObstacleShape { HalfSpace, Sphere, Capsule, Cylinder, Edge, Point, Roller };
const char* to_string(ObstacleShape shape);
/// Edge and point: zero radius, a concentrated contact force.
inline bool is_sharp(ObstacleShape shape) {
  return shape == ObstacleShape::Edge || shape == ObstacleShape::Point;
}

/// The contact law of a roller (docs/contact.md, "Rollers"): frictionless slip (a normal force only), or
/// adhesion (no slip: a prescribed material section of the rod is at the contact, with a normal and a
/// tangential force; rod_contact.hpp).
enum class RollerLaw { Slip, Adhesion };
const char* to_string(RollerLaw law);

struct Obstacle;
/// Sharp obstacles, those with point_contact and adhesive rollers: one concentrated force at one section.
bool concentrated_contact(const Obstacle& obstacle);
/// A roller with the adhesion law.
bool adhesive(const Obstacle& obstacle);

/// An obstacle's geometry in one frame (the world frame, or a link frame before the assembly places it).
struct Obstacle {
  std::string name;
  ObstacleShape shape = ObstacleShape::HalfSpace;
  Vec3 position = Vec3::Zero();    ///< half-space: a point of the plane; sphere: centre; capsule: x0;
                                   ///< cylinder: a point of the axis; edge: a point of the line or
                                   ///< its first end; point: the point; roller: its centre [m]
  Vec3 direction = Vec3::UnitZ();  ///< half-space: unit outward normal; cylinder, infinite edge,
                                   ///< roller: unit axis (unused else)
  Vec3 end = Vec3::Zero();         ///< capsule, finite edge: the other end x1 of its segment [m]
  bool finite = false;             ///< edge: the segment position-end (else the infinite line)
  double radius = 0.0;             ///< sphere, capsule, cylinder, roller [m] (> 0); edge, point: 0
  double length = 0.0;             ///< roller: its length along the axis [m] (> 0)
  /// Sphere, capsule, cylinder: the rod touches it at one section at most (a concentrated force at an
  /// unknown section, as a sharp obstacle; rod_contact.hpp) instead of a density at the midpoints.
  bool point_contact = false;
  RollerLaw law = RollerLaw::Slip;  ///< rollers only
  /// Adhesion: the arc length from the rod's start [m] of the material section that is at the roller's
  /// contact in the reference state (the initial guess: the contact direction nu_0 there, the roller's
  /// angle 0). The history of the motion sets it: an input of the state, not found by the solver.
  double stuck_section = 0.0;
  /// Adhesion: the roller's rotation [rad] about its axis (right-handed) since the reference state.
  double angle = 0.0;
  /// Adhesion: the section at the contact while the contact direction is the reference one,
  /// sigma_0 - R theta t . e with t . e = 1 (no-slip kinematics: rod_contact.hpp) [m].
  double adhesive_section() const { return stuck_section - radius * angle; }

  /// Throws InputError naming the obstacle and the value: non-finite numbers, a non-unit direction
  /// (|1 - |a|| > 1e-9), a non-positive radius, a capsule of zero length, point_contact on a half-space
  /// or a roller, adhesion on anything but a roller, a negative stuck section.
  void validate() const;
  /// The same obstacle in the parent frame of `rotation`, `translation` (x_parent = t + R x).
  Obstacle transformed(const Mat3& rotation, const Vec3& translation) const;
};

/// The offset v = p - c(p) of a centerline point p from the nearest point c(p) of a round obstacle's core
/// (sphere, point: the centre; capsule, finite edge: the segment; cylinder, infinite edge: the axis) and
/// its Jacobian dv/dp (I, or the projection normal to the axis / segment). Half-spaces and rollers have
/// none (their gap is piecewise: obstacle_gap).
struct ObstacleOffset {
  Vec3 offset = Vec3::Zero();
  Mat3 jacobian = Mat3::Identity();
};
ObstacleOffset obstacle_offset(const Obstacle& obstacle, const Vec3& p);

/// Gap g [m], unit normal nu and d nu / d p at a centerline point p of a rod of contact radius r.
struct ObstacleGap {
  double gap = 0.0;
  Vec3 normal = Vec3::UnitZ();
  Mat3 normal_derivative = Mat3::Zero();  ///< d nu / d p (0 for a half-space)
};
/// The gap function of the header's table. On the axis or at the centre of a round obstacle (where nu is
/// undefined; the rod's centerline is then deep inside it) nu is taken along the world z axis (or any
/// normal of the axis) and d nu / d p as 0.
ObstacleGap obstacle_gap(const Obstacle& obstacle, const Vec3& p, double rod_radius);

}  // namespace pcr
