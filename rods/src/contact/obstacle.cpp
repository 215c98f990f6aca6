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
    case ObstacleShape::Edge: return "edge";
    case ObstacleShape::Point: return "point";
    case ObstacleShape::Roller: return "roller";
  }
  return "unknown";
}

const char* to_string(RollerLaw law) {
  return law == RollerLaw::Adhesion ? "adhesion" : "slip";
}

bool adhesive(const Obstacle& o) {
  return o.law == RollerLaw::Adhesion;
}

bool concentrated_contact(const Obstacle& o) {
  return is_sharp(o.shape) || o.point_contact || adhesive(o);
}

void Obstacle::validate() const {
  const std::string who = std::string("obstacle '") + name + "' (" + to_string(shape) + ")";
  require(position.allFinite(), who, ": position (", position.transpose(), ") is not finite");
  const bool infinite_edge = shape == ObstacleShape::Edge && !finite;
  if (shape == ObstacleShape::HalfSpace || shape == ObstacleShape::Cylinder || infinite_edge ||
      shape == ObstacleShape::Roller) {
    require(direction.allFinite() && std::abs(direction.norm() - 1.0) <= 1e-9, who, ": ",
            shape == ObstacleShape::HalfSpace ? "normal" : "axis", " (", direction.transpose(),
            ") is not a unit vector");
  }
  if (is_sharp(shape)) {
    require(radius == 0.0, who, ": radius = ", radius, " (a sharp obstacle has none)");
  } else if (shape != ObstacleShape::HalfSpace) {
    require(std::isfinite(radius) && radius > 0.0, who, ": radius = ", radius, " (must be > 0)");
  }
  require(!point_contact || shape == ObstacleShape::Sphere || shape == ObstacleShape::Capsule ||
              shape == ObstacleShape::Cylinder || is_sharp(shape),
          who, ": point contact is supported on spheres, capsules and cylinders only");
  if (shape == ObstacleShape::Roller) {
    require(std::isfinite(length) && length > 0.0, who, ": length = ", length, " (must be > 0)");
  }
  require(law == RollerLaw::Slip || shape == ObstacleShape::Roller, who,
          ": the adhesion law is defined for rollers only");
  if (law == RollerLaw::Adhesion) {
    require(std::isfinite(stuck_section) && stuck_section >= 0.0, who, ": stuck section = ", stuck_section,
            " m (must be >= 0)");
    require(std::isfinite(angle), who, ": angle = ", angle, " (not finite)");
  }
  if (shape == ObstacleShape::Capsule || (shape == ObstacleShape::Edge && finite)) {
    require(end.allFinite(), who, ": end (", end.transpose(), ") is not finite");
    require((end - position).norm() > 0.0, who, ": its two ends coincide (", end.transpose(), "); use a ",
            shape == ObstacleShape::Capsule ? "sphere" : "point");
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

ObstacleOffset obstacle_offset(const Obstacle& o, const Vec3& p) {
  ObstacleOffset out;
  const bool segment = o.shape == ObstacleShape::Capsule || (o.shape == ObstacleShape::Edge && o.finite);
  if (segment) {
    const Vec3 e = o.end - o.position;
    const double t = (p - o.position).dot(e) / e.squaredNorm();
    if (t <= 0.0) {
      out.offset = p - o.position;
    } else if (t >= 1.0) {
      out.offset = p - o.end;
    } else {
      out.jacobian -= e * e.transpose() / e.squaredNorm();
      out.offset = p - o.position - t * e;
    }
  } else if (o.shape == ObstacleShape::Cylinder || o.shape == ObstacleShape::Edge) {
    out.jacobian -= o.direction * o.direction.transpose();  // projection normal to the axis
    out.offset = out.jacobian * (p - o.position);
  } else {
    out.offset = p - o.position;  // sphere, point
  }
  return out;
}

// The roller's gap (obstacle.hpp): side, end face, rim or inside.
ObstacleGap roller_gap(const Obstacle& o, const Vec3& p, double rod_radius) {
  const Vec3& a = o.direction;
  const Mat3 P = Mat3::Identity() - a * a.transpose();  // projection normal to the axis
  const Vec3 w = p - o.position, radial = P * w;
  const double along = a.dot(w), rho = radial.norm();
  const double d_r = rho - o.radius, d_a = std::abs(along) - 0.5 * o.length;
  const Vec3 face_normal = along >= 0.0 ? a : Vec3(-a);
  if (d_r > 0.0 && d_a > 0.0) {  // nearest to the rim circle c = x0 + (W / 2) n_f + R e_r, e_r = radial / rho
    const Vec3 e_r = radial / rho;
    const Mat3 de_r = (Mat3::Identity() - e_r * e_r.transpose()) * P / rho;
    return round_gap(p - o.position - 0.5 * o.length * face_normal - o.radius * e_r,
                     Mat3::Identity() - o.radius * de_r, rod_radius);
  }
  if (d_a > d_r) {  // beside an end face (or inside, nearer to it)
    ObstacleGap out;
    out.gap = d_a - rod_radius;
    out.normal = face_normal;
    return out;
  }
  return round_gap(radial, P, o.radius + rod_radius);  // beside the side (or inside, nearer to it)
}

ObstacleGap obstacle_gap(const Obstacle& o, const Vec3& p, double rod_radius) {
  if (o.shape == ObstacleShape::Roller) return roller_gap(o, p, rod_radius);
  if (o.shape == ObstacleShape::HalfSpace) {
    ObstacleGap out;
    out.normal = o.direction;
    out.gap = o.direction.dot(p - o.position) - rod_radius;
    return out;
  }
  const ObstacleOffset v = obstacle_offset(o, p);
  return round_gap(v.offset, v.jacobian, o.radius + rod_radius);
}

}  // namespace pcr
