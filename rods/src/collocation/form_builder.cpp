#include "form_builder.hpp"

#include <algorithm>
#include <cmath>

#include "pcr/math/quaternion.hpp"
#include "pcr/rods/drawn_rod.hpp"
#include "pcr/rods/end_axes.hpp"
#include "pcr/splines/basis.hpp"
#include "unit_quaternion_rows.hpp"

namespace pcr::collocation {

FormBuilder::FormBuilder(const CollocationRod& rod, Problem& problem, const RodVariables& vars,
                         const RodEndOptions& ends, double load_factor)
    : rod_(rod),
      problem_(problem),
      vars_(vars),
      ends_(ends),
      load_factor_(load_factor),
      tau_(rod.knots().greville()) {}

PointConstants FormBuilder::constants_at(double u) const {
  const RodModel& model = rod_.model();
  const double L = model.length;
  PointConstants c;
  c.k_se = model.shear_extension_stiffness;
  c.k_bt = model.bending_torsion_stiffness;
  c.length_scale = L;
  c.force_scale = rod_.force_scale();
  c.moment_scale = rod_.moment_scale();
  const double s = u * L;
  model.intrinsic.at(s, c.eps0, c.kappa0);
  if (model.intrinsic.varying) {
    // s-derivatives of the intrinsic strains by central differences (h = 1e-5 L: error ~1e-10 of the
    // strain variation scale); one-sided at the ends.
    const double h = 1e-5 * L, sa = std::max(0.0, s - h), sb = std::min(L, s + h);
    Vec3 ea, ka, eb, kb;
    model.intrinsic.at(sa, ea, ka);
    model.intrinsic.at(sb, eb, kb);
    c.eps0_s = load_factor_ * (eb - ea) / (sb - sa);
    c.kappa0_s = load_factor_ * (kb - ka) / (sb - sa);
  }
  c.eps0 *= load_factor_;
  c.kappa0 *= load_factor_;
  // Drawn rods: the effective constants (M4) of the unknowns N, M (drawn_rod.hpp; uniform rods only, so
  // eps0_s = kappa0_s = 0). Nothing changes at c = 0.
  drawn_flux(model, c.flux_force, c.flux_moment);
  apply_drawn_constants(c.flux_force, c.flux_moment, c.k_se, c.k_bt, c.eps0, c.kappa0);
  c.f = load_factor_ * model.distributed_force();
  c.l = load_factor_ * model.loads.moment_per_length;
  return c;
}

PointBasis FormBuilder::basis_at(double u, int max_derivative) const {
  const int p = rod_.discretization().degree;
  const BasisDerivatives d = basis_derivatives(rod_.knots(), u, max_derivative);
  PointBasis b;
  b.first = d.first;
  b.count = p + 1;
  b.B.assign(p + 1, {});
  for (int k = 0; k <= max_derivative; ++k)
    for (int i = 0; i <= p; ++i) b.B[i][k] = d.values(k, i);
  return b;
}

PointBasis FormBuilder::end_basis(bool at_tip) const {
  PointBasis b;
  b.first = at_tip ? num_control_points() - 1 : 0;
  b.count = 1;
  b.B.assign(1, {});
  b.B[0][0] = 1.0;
  return b;
}

EndData FormBuilder::end_data(bool at_tip) const {
  const RodEnd& end = at_tip ? rod_.model().tip : rod_.model().base;
  EndData e;
  e.kind = end.kind;
  e.target.position = end.position;
  e.target.orientation = end.orientation.normalized();
  e.target.frame = rotation_matrix(e.target.orientation);
  e.target.axes = joint_axes(end.axis);
  // n, m are the force and moment of the part s+ on s-: an applied load is -(F, M) at the base.
  const double sign = at_tip ? 1.0 : -1.0;
  e.loads.n_bar = sign * load_factor_ * end.force;
  e.loads.m_bar = sign * load_factor_ * end.moment;
  return e;
}

std::string FormBuilder::end_kind(bool at_tip) const {
  return std::string("rod.end_") + to_string(at_tip ? rod_.model().tip.kind : rod_.model().base.kind);
}

// "<rod>@u=0.123456": u in [0, 1] with six decimals, as std::to_string prints it, written by hand (the
// printf of std::to_string was 3 % of a cold solve's instructions: one name per residual block).
std::string FormBuilder::where(double u) const {
  const std::string& name = rod_.model().name;
  if (!(u >= 0.0 && u <= 1.0)) return name + "@u=" + std::to_string(u);
  const long micro = std::lround(u * 1e6);  // 0 .. 1000000
  char digits[9] = {static_cast<char>('0' + micro / 1000000), '.'};
  for (int k = 7, rest = static_cast<int>(micro % 1000000); k >= 2; --k, rest /= 10)
    digits[k] = static_cast<char>('0' + rest % 10);
  digits[8] = '\0';
  std::string out;
  out.reserve(name.size() + 11);
  out.append(name).append("@u=").append(digits, 8);
  return out;
}

void FormBuilder::add_unit_quaternion_rows(const PointLayout& layout) const {
  // Blocks of kRowsPerBlock consecutive abscissae: the Problem's per-block overhead is shared by their
  // rows, and a block's dense Jacobian (rows x its control points) stays small on fine meshes.
  constexpr int kRowsPerBlock = 8;
  const int last_row = num_control_points() - 2;  // rows at tau_1 .. tau_{n-2}
  for (int j0 = 1; j0 <= last_row; j0 += kRowsPerBlock) {
    const int j1 = std::min(last_row, j0 + kRowsPerBlock - 1);
    std::vector<PointBasis> bases;
    for (int j = j0; j <= j1; ++j) bases.push_back(basis_at(tau_[j], 0));
    const int first = bases.front().first;
    const int end = bases.back().first + bases.back().count;
    for (PointBasis& b : bases) b.first -= first;  // relative to the block's first control point
    std::vector<VariableId> points(vars_.control_points.begin() + first, vars_.control_points.begin() + end);
    problem_.add_residual_block(make_unit_quaternion_rows(
        where(tau_[j0]), std::move(points), rod_.control_point_size(), layout.q, std::move(bases)));
  }
}

}  // namespace pcr::collocation
