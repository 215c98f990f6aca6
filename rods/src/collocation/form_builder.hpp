#pragma once
// Private to pcr_rods: one rod formulation as a unit (RodForm) and what each unit needs to add its
// residual blocks for one rod to a Problem (FormBuilder: the point constants, bases, end frames and
// names). The units: primal_form.cpp, mixed_forms.cpp (Greville points and midpoints),
// condensed_forms.cpp (without and with distributed loads).
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "pcr/rods/collocation/end_equations.hpp"
#include "pcr/rods/collocation/point_block.hpp"
#include "pcr/rods/collocation_rod.hpp"

namespace pcr::collocation {

class FormBuilder;

/// Values of one control point block or of a basis combination of them (at most 13, no heap).
using PointValues = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 13, 1>;

/// One rod formulation: its control point layout, its equation count and its residual blocks.
class RodForm {
 public:
  virtual ~RodForm() = default;
  virtual const PointLayout& layout() const = 0;
  /// Rows of the field equations of a rod with n control points (all rows but the 7 + 7 end conditions).
  virtual int field_rows(int n) const = 0;
  /// Adds the field equations and the end conditions the builder's end options ask for.
  virtual void add_blocks(const FormBuilder& b) const = 0;
  /// The internal force and moment of the state `st` (p, q and strains set) at u = s / L, from the
  /// control point values `value` (the basis combination at u, point layout) and the rod's variables.
  virtual void internal_wrench(const CollocationRod& rod, const VecX& x, const RodVariables& vars,
                               const BasisDerivatives& d, const PointValues& value, RodState& st) const = 0;
};

const RodForm& primal_form();
const RodForm& mixed_greville_form();
const RodForm& mixed_midpoint_form();
const RodForm& condensed_form();
/// The condensed form with distributed loads: running integrals T per control point, or (small rods)
/// the integral of p summed over the control points.
const RodForm& condensed_loaded_form();
const RodForm& condensed_summed_form();

/// The constant frame and the prescribed loads of a model end (load factor and signs applied).
struct EndData {
  RodEndKind kind;
  EndTarget<double> target;
  EndLoads loads;
};

template <typename T>
EndTarget<T> cast_target(const EndTarget<double>& t) {
  return {t.position.cast<T>(), t.orientation.cast<T>(), t.frame.cast<T>(), t.axes};
}

class FormBuilder {
 public:
  FormBuilder(const CollocationRod& rod, Problem& problem, const RodVariables& vars,
              const RodEndOptions& ends, double load_factor);

  const CollocationRod& rod() const { return rod_; }
  const RodVariables& vars() const { return vars_; }
  Problem& problem() const { return problem_; }
  int num_control_points() const { return rod_.num_control_points(); }
  /// Greville abscissae tau_0 = 0 < ... < tau_{n-1} = 1.
  const std::vector<double>& greville() const { return tau_; }
  /// (tau_j + tau_{j+1}) / 2, j = 0 .. n - 2.
  double midpoint(int j) const { return 0.5 * (tau_[j] + tau_[j + 1]); }

  /// Material, intrinsic strains (and s-derivatives), distributed loads and scales at u.
  PointConstants constants_at(double u) const;
  /// The p + 1 basis functions active at u with their u-derivatives up to max_derivative.
  PointBasis basis_at(double u, int max_derivative) const;
  /// The end control point alone (open knot vector: p(0) = P_0, p(1) = P_{n-1}).
  PointBasis end_basis(bool at_tip) const;
  /// Whether the end conditions of that end are added (RodEndOptions), and its data.
  bool adds_end(bool at_tip) const { return at_tip ? ends_.tip : ends_.base; }
  EndData end_data(bool at_tip) const;
  /// "rod.end_<kind>" of that end.
  std::string end_kind(bool at_tip) const;

  /// Adds a PointBlock at u whose local vector is named by Z (its control points from b, then the
  /// direct blocks in Z's entry order).
  template <typename Z, int NR, typename Kernel>
  void add(const std::string& kind, double u, const PointBasis& b, std::initializer_list<VariableId> direct,
           Kernel kernel,
           const KernelPattern<Z::layout.size(), NR>& pattern =
               dense_kernel_pattern<Z::layout.size(), NR>()) const {
    std::vector<VariableId> v(vars_.control_points.begin() + b.first,
                              vars_.control_points.begin() + b.first + b.count);
    v.insert(v.end(), direct);
    problem_.add_residual_block(make_point_block<Z, NR>(
        kind, where(u), std::move(v), rod_.control_point_size(), b, std::move(kernel), pattern));
  }
  /// As add, with the kernel's sparsity pattern detected once per rod and kernel (point_block.hpp:
  /// the pattern does not depend on the point's constants) and kept in `pattern`.
  template <typename Z, int NR, typename Kernel>
  void add_detected(const std::string& kind, double u, const PointBasis& b,
                    std::initializer_list<VariableId> direct, Kernel kernel,
                    std::optional<KernelPattern<Z::layout.size(), NR>>& pattern) const {
    if (!pattern) pattern = detect_kernel_pattern<Z::layout.size(), NR>(kernel);
    add<Z, NR>(kind, u, b, direct, std::move(kernel), *pattern);
  }
  /// |q|^2 - 1 = 0 at the interior Greville abscissae (the forms that collocate their field equations
  /// at the midpoints).
  void add_unit_quaternion_rows(const PointLayout& layout) const;

 private:
  std::string where(double u) const;

  const CollocationRod& rod_;
  Problem& problem_;
  const RodVariables& vars_;
  RodEndOptions ends_;
  double load_factor_;
  std::vector<double> tau_;
};

}  // namespace pcr::collocation
