// The condensed form (collocation_rod.hpp): n(s) = n - f s and
// m(s) = h - (p(s) - c) x n(s) - l s - A(s) x f, A(s) = integral_0^s (p - c) = L (I(u) - c u),
// I(u) = integral_0^u p du', with the rod's constant wrench block [n, h]. Rows:
//  - the 6 constitutive rows (constitutive_rows) at each of the n - 1 midpoints of consecutive Greville
//    abscissae, |q|^2 = 1 at the n - 2 interior abscissae, the 7 + 7 end conditions;
//  - with distributed loads also 3 rows per control point for its running integral T_i (below).
// Without loads: control points [P (3), Q (4)]; I is not needed.
// With loads: control points [P (3), Q (4), T (3)] with T_i = sum_{j < i} w_j P_j, w_j = integral_0^1 N_j,
// the integral of p carried by the basis functions before N_i. At u in a knot span whose active
// functions are N_k .. N_{k+p}, every N_j with j < k has its whole support below u, so
//   I(u) = sum_j J_j(u) P_j = T_k + sum_{i=k}^{k+p} J_i(u) P_i,   J_i(u) = integral_0^u N_i:
// each point reads only its p + 1 active control points (T of the first of them), and T is fixed by
// the local recurrence (rows "rod.integral", scaled by 1 / L0)
//   T_0 = 0,   T_{i+1} - T_i - w_i P_i = 0   (i = 0 .. n - 2).
// This is the same discrete solution as with I(u) summed over all control points, whose rows fill the
// rod's Jacobian block below the diagonal; here it stays banded (bandwidth about (p + 1) 10). Rods with at
// most CollocationRod::kMaxBandedCondensedPoints control points, where the square cost of the sum is still
// small, keep the sum over all control points (CondensedSummedForm: 7 unknowns per point, no T rows).
#include "condensed_jacobian.hpp"
#include "form_builder.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr::collocation {
namespace {

/// An end of the condensed form without the integral: n = n0, m = h - (p - c) x n (without loads, or at
/// the base, where s = 0 and I = 0).
struct CondensedEndZ {
  enum Entry { p, q, wrench, kEntries };
  static constexpr LocalLayout<kEntries> layout{
      {{{kCondensedPoint.p, 3, 0}, {kCondensedPoint.q, 4, 0}, {kDirect, kWrenchSize}}}};
};
static_assert(kCondensedPoint.p == kCondensedLoadedPoint.p && kCondensedPoint.q == kCondensedLoadedPoint.q,
              "CondensedEndZ serves both condensed layouts");

/// The tip of the condensed form with loads: the quantities of CondensedLoadedZ at u = 1, where
/// I(1) = T_{n-1} + w_{n-1} P_{n-1}.
struct CondensedLoadedTipZ {
  enum Entry { p, q, wrench, L, T_first, I_active, kEntries };
  static constexpr LocalLayout<kEntries> layout{{{{kCondensedLoadedPoint.p, 3, 0},
                                                  {kCondensedLoadedPoint.q, 4, 0},
                                                  {kDirect, kWrenchSize},
                                                  {kDirect, 1},
                                                  {kCondensedLoadedPoint.integral, 3, kSelected},
                                                  {kCondensedLoadedPoint.p, 3, kIntegral}}}};
};

void add_condensed_end(const FormBuilder& b, bool at_tip) {
  if (!b.adds_end(at_tip)) return;
  const double u = at_tip ? 1.0 : 0.0;
  const PointConstants c = b.constants_at(u);
  const EndData e = b.end_data(at_tip);
  const Vec3 c_point = b.rod().moment_point();
  b.add<CondensedEndZ, 7>(
      b.end_kind(at_tip), u, b.end_basis(at_tip), {b.vars().wrench}, [c, e, c_point](const auto& z, auto* r) {
        using T = typename std::decay_t<decltype(z)>::Scalar;
        using Z = CondensedEndZ;
        const V3<T> p = get<Z, Z::p>(z), n = get<Z, Z::wrench>(z).template head<3>();
        const V3<T> m = get<Z, Z::wrench>(z).template tail<3>() - (p - c_point.cast<T>()).cross(n);
        end_conditions<T>(e.kind, cast_target<T>(e.target), e.loads, c, p, get<Z, Z::q>(z), n, m, r);
      });
}

// The rows "rod.integral": T_0 = 0 (one control point) or T_{i+1} - T_i - w_i P_i = 0 (points i, i + 1),
// scaled by 1 / L0; linear, with a constant Jacobian.
class IntegralStepBlock final : public ResidualBlock {
 public:
  IntegralStepBlock(std::string name, std::vector<VariableId> points, double weight, double length_scale)
      : ResidualBlock("rod.integral", std::move(name), 3, std::move(points)),
        weight_(weight),
        scale_(1.0 / length_scale) {}

  int expected_variable_size(int) const override { return kCondensedLoadedPoint.size; }

  bool structural_nonzero(int k, int row, int column) const override {
    const int t = kCondensedLoadedPoint.integral, p = kCondensedLoadedPoint.p;
    return column == t + row || (k == 0 && is_step() && column == p + row);
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    const int t = kCondensedLoadedPoint.integral, p = kCondensedLoadedPoint.p,
              size = kCondensedLoadedPoint.size;
    for (int row = 0; row < 3; ++row) {
      residual[row] = is_step()
                          ? (values[1][t + row] - values[0][t + row] - weight_ * values[0][p + row]) * scale_
                          : values[0][t + row] * scale_;
    }
    if (jacobians == nullptr) return;
    for (size_t k = 0; k < variables().size(); ++k) {
      if (jacobians[k] == nullptr) continue;
      std::fill(jacobians[k], jacobians[k] + 3 * size, 0.0);
      const double sign = k == 0 && is_step() ? -1.0 : 1.0;
      for (int row = 0; row < 3; ++row) {
        jacobians[k][row * size + t + row] = sign * scale_;
        if (k == 0 && is_step()) jacobians[k][row * size + p + row] = -weight_ * scale_;
      }
    }
  }

 private:
  // A step T_{i+1} - T_i - w_i P_i (two control points), else T_0.
  bool is_step() const { return variables().size() == 2; }
  double weight_, scale_;
};

struct CondensedSummedTipZ {
  enum Entry { p, q, wrench, L, I, kEntries };
  static constexpr LocalLayout<kEntries> layout{{{{kCondensedPoint.p, 3, 0},
                                                  {kCondensedPoint.q, 4, 0},
                                                  {kDirect, kWrenchSize},
                                                  {kDirect, 1},
                                                  {kCondensedPoint.p, 3, kIntegral}}}};
};

// n(s), m(s) at u from a local vector with the entries p, wrench, L, I of Z.
template <typename Z, typename T, typename Local>
void condensed_summed_wrench(const Local& z, const PointConstants& c, const Vec3& moment_point, double u,
                             V3<T>& n, V3<T>& m) {
  condensed_wrench_from_integral<Z, T>(z, V3<T>(get<Z, Z::I>(z)), c, moment_point, u, n, m);
}

// The tip rows of a condensed form with loads: the end conditions with n(1), m(1) from
// tip_wrench(z, c, moment_point, n, m) on the local vector of TipZ (entries p, q and what tip_wrench reads).
template <typename TipZ, typename TipWrench>
void add_loaded_tip(const FormBuilder& b, const PointBasis& basis, const TipWrench& tip_wrench) {
  const PointConstants c = b.constants_at(1.0);
  const EndData e = b.end_data(true);
  const Vec3 c_point = b.rod().moment_point();
  b.add<TipZ, 7>(b.end_kind(true), 1.0, basis, {b.vars().wrench, b.vars().length},
                 [c, e, c_point, tip_wrench](const auto& z, auto* r) {
                   using T = typename std::decay_t<decltype(z)>::Scalar;
                   V3<T> n, m;
                   tip_wrench(z, c, c_point, n, m);
                   end_conditions<T>(e.kind, cast_target<T>(e.target), e.loads, c, get<TipZ, TipZ::p>(z),
                                     get<TipZ, TipZ::q>(z), n, m, r);
                 });
}

// The internal force and moment of a condensed form with loads at a sample point from its position p and
// I(u) = integral_0^u p du' (the forms hold I in different ways): n(s) = n - f s, condensed_moment.
void loaded_internal_wrench(const CollocationRod& rod, const VecX& x, const RodVariables& vars, const Vec3& p,
                            const Vec3& I, RodState& st) {
  const double L = rod.length(x, vars), u = st.s / L;
  PointConstants loads;
  loads.f = rod.model().distributed_force();
  loads.l = rod.model().loads.moment_per_length;
  st.force = x.segment<3>(vars.wrench_offset) - loads.f * (u * L);
  st.moment = condensed_moment<double>(p, st.force, x.segment<3>(vars.wrench_offset + 3), L, I, loads,
                                       rod.moment_point(), u);
}

void require_basis_integrals(const CollocationRod& rod, const BasisDerivatives& d) {
  require(static_cast<int>(d.integrals.size()) == rod.num_control_points(), "rod '", rod.model().name,
          "': sample basis without the basis integrals the condensed form with loads needs");
}

class CondensedForm final : public RodForm {
 public:
  const PointLayout& layout() const override { return kCondensedPoint; }
  int field_rows(int n) const override { return 7 * (n - 2) + 6; }

  void add_blocks(const FormBuilder& b) const override {
    const Vec3 c_point = b.rod().moment_point();
    for (int j = 0; j + 1 < b.num_control_points(); ++j) {
      const double u = b.midpoint(j);
      const PointConstants c = b.constants_at(u);
      const CondensedFieldKernel kernel{c, c_point};
      // Its constants (stiffnesses > 0 as factors, intrinsic strains and the moment point as addends)
      // cannot hide a dependency (point_block.hpp): one detection serves every rod of the process.
      static const KernelPattern<CondensedZ::layout.size(), 6> pattern =
          detect_kernel_pattern<CondensedZ::layout.size(), 6>(kernel);
      b.add<CondensedZ, 6>("rod.condensed_field", u, b.basis_at(u, 1), {b.vars().wrench, b.vars().length},
                           kernel, pattern);
    }
    b.add_unit_quaternion_rows(kCondensedPoint);
    add_condensed_end(b, false);
    add_condensed_end(b, true);
  }

  void internal_wrench(const CollocationRod& rod, const VecX& x, const RodVariables& vars,
                       const BasisDerivatives&, const PointValues&, RodState& st) const override {
    st.force = x.segment<3>(vars.wrench_offset);
    st.moment = x.segment<3>(vars.wrench_offset + 3) - (st.position - rod.moment_point()).cross(st.force);
  }
};

class CondensedLoadedForm final : public RodForm {
 public:
  const PointLayout& layout() const override { return kCondensedLoadedPoint; }
  int field_rows(int n) const override { return 10 * (n - 2) + 12; }

  void add_blocks(const FormBuilder& b) const override {
    const Vec3 c_point = b.rod().moment_point();
    const VariableId wrench = b.vars().wrench, L = b.vars().length;
    std::optional<KernelPattern<CondensedLoadedZ::layout.size(), 6>> pattern;
    for (int j = 0; j + 1 < b.num_control_points(); ++j) {
      const double u = b.midpoint(j);
      const PointConstants c = b.constants_at(u);
      b.add_detected<CondensedLoadedZ, 6>(
          "rod.condensed_field", u, with_integrals(b, b.basis_at(u, 1), u), {wrench, L},
          CondensedLoadedFieldKernel<CondensedLoadedZ>{c, c_point, u}, pattern);
    }
    b.add_unit_quaternion_rows(kCondensedLoadedPoint);
    add_integral_rows(b);
    add_condensed_end(b, false);
    if (!b.adds_end(true)) return;
    add_loaded_tip<CondensedLoadedTipZ>(
        b, with_integrals(b, b.end_basis(true), 1.0),
        [](const auto& z, const PointConstants& c, const Vec3& c_point, auto& n, auto& m) {
          condensed_loaded_wrench<CondensedLoadedTipZ>(z, c, c_point, 1.0, n, m);
        });
  }

  void internal_wrench(const CollocationRod& rod, const VecX& x, const RodVariables& vars,
                       const BasisDerivatives& d, const PointValues& value, RodState& st) const override {
    require_basis_integrals(rod, d);
    const int size = kCondensedLoadedPoint.size;
    // I(u) = T_k + sum_i J_i(u) P_i over the active control points k .. k + degree.
    Vec3 I = x.segment<3>(vars.control_point_offset + d.first * size + kCondensedLoadedPoint.integral);
    for (int i = 0; i <= rod.discretization().degree; ++i)
      I += d.integrals[d.first + i] * x.segment<3>(vars.control_point_offset + (d.first + i) * size);
    loaded_internal_wrench(rod, x, vars, value.segment<3>(kCondensedLoadedPoint.p), I, st);
  }

 private:
  // The basis b at u with the integrals J_i(u) of its functions (kIntegral) and T of its first control
  // point (kSelected).
  static PointBasis with_integrals(const FormBuilder& b, PointBasis basis, double u) {
    const int p = b.rod().discretization().degree;
    int first = 0;
    VecX J(p + 1);
    active_basis_integrals(b.rod().knots(), u, first, J);
    // The end basis (one control point) reads the last active function's integral.
    const int offset = basis.first - first;
    require(offset >= 0 && offset + basis.count <= p + 1, "condensed form: basis at u = ", u,
            " outside the active functions");
    for (int i = 0; i < basis.count; ++i) basis.B[i][kIntegral] = J[offset + i];
    basis.B[0][kSelected] = 1.0;
    return basis;
  }

  static void add_integral_rows(const FormBuilder& b) {
    const std::vector<VariableId>& cp = b.vars().control_points;
    const VecX w = basis_integrals(b.rod().knots(), 1.0);
    const std::string& name = b.rod().model().name;
    const double L0 = b.rod().length_scale();
    b.problem().add_residual_block(
        std::make_shared<IntegralStepBlock>(name + ".T0", std::vector<VariableId>{cp[0]}, 0.0, L0));
    for (size_t i = 0; i + 1 < cp.size(); ++i)
      b.problem().add_residual_block(std::make_shared<IntegralStepBlock>(
          name + ".T" + std::to_string(i + 1), std::vector<VariableId>{cp[i], cp[i + 1]}, w[i], L0));
  }
};

class CondensedSummedForm final : public RodForm {
 public:
  const PointLayout& layout() const override { return kCondensedPoint; }
  int field_rows(int n) const override { return 7 * (n - 2) + 6; }

  void add_blocks(const FormBuilder& b) const override {
    const Vec3 c_point = b.rod().moment_point();
    const VariableId wrench = b.vars().wrench, L = b.vars().length;
    std::optional<KernelPattern<CondensedSummedZ::layout.size(), 6>> pattern;
    for (int j = 0; j + 1 < b.num_control_points(); ++j) {
      const double u = b.midpoint(j);
      const PointConstants c = b.constants_at(u);
      b.add_detected<CondensedSummedZ, 6>(
          "rod.condensed_field", u, widened(b, b.basis_at(u, 1), u), {wrench, L},
          CondensedLoadedFieldKernel<CondensedSummedZ>{c, c_point, u}, pattern);
    }
    b.add_unit_quaternion_rows(kCondensedPoint);
    add_condensed_end(b, false);
    if (!b.adds_end(true)) return;
    add_loaded_tip<CondensedSummedTipZ>(
        b, widened(b, b.end_basis(true), 1.0),
        [](const auto& z, const PointConstants& c, const Vec3& c_point, auto& n, auto& m) {
          condensed_summed_wrench<CondensedSummedTipZ>(z, c, c_point, 1.0, n, m);
        });
  }

  void internal_wrench(const CollocationRod& rod, const VecX& x, const RodVariables& vars,
                       const BasisDerivatives& d, const PointValues& value, RodState& st) const override {
    require_basis_integrals(rod, d);
    const int size = kCondensedPoint.size;
    // I(u) = sum_j J_j(u) P_j over every control point.
    Vec3 I = Vec3::Zero();
    for (int j = 0; j < rod.num_control_points(); ++j)
      if (d.integrals[j] != 0.0) I += d.integrals[j] * x.segment<3>(vars.control_point_offset + j * size);
    loaded_internal_wrench(rod, x, vars, value.segment<3>(kCondensedPoint.p), I, st);
  }

 private:
  // The basis b at u widened to the control points 0 .. its last one, with the integrals J_j(u)
  // (kIntegral) that I(u) reads.
  static PointBasis widened(const FormBuilder& b, PointBasis basis, double u) {
    const VecX J = basis_integrals(b.rod().knots(), u);
    const int last = basis.first + basis.count - 1;
    std::vector<std::array<double, kBasisSlots>> B(last + 1, std::array<double, kBasisSlots>{});
    for (int i = 0; i < basis.count; ++i) B[basis.first + i] = basis.B[i];
    for (int i = 0; i <= last; ++i) B[i][kIntegral] = J[i];
    basis.B = std::move(B);
    basis.first = 0;
    basis.count = last + 1;
    return basis;
  }
};

}  // namespace

const RodForm& condensed_summed_form() {
  static const CondensedSummedForm form;
  return form;
}

const RodForm& condensed_form() {
  static const CondensedForm form;
  return form;
}

const RodForm& condensed_loaded_form() {
  static const CondensedLoadedForm form;
  return form;
}

}  // namespace pcr::collocation
