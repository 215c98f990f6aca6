// The primal form: control points [P (3), Q (4)]; n, m from the constitutive law.
// Rows: at the n - 2 interior Greville abscissae the force balance n' + f = 0 (3), the moment balance
// m' + p' x n + l = 0 (3) and |q|^2 = 1 (1), with n = R K_SE (eps - eps0), m = R K_BT (kappa - kappa0)
// (primal_interior); at u = 0 and u = 1 the 7 end conditions with the same n, m.
#include "form_builder.hpp"
#include "pcr/rods/drawn_rod.hpp"

namespace pcr::collocation {
namespace {

/// The local vector of the primal end conditions: n, m from q, q_u, p_u and L; p, q at the end.
struct PrimalEndZ {
  enum Entry { p, q, q_u, p_u, L, kEntries };
  static constexpr LocalLayout<kEntries> layout{{{{kPrimalPoint.p, 3, 0},
                                                  {kPrimalPoint.q, 4, 0},
                                                  {kPrimalPoint.q, 4, 1},
                                                  {kPrimalPoint.p, 3, 1},
                                                  {kDirect, 1}}}};
};

class PrimalForm final : public RodForm {
 public:
  const PointLayout& layout() const override { return kPrimalPoint; }
  int field_rows(int n) const override { return 7 * (n - 2); }

  void add_blocks(const FormBuilder& b) const override {
    const int n = b.num_control_points();
    const VariableId L = b.vars().length;
    // Row order: base end, interior points, tip end (along the rod).
    add_end(b, false);
    std::optional<KernelPattern<PrimalInteriorZ::layout.size(), 7>> pattern;
    for (int j = 1; j + 1 < n; ++j) {
      const double u = b.greville()[j];
      const PointConstants c = b.constants_at(u);
      b.add_detected<PrimalInteriorZ, 7>(
          "rod.primal_equilibrium", u, b.basis_at(u, 2), {L},
          [c](const auto& z, auto* r) { primal_interior(z, c, r); }, pattern);
    }
    add_end(b, true);
  }

  void internal_wrench(const CollocationRod& rod, const VecX&, const RodVariables&, const BasisDerivatives&,
                       const PointValues&, RodState& st) const override {
    // The constitutive law (M4): N, M for a drawn rod (the model's n, m otherwise).
    const RodModel& m = rod.model();
    Vec3 eps0, kappa0;
    m.intrinsic.at(st.s, eps0, kappa0);
    const DrawnConstants d = drawn_constants(m, eps0, kappa0);
    st.force = st.rotation * d.k_se.cwiseProduct(st.shear_extension_body - d.eps0);
    st.moment = st.rotation * d.k_bt.cwiseProduct(st.curvature_body - d.kappa0);
  }

 private:
  static void add_end(const FormBuilder& b, bool at_tip) {
    if (!b.adds_end(at_tip)) return;
    const double u = at_tip ? 1.0 : 0.0;
    const PointConstants c = b.constants_at(u);
    const EndData e = b.end_data(at_tip);
    b.add<PrimalEndZ, 7>(b.end_kind(at_tip), u, b.basis_at(u, 1), {b.vars().length},
                         [c, e](const auto& z, auto* r) {
                           using T = typename std::decay_t<decltype(z)>::Scalar;
                           using Z = PrimalEndZ;
                           V3<T> nn, mm;
                           primal_wrench<T>(get<Z, Z::q>(z), get<Z, Z::q_u>(z), get<Z, Z::p_u>(z),
                                            get<Z, Z::L>(z)[0], c, nn, mm);
                           end_conditions<T>(e.kind, cast_target<T>(e.target), e.loads, c, get<Z, Z::p>(z),
                                             get<Z, Z::q>(z), nn, mm, r);
                         });
  }
};

}  // namespace

const RodForm& primal_form() {
  static const PrimalForm form;
  return form;
}

}  // namespace pcr::collocation
