#include "pcr/rods/obstacle.hpp"

#include <algorithm>
#include <cmath>

#include "pcr/core/error.hpp"

namespace pcr {

const char* to_string(ObstacleShape shape) {
  switch (shape) {
    case ObstacleShape::HalfSpace: return "half_space";
    case ObstacleShape::Sphere: return "sphere";
    case ObstacleShape::Capsule: return "capsule";
    case ObstacleShape::Cylinder: return "cylinder";
  }
  return "unknown";
}

void Obstacle::validate() const {
  const std::string who = std::string("obstacle '") + name + "' (" + to_string(shape) + ")";
  require(position.allFinite(), who, ": position (", position.transpose(), ") is not finite");
  if (shape == ObstacleShape::HalfSpace || shape == ObstacleShape::Cylinder) {
    require(direction.allFinite() && std::abs(direction.norm() - 1.0) <= 1e-9, who, ": ",
            shape == ObstacleShape::HalfSpace ? "normal" : "axis", " (", direction.transpose(),
            ") is not a unit vector");
  }
  if (shape != ObstacleShape::HalfSpace) {
    require(std::isfinite(radius) && radius > 0.0, who, ": radius = ", radius, " (must be > 0)");
  }
  if (shape == ObstacleShape::Capsule) {
    require(end.allFinite(), who, ": end (", end.transpose(), ") is not finite");
    require((end - position).norm() > 0.0, who, ": its two ends coincide (", end.transpose(),
            "); use a sphere");
  }
}

Obstacle Obstacle::transformed(const Mat3& rotation, const Vec3& translation) const {
  Obstacle o = *this;
  o.position = translation + rotation * position;
  o.end = translation + rotation * end;
  o.direction = rotation * direction;
  return o;
}

namespace {

// g = |v| - (R + r), nu = v / |v|, d nu / d p = (I - nu nu^T) / |v| dv/dp for a round obstacle whose
// centre point c(p) gives v = p - c(p) with the Jacobian dv/dp.
ObstacleGap round_gap(const Vec3& v, const Mat3& dv_dp, double radii) {
  ObstacleGap out;
  const double d = v.norm();
  out.gap = d - radii;
  if (d == 0.0) {  // on the centre or axis: nu undefined (deep inside the obstacle)
    out.normal = std::abs(dv_dp(2, 2)) > 0.5 ? Vec3::UnitZ() : Vec3::UnitX();
    return out;
  }
  out.normal = v / d;
  out.normal_derivative = (Mat3::Identity() - out.normal * out.normal.transpose()) * dv_dp / d;
  return out;
}

}  // namespace

ObstacleGap obstacle_gap(const Obstacle& o, const Vec3& p, double rod_radius) {
  switch (o.shape) {
    case ObstacleShape::HalfSpace: {
      ObstacleGap out;
      out.normal = o.direction;
      out.gap = o.direction.dot(p - o.position) - rod_radius;
      return out;
    }
    case ObstacleShape::Sphere: return round_gap(p - o.position, Mat3::Identity(), o.radius + rod_radius);
    case ObstacleShape::Cylinder: {
      const Mat3 P = Mat3::Identity() - o.direction * o.direction.transpose();  // projection normal to a
      return round_gap(P * (p - o.position), P, o.radius + rod_radius);
    }
    case ObstacleShape::Capsule: {
      const Vec3 e = o.end - o.position;
      const double t = (p - o.position).dot(e) / e.squaredNorm();
      if (t <= 0.0) return round_gap(p - o.position, Mat3::Identity(), o.radius + rod_radius);
      if (t >= 1.0) return round_gap(p - o.end, Mat3::Identity(), o.radius + rod_radius);
      const Mat3 P = Mat3::Identity() - e * e.transpose() / e.squaredNorm();
      return round_gap(p - o.position - t * e, P, o.radius + rod_radius);
    }
  }
  throw_input_error("obstacle '", o.name, "': unknown shape");
}

}  // namespace pcr
