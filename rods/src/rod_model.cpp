#include "pcr/rods/rod_model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "pcr/core/error.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/rods/end_axes.hpp"

namespace pcr {
namespace {

using Twist = Eigen::Matrix<double, 6, 1>;

bool positive_finite(double v) {
  return std::isfinite(v) && v > 0.0;
}

void require_positive(const std::string& rod, const char* what, double v) {
  require(positive_finite(v), "rod '", rod, "': ", what, " must be positive and finite, got ", v);
}

void validate_end(const std::string& rod, const char* which, const RodEnd& end) {
  require(end.position.allFinite(), "rod '", rod, "': ", which, " position is not finite");
  require(end.orientation.allFinite() && end.orientation.norm() > 1e-12, "rod '", rod, "': ", which,
          " orientation quaternion must be finite and non-zero, got [", end.orientation.transpose(), "]");
  require(end.force.allFinite() && end.moment.allFinite(), "rod '", rod, "': ", which, " load is not finite");
  if (end.kind != RodEndKind::Universal && end.kind != RodEndKind::Revolute) return;
  require(end.axis.allFinite() && end.axis.norm() > 1e-12, "rod '", rod, "': ", which, " ",
          to_string(end.kind), " axis = [", end.axis.transpose(), "] must be a finite non-zero vector");
  require(end.kind != RodEndKind::Universal || sine_to_tangent(end.axis) >= kMinJointAxisSine, "rod '", rod,
          "': ", which, " universal axis = [", end.axis.transpose(),
          "] lies along the end frame's z axis (the rod tangent); the first joint axis must be normal to it");
}

// Rigid motions of the rod (twist [v at the world origin; w]) that the kinematic conditions of its two
// ends allow: rows [I, -hat(p)] for a held position, [0, B] for the blocked rotations B of the end's
// kind (blocked_rotations, with the rod frame at its prescribed frame). A non-zero null vector is a
// mechanism (e.g. a universal or revolute end with the other end free): the equilibrium is not unique.
Twist free_rigid_motion(const RodModel& m) {
  MatX C = MatX::Zero(12, 6);  // at most 6 rows per end; unused rows stay zero
  int row = 0;
  for (const RodEnd* end : {&m.base, &m.tip}) {
    if (end->kind == RodEndKind::Free) continue;
    const MatX B = blocked_rotations(end->kind, rotation_matrix(end->orientation.normalized()), end->axis);
    C.block<3, 3>(row, 0).setIdentity();
    C.block<3, 3>(row, 3) = -hat(end->position);
    C.block(row + 3, 3, B.rows(), 3) = B;
    row += 3 + static_cast<int>(B.rows());
  }
  const RightSingularVectors svd = right_singular_vectors(C);
  const VecX& sigma = svd.sigma;
  // Relative threshold as in the robot's rank check (platform_hold_check.cpp): exact dependencies give
  // ~1e-16 sigma_max, held rods ~ (shortest lever / longest) sigma_max.
  if (sigma[5] > 1e-9 * std::max(sigma[0], 1.0)) return Twist::Zero();
  Twist motion = svd.V.col(5);
  for (int k = 0; k < 6; ++k) motion[k] = std::abs(motion[k]) < 1e-12 ? 0.0 : motion[k];
  return motion;
}

}  // namespace

Material Material::from_poisson_ratio(double youngs_modulus, double poisson_ratio, double density) {
  require(poisson_ratio > -1.0 && poisson_ratio < 0.5, "Poisson ratio must lie in (-1, 0.5), got ",
          poisson_ratio);
  return Material{youngs_modulus, youngs_modulus / (2.0 * (1.0 + poisson_ratio)), density};
}

CrossSection CrossSection::circle(double radius) {
  require(positive_finite(radius), "circular section: radius must be positive and finite, got ", radius);
  CrossSection s;
  const double r2 = radius * radius;
  s.area = M_PI * r2;
  s.second_moment_1 = s.second_moment_2 = M_PI * r2 * r2 / 4.0;
  s.torsion_constant = M_PI * r2 * r2 / 2.0;
  s.shear_coefficient = 1.0;
  s.outer_radius = radius;
  return s;
}

CrossSection CrossSection::rectangle(double width, double height) {
  require(positive_finite(width), "rectangular section: width must be positive and finite, got ", width);
  require(positive_finite(height), "rectangular section: height must be positive and finite, got ", height);
  CrossSection s;
  s.area = width * height;
  s.second_moment_1 = width * height * height * height / 12.0;
  s.second_moment_2 = height * width * width * width / 12.0;
  const double a = std::max(width, height), b = std::min(width, height);
  const double ratio = b / a;
  s.torsion_constant = a * b * b * b * (1.0 / 3.0 - 0.21 * ratio * (1.0 - std::pow(ratio, 4) / 12.0));
  s.shear_coefficient = 5.0 / 6.0;
  s.outer_radius = 0.5 * std::hypot(width, height);
  return s;
}

const char* to_string(RodEndKind kind) {
  switch (kind) {
    case RodEndKind::Clamped: return "clamped";
    case RodEndKind::Collar: return "collar";
    case RodEndKind::Spherical: return "spherical";
    case RodEndKind::Universal: return "universal";
    case RodEndKind::Revolute: return "revolute";
    case RodEndKind::Free: return "free";
  }
  return "unknown";
}

void IntrinsicStrains::at(double s, Vec3& eps0, Vec3& kappa0) const {
  eps0 = shear_extension;
  kappa0 = curvature;
  if (varying) varying(s, eps0, kappa0);
}

bool IntrinsicStrains::is_zero() const {
  return !varying && shear_extension.isZero(0.0) && curvature.isZero(0.0);
}

void RodModel::set_material_and_section(const Material& material, const CrossSection& section) {
  require_positive(name, "Young's modulus E", material.youngs_modulus);
  require_positive(name, "shear modulus G", material.shear_modulus);
  require(std::isfinite(material.density) && material.density >= 0.0, "rod '", name,
          "': density must be non-negative and finite, got ", material.density);
  const double kGA = section.shear_coefficient * material.shear_modulus * section.area;
  shear_extension_stiffness = Vec3(kGA, kGA, material.youngs_modulus * section.area);
  bending_torsion_stiffness = Vec3(material.youngs_modulus * section.second_moment_1,
                                   material.youngs_modulus * section.second_moment_2,
                                   material.shear_modulus * section.torsion_constant);
  mass_per_length = material.density * section.area;
  outer_radius = section.outer_radius;
  youngs_modulus = material.youngs_modulus;
}

Vec3 RodModel::distributed_force() const {
  return mass_per_length * loads.gravity + loads.force_per_length;
}

void RodModel::validate() const {
  require_positive(name, "length", length);
  const char* se[] = {"shear stiffness kGA (d1)", "shear stiffness kGA (d2)", "axial stiffness EA"};
  const char* bt[] = {"bending stiffness EI1", "bending stiffness EI2", "torsional stiffness GJ"};
  for (int i = 0; i < 3; ++i) {
    require_positive(name, se[i], shear_extension_stiffness[i]);
    require_positive(name, bt[i], bending_torsion_stiffness[i]);
  }
  require(std::isfinite(mass_per_length) && mass_per_length >= 0.0, "rod '", name,
          "': mass per length must be non-negative and finite, got ", mass_per_length);
  require(
      loads.gravity.allFinite() && loads.force_per_length.allFinite() && loads.moment_per_length.allFinite(),
      "rod '", name, "': distributed loads are not finite");
  const std::string drawing = drawing_speed_problem();
  require(drawing.empty(), "rod '", name, "': ", drawing);
  validate_end(name, "base", base);
  validate_end(name, "tip", tip);
  require(holds_twist(base.kind, base.axis) || holds_twist(tip.kind, tip.axis), "rod '", name,
          "': end conditions (base ", to_string(base.kind), ", tip ", to_string(tip.kind),
          ") leave the rod free to move or twist about its tangent; clamp at least one end, or hold one by a "
          "universal coupling or a revolute coupling whose axis is not along the tangent");
  const Twist motion = free_rigid_motion(*this);
  require(motion.isZero(0.0), "rod '", name, "': end conditions (base ", to_string(base.kind), ", tip ",
          to_string(tip.kind), ") leave the rod free to move as a rigid body: v = [",
          motion.head<3>().transpose(), "] (at the world origin), w = [", motion.tail<3>().transpose(), "]");
}

std::string RodModel::drawing_speed_problem() const {
  std::ostringstream msg;
  const double c = drawing_speed;
  if (!std::isfinite(c)) {
    msg << "drawing_speed c = " << c << " m/s is not finite";
    return msg.str();
  }
  if (c == 0.0) return {};
  if (intrinsic.varying) {
    msg << "drawing_speed c = " << c << " m/s needs a uniform rod: steady axial motion is defined only for "
        << "material, section and intrinsic strains that do not vary along the rod, and this rod's "
        << "intrinsic strains vary with s";
    return msg.str();
  }
  // Admissibility (docs/design.md §1 "Drawn rods"): K_SE - rho A c^2 and K_BT - rho c^2 J_rho positive
  // definite, i.e. c below each limit speed sqrt(K_i / (rho A)), sqrt(K_BT,i / (rho J_rho,i)).
  double flux_force = 0.0;
  Vec3 flux_moment;
  drawn_flux(*this, flux_force, flux_moment);
  const char* se[] = {"shear stiffness kGA (d1)", "shear stiffness kGA (d2)", "axial stiffness EA"};
  const char* bt[] = {"bending stiffness EI1", "bending stiffness EI2", "torsional stiffness GJ"};
  for (int i = 0; i < 3; ++i) {
    const double k = shear_extension_stiffness[i];
    if (flux_force >= k) {
      msg << "drawing_speed c = " << c << " m/s is at or above the limit of the " << se[i] << " = " << k
          << " N: rho A c^2 = " << flux_force << " N must stay below it (|c| < "
          << std::sqrt(k / mass_per_length)
          << " m/s), else the effective stiffness K_SE - rho A c^2 is not positive definite";
      return msg.str();
    }
  }
  for (int i = 0; i < 3; ++i) {
    const double k = bending_torsion_stiffness[i];
    if (flux_moment[i] >= k) {
      msg << "drawing_speed c = " << c << " m/s is at or above the limit of the " << bt[i] << " = " << k
          << " N m^2: rho c^2 J_rho = " << flux_moment[i] << " N m^2 must stay below it (|c| < "
          << std::abs(c) * std::sqrt(k / flux_moment[i])
          << " m/s), else the effective stiffness K_BT - rho c^2 J_rho is not positive definite";
      return msg.str();
    }
  }
  return {};
}

double checked_arc_length(double s, double length, const std::string& who) {
  require(std::isfinite(s) && s >= -1e-12 * length && s <= length * (1.0 + 1e-12), who,
          ": arc length s = ", s, " outside [0, ", length, "]");
  return std::clamp(s, 0.0, length);
}

}  // namespace pcr
