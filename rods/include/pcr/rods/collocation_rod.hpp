#pragma once
// One Cosserat rod discretised by isogeometric collocation (docs/design.md §2; Weeger, Yeung & Dunn 2017).
//
// p(u), q(u) (and in the mixed form n(u), m(u)) are B-splines of degree p >= 2 on an open knot vector
// over u in [0, 1], s = L u. Each control point is one variable block: [P (3), Q (4)] in the primal
// form, [P (3), Q (4), N (3), M (3)] in the mixed form; the rod length L is one more block (fixed for
// a rod of given length, free when it is an actuation input). Equations at the Greville abscissae
// tau_1 = 0 < ... < tau_n = 1: u = 0 and u = 1 carry the end conditions (7 each); in the primal form
// the n - 2 interior points carry the field equations. Mixed form: see MixedPoints. Condensed form:
// [P (3), Q (4)] per control point (and T (3) with distributed loads on long rods) and one block [n (3), h
// (3)] per rod, see RodFormulation. Each formulation is one unit in rods/src/collocation (primal_form.cpp,
// mixed_forms.cpp, condensed_forms.cpp, which say which equation each row is); its control point
// layout is named once in collocation/layout.hpp (PointLayout). All residuals are
// dimensionless: forces by F0 = max(K_BT) / L0^2, moments by M0 = max(K_BT) / L0, lengths by L0
// (the model's length), constitutive equations as strains; the primal force balance (which carries
// K_SE times the round-off of p'') by max(K_SE) / L0.
#include <memory>
#include <string>
#include <vector>

#include "pcr/rods/collocation/layout.hpp"
#include "pcr/rods/rod_model.hpp"
#include "pcr/solve/problem.hpp"
#include "pcr/splines/basis.hpp"
#include "pcr/splines/knot_vector.hpp"

namespace pcr {

namespace collocation {
class RodForm;
}

/// - Primal: p, q; n, m from the constitutive law (locks for slender rods, docs/design.md §2).
/// - Mixed: p, q, n, m all splines; balance and constitutive laws collocated.
/// - Condensed: the balance laws integrate in closed form, n(s) = n - f s and
///   m(s) = h - (p(s) - c) x n(s) - l s - (integral_0^s (p - c)) x f with the constant unknowns n, h
///   (force and moment about the fixed point c = moment_point(), the model's base position) and the
///   constant distributed loads f, l; so only p, q are splines and the 6 constitutive rows are
///   collocated at the midpoints of the Greville abscissae (as MixedPoints::Midpoints). Equilibrium is
///   exact; 7 instead of 13 unknowns per control point. Without distributed loads it is the mixed
///   midpoint scheme with n, m eliminated (the same discrete solution). With them each row needs
///   I(u) = integral_0^u p, which reads every control point before u. Rods with at most
///   kMaxBandedCondensedPoints control points (whose band the constant wrench fills anyway) sum it so.
///   Longer rods carry T_i = sum_{j<i} (integral_0^1 N_j) P_j in each control point as well (10
///   unknowns), tied by the local recurrence T_{i+1} = T_i + (integral_0^1 N_i) P_i, so that
///   I(u) = T_k + the sum of the p + 1 active J_i(u) P_i (k the first active function) and the rows stay
///   local: the same discrete solution at a cost linear in the element count (condensed_forms.cpp).
///   Free of shear locking for the same reason as the mixed form (n is not computed from p').
enum class RodFormulation { Primal, Mixed, Condensed };
const char* to_string(RodFormulation formulation);

/// Where the mixed form collocates its 12 first-order field equations (n' + f, m' + p' x n + l and the
/// two constitutive laws); the unit-norm rows |q|^2 - 1 stay at the n - 2 interior Greville points.
///  - Midpoints (default): at the n - 1 midpoints (tau_i + tau_{i+1}) / 2, so each first-order field
///    equation has n - 1 rows and the 6 + 6 end conditions complete it, as for a shooting method.
///  - Greville (Weeger, Yeung & Dunn 2017; docs/design.md §2): balance laws at the n - 2 interior points,
///    constitutive laws at all n. The forces n(u) then have a second mode besides the constant one
///    that the balance rows do not see; only the compliant constitutive rows fix it, weakly when
///    n = p + E is odd. Measured (docs/benchmarks.md "Midpoints against Greville points"): errors 100-1000x
///    larger at p = 5, E = 8. Kept to reproduce the published scheme and as the baseline of that comparison.
enum class MixedPoints { Midpoints, Greville };
const char* to_string(MixedPoints points);

struct RodDiscretization {
  RodFormulation formulation = RodFormulation::Mixed;
  int degree = 4;                                     ///< polynomial degree p >= 2
  int elements = 4;                                   ///< number of equal knot spans >= 1
  MixedPoints mixed_points = MixedPoints::Midpoints;  ///< mixed form only (the condensed form: midpoints)
  /// Mixed form at the midpoints only: one contact force density unknown F_j (3, N/m) per midpoint in its
  /// force balance n' + f + F_j = 0, to be tied to obstacles by add_rod_contact (rod_contact.hpp).
  bool contact_forces = false;
};

/// Memory [bytes] that one rod's discretisation of this degree and element count is estimated to take
/// in a solve, for the mixed form (13 unknowns per control point, the most of the formulations): the row
/// of each unknown has about 13 (p + 1) Jacobian entries of 8 bytes, held about 8 times over (the
/// residual blocks' dense Jacobians, the problem's Jacobian and its free-column copy with their indices,
/// the LU factors with their fill). Measured for comparison (`/usr/bin/time -v pcr fk
/// models/stewart_gough.urdf --elements E --formulation mixed`, six rods, degree 6): 4.7 KB per unknown
/// at E = 1,000; the estimate is 5.8 KB.
double rod_memory_estimate(int degree, int elements);
/// Limit of rod_memory_estimate for one rod: 2 GiB (about 28,000 elements at degree 6, 19,800 at
/// degree 9), so that a robot of a few such rods still fits a machine of some 16 GiB.
inline constexpr double kMaxRodMemoryBytes = 2.0 * 1024.0 * 1024.0 * 1024.0;
/// Empty when rod_memory_estimate(degree, elements) is within kMaxRodMemoryBytes, else what is wrong
/// (the estimate and the limit), for a message naming where the element count came from.
std::string rod_memory_excess(int degree, int elements);

/// State of a rod at arc length s (world frame unless named _body).
struct RodState {
  double s = 0.0;
  Vec3 position = Vec3::Zero();
  Quat quaternion = Quat(1, 0, 0, 0);  ///< as interpolated (|q| ~ 1)
  Mat3 rotation = Mat3::Identity();    ///< R(q)
  /// n: force of the part s+ on the part s- (the section force; for a drawn rod not the effective
  /// N = n - rho A c^2 p' of the unknowns, drawn_rod.hpp)
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();  ///< m (the section moment; drawn rods: M = m - rho c^2 R J_rho kappa)
  Vec3 shear_extension_body = Vec3::Zero();  ///< eps = R^T p' - e3
  Vec3 curvature_body = Vec3::Zero();        ///< kappa
};

/// Axial stretch v3 = 1 + eps3 (1 = unstretched).
inline double axial_stretch(const RodState& s) {
  return 1.0 + s.shear_extension_body[2];
}
/// Antman's admissibility v3 > 0, with a margin of 1e-6 for round-off: at or below it the rod is
/// compressed to a point or inverted, an exact equilibrium of the extensible model but no physical
/// state (e.g. a rod whose clamped ends coincide, compressed to zero length).
inline bool admissible_axial_stretch(double v3) {
  return v3 > 1e-6;
}

/// Variable blocks of one rod in a Problem.
struct RodVariables {
  std::vector<VariableId> control_points;
  VariableId length = -1;
  VariableId wrench = -1;        ///< condensed form: [n (3), h (3)]; -1 otherwise
  int control_point_offset = 0;  ///< index in x of the first control point (they are contiguous)
  int length_offset = 0;         ///< index in x of L
  int wrench_offset = -1;        ///< index in x of the wrench block (condensed form), else -1
  /// RodDiscretization::contact_forces: F_j (3) per midpoint u_j, j = 0 .. n - 2; empty otherwise.
  std::vector<VariableId> contact_forces;
};

/// Which end conditions of the model the rod adds itself (robots add coupling blocks instead).
struct RodEndOptions {
  bool base = true;
  bool tip = true;
};

class CollocationRod {
 public:
  /// Condensed form with distributed loads: rods with at most this many control points sum I(u) over all
  /// control points (7 unknowns per point; the sum fills the rod's block below the diagonal, at a cost
  /// growing with the square of the point count), longer rods carry the running integrals T (10 unknowns
  /// per point, banded, linear cost). In either case the constant wrench [n, h] is read by every row of
  /// the rod; BorderedBlockLu moves such wide columns to its border, so every rod keeps its group (a band
  /// per rod) whatever its length.
  static constexpr int kMaxBandedCondensedPoints = 40;

  /// Validates the model and the discretisation (InputError naming the value).
  CollocationRod(RodModel model, RodDiscretization discretization);

  const RodModel& model() const { return model_; }
  const RodDiscretization& discretization() const { return discretization_; }
  const KnotVector& knots() const { return *knots_; }
  /// Condensed form with distributed loads: n, m read the integral of p (basis integrals).
  bool condensed_with_loads() const { return loaded_condensed_; }
  int num_control_points() const;
  /// 7 (primal, condensed), 10 (condensed with loads and running integrals) or 13 (mixed)
  int control_point_size() const;
  /// The components of a control point block (offsets of P, Q and of N, M or T where present).
  const collocation::PointLayout& point_layout() const;
  /// Condensed form with loads: w_j = integral_0^1 N_j (the recurrence of T); empty otherwise.
  const VecX& integral_weights() const { return integral_weights_; }
  /// Values of a rod configuration (initial guesses): the control points, then in the condensed
  /// form the wrench [n, h] (6).
  int configuration_size() const;
  /// Condensed form: the point c about which the moment unknown h is taken (the model's base position).
  const Vec3& moment_point() const { return model_.base.position; }
  /// Rows of the interior/end equations added for the given end options (for counting).
  int num_equations(const RodEndOptions& ends) const;

  /// Adds the rod's variable blocks (initial guess: the straight rod leaving the clamped end frame,
  /// or `initial` when given; the running integrals T of the condensed form with loads are taken from
  /// its P, whatever `initial` holds there) and its residual blocks, with loads and intrinsic strains
  /// multiplied by load_factor (for continuation). The length block is fixed at the model's length unless
  /// free_length. `group` tags the rod's variables for structured solvers (a band per rod,
  /// BorderedBlockLu).
  RodVariables add_to_problem(Problem& problem, const RodEndOptions& ends = {}, double load_factor = 1.0,
                              bool free_length = false, int group = -1, const VecX* initial = nullptr) const;
  /// The variable blocks of add_to_problem alone (no residual blocks): e.g. to lay out an initial guess
  /// as a Problem's values (Problem::initial_values) without building the equations.
  RodVariables add_variables(Problem& problem, bool free_length = false, int group = -1,
                             const VecX* initial = nullptr) const;

  /// Control point values of the straight rod along the frame of `end` (or the base frame if free);
  /// configuration_size() values (a zero wrench in the condensed form).
  VecX straight_configuration() const;
  /// Control point values of the stress-free shape (intrinsic strains, no load) leaving the base frame:
  /// p' = R (e3 + eps0), R' = R hat(kappa0), integrated from the base, interpolated at the Greville
  /// abscissae (n = m = 0). The straight configuration when the base is not clamped.
  VecX stress_free_configuration() const;

  /// Post-processing at arc length s in [0, L] (L read from x): p, R, n, m and strains.
  RodState state_at(const VecX& x, const RodVariables& vars, double s) const;
  /// States at num_points equally spaced arc lengths from 0 to L.
  std::vector<RodState> sample(const VecX& x, const RodVariables& vars, int num_points) const;
  /// Basis values and first derivatives at num_points equally spaced u = s / L in [0, 1] (they do not
  /// depend on L), with the basis integrals when condensed_with_loads(): for sampling many states of
  /// one rod, e.g. the results along a path.
  std::vector<BasisDerivatives> sample_basis(int num_points) const;
  /// sample() with the bases of sample_basis(num_points).
  std::vector<RodState> sample(const VecX& x, const RodVariables& vars,
                               const std::vector<BasisDerivatives>& basis) const;
  /// The centerline part of sample(): positions p and axial stretches v3 = d3 . p_s at the points of
  /// `basis` (the same values as sample() gives, without rotations, curvatures and wrenches).
  void sample_centerline(const VecX& x, const RodVariables& vars, const std::vector<BasisDerivatives>& basis,
                         std::vector<Vec3>& positions, std::vector<double>& axial_stretches) const;
  /// The smallest axial stretch v3 = d3 . p_s at the points of `basis` (the minimum of
  /// sample_centerline's axial_stretches, without the positions).
  double min_axial_stretch(const VecX& x, const RodVariables& vars,
                           const std::vector<BasisDerivatives>& basis) const;
  /// Rod length in x.
  double length(const VecX& x, const RodVariables& vars) const;

  /// Reference scales of the dimensionless residuals: L0 = model length, F0 = max(K_BT) / L0^2,
  /// M0 = max(K_BT) / L0.
  double length_scale() const { return model_.length; }
  double force_scale() const { return force_scale_; }
  double moment_scale() const { return moment_scale_; }

  /// state_at with the basis at u = s / L given (e.g. an entry of sample_basis).
  RodState state_with_basis(const VecX& x, const RodVariables& vars, double s,
                            const BasisDerivatives& d) const;

 private:
  RodModel model_;
  RodDiscretization discretization_;
  std::shared_ptr<const KnotVector> knots_;
  double force_scale_ = 1.0, moment_scale_ = 1.0;
  bool loaded_condensed_ = false;
  const collocation::RodForm* form_ = nullptr;  ///< the formulation's unit (static, one per formulation)
  VecX integral_weights_;

  /// basis_integrals(knots(), u) from integral_weights_ and the active functions' integrals.
  VecX integrals_at(double u) const;
  /// Condensed form with loads: T_0 = 0, T_{i+1} = T_i + w_i P_i in a configuration; else nothing.
  void set_running_integrals(VecX& configuration) const;
};

}  // namespace pcr
