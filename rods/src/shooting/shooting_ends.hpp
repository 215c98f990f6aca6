#pragma once
// Private to the shooting solver: how each end kind enters the shooting problem (unknowns at the base,
// residuals at the tip), see pcr/rods/shooting/rod_shooting.hpp for the equations.
#include "pcr/rods/rod_model.hpp"
#include "pcr/rods/shooting/rod_ode.hpp"

namespace pcr {
namespace shooting {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// The model with all loads scaled by lambda; if unloaded_tip is given (clamped base), a prescribed
/// tip pose moves from the unloaded tip pose (lambda = 0) to the prescribed one (lambda = 1).
RodModel model_at_load(const RodModel& model, double lambda, const RodStateVector* unloaded_tip);

/// Sets the base quantities that the base kind prescribes (p, R, n or m), keeping the unknown ones.
void enforce_base(const RodEnd& base, RodStateVector& y0);
/// A first guess of the base state (straight-rod statics), already satisfying enforce_base.
RodStateVector initial_base_guess(const RodModel& model);
/// Y(0): column 0 the base state, columns 1..6 its derivatives w.r.t. the six unknowns.
void base_tangents(const RodEnd& base, const RodStateVector& y0, RodStateWithTangents& Y);
/// y0 <- y0 moved by dz along the unknowns (multiplicative on rotations).
void retract_base(const RodEnd& base, const Vec6& dz, RodStateVector& y0);

/// Tip residual r (unscaled, SI units) of the tip kind at y(L).
Vec6 tip_residual(const RodEnd& tip, const RodStateVector& y);
/// dr/dz = dr/dy(L) Y(L) for the six tangent columns of Y.
Mat6 tip_residual_jacobian(const RodEnd& tip, const RodStateWithTangents& Y);
/// Divisors that make the residuals dimensionless: L, 1, F_c, M_c.
Vec6 residual_scale(const RodEnd& tip, const RodOde& ode);

/// Sizes of the base unknowns for the step cap: EI/L^2 for forces, EI/L for moments, L, 1 rad.
Vec6 unknown_scale(const RodEnd& base, const RodOde& ode);

/// Unit quaternion of the smallest rotation taking unit vector a to unit vector b.
Quat quat_between(const Vec3& a, const Vec3& b);

}  // namespace shooting
}  // namespace pcr
