// The mixed form: control points [P (3), Q (4), N (3), M (3)]; n, m are splines of their own. Rows,
// with the field equations n' + f = 0 (3), m' + p' x n + l = 0 (3) and the constitutive laws in
// compliance form (6, constitutive_rows) as mixed_field:
//  - at the midpoints (MixedPoints::Midpoints): the 12 field rows at each of the n - 1 midpoints of
//    consecutive Greville abscissae, |q|^2 = 1 at the n - 2 interior abscissae, the 7 + 7 end
//    conditions: 12 (n - 1) + (n - 2) = 13 (n - 2) + 12 field rows;
//  - at the Greville points (MixedPoints::Greville): the 12 field rows and |q|^2 = 1 at the n - 2
//    interior abscissae, the 6 constitutive rows at both ends, the end conditions: the same count.
// End conditions read p, q, n, m of the end control point (the open knot vector interpolates it).
#include "form_builder.hpp"

namespace pcr::collocation {
namespace {

struct MixedEndZ {
  enum Entry { p, q, n, m, kEntries };
  static constexpr LocalLayout<kEntries> layout{
      {{{kMixedPoint.p, 3, 0}, {kMixedPoint.q, 4, 0}, {kMixedPoint.n, 3, 0}, {kMixedPoint.m, 3, 0}}}};
};

void add_mixed_end(const FormBuilder& b, bool at_tip) {
  if (!b.adds_end(at_tip)) return;
  const double u = at_tip ? 1.0 : 0.0;
  const PointConstants c = b.constants_at(u);
  const EndData e = b.end_data(at_tip);
  b.add<MixedEndZ, 7>(b.end_kind(at_tip), u, b.end_basis(at_tip), {}, [c, e](const auto& z, auto* r) {
    using T = typename std::decay_t<decltype(z)>::Scalar;
    using Z = MixedEndZ;
    end_conditions<T>(e.kind, cast_target<T>(e.target), e.loads, c, get<Z, Z::p>(z), get<Z, Z::q>(z),
                      get<Z, Z::n>(z), get<Z, Z::m>(z), r);
  });
}

/// MixedZ with the contact force density F_j (3, a direct block after L) of
/// RodDiscretization::contact_forces.
struct MixedContactZ {
  enum Entry { q, q_u, p_u, n, n_u, m, m_u, L, F, kEntries };
  static constexpr LocalLayout<kEntries> layout = append(MixedZ::layout, {kDirect, 3});
};
static_assert(int{MixedContactZ::F} == int{MixedZ::kEntries} && int{MixedContactZ::L} == int{MixedZ::L},
              "MixedContactZ names MixedZ's entries, then F");

/// mixed_field with the contact force density F added to f: n' + f + F = 0 (rod_contact.hpp).
template <typename T>
void mixed_contact_field(const Eigen::Matrix<T, MixedContactZ::layout.size(), 1>& z, const PointConstants& c,
                         T* r) {
  const MixedLocal<T> head = z.template head<MixedZ::layout.size()>();
  mixed_field(head, c, r);
  const double fr = c.length_scale / c.force_scale;
  for (int i = 0; i < 3; ++i) r[i] += get<MixedContactZ, MixedContactZ::F>(z)[i] * fr;
}

class MixedForm : public RodForm {
 public:
  const PointLayout& layout() const override { return kMixedPoint; }
  int field_rows(int n) const override { return 13 * (n - 2) + 12; }
  void internal_wrench(const CollocationRod&, const VecX&, const RodVariables&, const BasisDerivatives&,
                       const PointValues& value, RodState& st) const override {
    st.force = value.segment<3>(kMixedPoint.n);
    st.moment = value.segment<3>(kMixedPoint.m);
  }
};

class MixedMidpointForm final : public MixedForm {
 public:
  void add_blocks(const FormBuilder& b) const override {
    std::optional<KernelPattern<MixedZ::layout.size(), 12>> pattern;
    std::optional<KernelPattern<MixedContactZ::layout.size(), 12>> contact_pattern;
    const std::vector<VariableId>& F = b.vars().contact_forces;
    for (int j = 0; j + 1 < b.num_control_points(); ++j) {
      const double u = b.midpoint(j);
      const PointConstants c = b.constants_at(u);
      if (!F.empty()) {
        b.add_detected<MixedContactZ, 12>(
            "rod.mixed_field", u, b.basis_at(u, 1), {b.vars().length, F[j]},
            [c](const auto& z, auto* r) { mixed_contact_field(z, c, r); }, contact_pattern);
        continue;
      }
      b.add_detected<MixedZ, 12>(
          "rod.mixed_field", u, b.basis_at(u, 1), {b.vars().length},
          [c](const auto& z, auto* r) { mixed_field(z, c, r); }, pattern);
    }
    b.add_unit_quaternion_rows(kMixedPoint);
    add_mixed_end(b, false);
    add_mixed_end(b, true);
  }
};

class MixedGrevilleForm final : public MixedForm {
 public:
  void add_blocks(const FormBuilder& b) const override {
    const int n = b.num_control_points();
    const VariableId L = b.vars().length;
    std::optional<KernelPattern<MixedZ::layout.size(), 13>> interior;
    std::optional<KernelPattern<MixedZ::layout.size(), 6>> constitutive;
    // Row order along the rod: each end's constitutive rows come before its end conditions.
    for (int j = 0; j < n; ++j) {
      const double u = b.greville()[j];
      const PointConstants c = b.constants_at(u);
      if (j > 0 && j + 1 < n) {
        b.add_detected<MixedZ, 13>(
            "rod.mixed_equilibrium", u, b.basis_at(u, 1), {L},
            [c](const auto& z, auto* r) { mixed_interior(z, c, r); }, interior);
        continue;
      }
      b.add_detected<MixedZ, 6>(
          "rod.mixed_constitutive", u, b.basis_at(u, 1), {L},
          [c](const auto& z, auto* r) { mixed_constitutive(z, c, r); }, constitutive);
      add_mixed_end(b, j > 0);
    }
  }
};

}  // namespace

const RodForm& mixed_midpoint_form() {
  static const MixedMidpointForm form;
  return form;
}

const RodForm& mixed_greville_form() {
  static const MixedGrevilleForm form;
  return form;
}

}  // namespace pcr::collocation
