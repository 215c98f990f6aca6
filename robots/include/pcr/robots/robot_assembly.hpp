#pragma once
// The multibody system of a robot (docs/design.md §3) as one Problem:
//   unknowns  — per rod: control points (+ length), per platform: pose [x (3), Q (4)], per moving
//               URDF joint: its value;
//   equations — per rod: its collocation equations; per attached rod end: the 7 coupling equations
//               of its kind (the rod end frame = link pose * attachment frame); per free rod end: its
//               dead loads; per platform: force and moment balance + |Q|^2 = 1; per passive joint: the
//               balance of the generalised force beyond it and its spring (its value is free).
// Actuation inputs (rod lengths, joint values) are variable blocks too, fixed in the assembly's problem
// (the forward kinematics system: their values are whatever x holds); inverse kinematics builds its own
// problems from it with the inputs free (IkModel, robots/src/kinematics/ik_data.hpp).
// A RobotAssembly is immutable once built: share it (std::shared_ptr<const RobotAssembly>) between
// kinematics objects and threads; its const functions, the problem's evaluations included, may run in
// several threads at once.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "pcr/robots/robot_model.hpp"
#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/contact_ipopt.hpp"
#include "pcr/rods/rod_contact.hpp"
#include "pcr/solve/problem.hpp"

namespace pcr {

struct AssemblyOptions {
  /// Discretisation of rods that carry no hints in the model (the formulation only when
  /// formulation_by_slenderness is off): mixed at the midpoints (MixedPoints; each rod's force balance
  /// holds exactly under gravity at any degree), degree 6, 8 elements. Against degree 5 at 8 elements
  /// in the same bench_robots run (docs/benchmarks.md "Robots"): R5b warm IK inputs 1.9e-7
  /// against 1.0e-6 m at 1.0-1.3x the time per solve (three runs), R5a FK platform
  /// 1.8e-10 against 4.2e-10 m, R5a IK inputs 1.7e-8 against 1.8e-8 m (against 32 elements of degree 5).
  RodDiscretization discretization{RodFormulation::Mixed, 6, 8};
  /// Use the model's per-rod discretisation hints where given (they win over everything else).
  bool use_model_hints = true;
  /// Formulation of rods without a model hint chosen by slenderness (formulation_by_slenderness()):
  /// primal (7 instead of 13 unknowns per control point) only for thick rods, mixed otherwise (the
  /// primal form locks for slender rods, docs/design.md §2). Off: discretization.formulation for all.
  bool formulation_by_slenderness = true;
  double primal_min_gyration_ratio = 1.0 / 16.0;  ///< threshold of gyration_ratio() for primal
  /// Mixed rods at the midpoints (MixedPoints::Midpoints) are solved in the condensed form instead
  /// (RodFormulation::Condensed: n, m from the closed-form balance, 7 instead of 13 unknowns per
  /// control point). Without distributed loads it is the same discrete solution; with them (gravity)
  /// the same accuracy (test_shooting_crosscheck: within 0.49-1.006x the mixed error against shooting).
  /// Off: such rods stay mixed.
  bool condense_mixed_rods = true;
  /// Complementarity function of the contact rows of rods with obstacles (rod_contact.hpp,
  /// docs/contact.md); such rods are always discretised in the mixed form at the midpoints.
  ComplementarityFunction contact_function = ComplementarityFunction::FischerBurmeister;
  /// How the contact conditions are solved (contact_ipopt.hpp, docs/contact.md "Solvers compared"):
  /// Semismooth (contact_function rows, a square system for Newton) or Ipopt (Scholtes' relaxation with
  /// inequalities: forward kinematics then solves by Ipopt along a homotopy in the relaxation, whatever
  /// KinematicsOptions::solver says; inverse kinematics rejects it).
  ContactMethod contact_method = ContactMethod::Semismooth;
};

/// Field by field (the discretisation's fields included). Assemblies of one model with equal options are
/// the same system, variable for variable: forward kinematics shares results derived from them
/// (default_equilibrium.hpp), so a field added to AssemblyOptions belongs in this comparison.
bool operator==(const AssemblyOptions& a, const AssemblyOptions& b);
bool operator!=(const AssemblyOptions& a, const AssemblyOptions& b);

/// Radius of gyration over length, sqrt(min(EI1, EI2) / EA) / L, with the longest length of a fed
/// rod (a solid circle of diameter d: d / (4 L)).
double gyration_ratio(const RodElement& rod);

/// Primal when gyration_ratio(rod) >= primal_min_gyration_ratio, else mixed. The default threshold
/// 1/16 (solid circle: d / L >= 1/4) was set where the primal form at the then default discretisation
/// (degree 5, 8 elements) was within 1e-5 L of the converged tip of a cantilever under P L^2 / EI = 1.
/// Measured at the default discretisation with `build/release/tests/test_ik_objectives
/// --run_test=primal_locking_study`, primal tip error / L (degree 6, 8 elements; degree 5 in brackets):
/// 7.3e-8 (3.9e-6) at d/L = 0.4, 1.8e-7 (1.0e-5) at 0.25, 2.7e-7 (1.6e-5) at 0.2, 5.3e-6 (2.6e-4) at
/// 0.05, 2.1e-4 (6.0e-3) at 0.01, no convergence at 0.005 (locking), in 7 .. 48 Newton iterations;
/// mixed 1.2e-9 throughout, in 4. So the primal form is never more accurate: it is chosen only where
/// its error is well within 1e-5 L and it has fewer unknowns (7 instead of 13 per control point).
/// Whether primal should be chosen at all, now that the mixed form is 100x more accurate there, is open.
RodFormulation formulation_by_slenderness(const RodElement& rod, double primal_min_gyration_ratio);

class RobotAssembly {
 public:
  RobotAssembly(std::shared_ptr<const RobotModel> model, const AssemblyOptions& options = {});

  const RobotModel& model() const { return *model_; }
  const std::shared_ptr<const RobotModel>& model_ptr() const { return model_; }
  /// The options it was built with.
  const AssemblyOptions& options() const { return options_; }
  /// The forward kinematics system: inputs fixed, square.
  const Problem& problem() const { return problem_; }

  int num_rods() const { return static_cast<int>(rods_.size()); }
  const CollocationRod& rod(int i) const { return *rods_[i]; }
  const RodVariables& rod_variables(int i) const { return rod_variables_[i]; }
  /// The contact rows of rod i (docs/contact.md), or nullptr when it touches no obstacle.
  const RodContactVariables* rod_contact(int i) const;
  VariableId platform_variable(int platform) const { return platform_variables_[platform]; }
  /// Variable block (size 1) of model input i (a rod length or a joint value).
  VariableId input_variable(int input) const { return input_variables_[input]; }
  /// Residual block of a platform's force and moment balance and |Q|^2 = 1 (7 rows: force / force scale,
  /// moment / moment scale, the unit quaternion).
  ResidualId platform_balance(int platform) const;
  /// Residual block coupling rod i's end (at_tip: s = L, else s = 0) to its link; -1 for a free end.
  ResidualId rod_coupling(int rod, bool at_tip) const;
  /// Variable block (size 1) of passive joint i (RobotModel::passive_joints() order): free, not an input.
  VariableId passive_joint_variable(int passive) const;
  /// Residual block (1 row) of passive joint i's balance: (Q - k (q - rest)) / scale, Q the generalised
  /// force of everything beyond it, scale the moment scale (revolute, continuous) or the force scale
  /// (prismatic).
  ResidualId passive_joint_balance(int passive) const;
  /// Representative scales: the longest rod [m], and the largest rod force / moment scale.
  double length_scale() const { return length_scale_; }
  double force_scale() const { return force_scale_; }
  double moment_scale() const { return moment_scale_; }

  /// Initial guess: platforms at their initial poses, each rod a cubic Hermite curve from its start
  /// frame to its end frame (straight when free), inputs at their defaults.
  VecX initial_guess() const;
  VecX inputs(const VecX& x) const;
  /// Writes input values into x (throws InputError for a wrong count).
  void set_inputs(VecX& x, const VecX& inputs) const;
  /// Throws InputError unless there is one finite value per input within its bounds.
  void check_inputs(const VecX& inputs) const;
  Pose platform_pose(const VecX& x, int platform) const;

 private:
  struct Builder;  // the constructor's steps (robot_assembly.cpp)
  friend struct Builder;
  std::shared_ptr<const RobotModel> model_;
  AssemblyOptions options_;
  Problem problem_;
  std::vector<std::shared_ptr<const CollocationRod>> rods_;
  std::vector<RodVariables> rod_variables_;
  std::vector<RodContactVariables> rod_contacts_;  // per rod (no obstacles: empty)
  std::vector<VariableId> platform_variables_, joint_variables_, input_variables_;
  std::vector<ResidualId> platform_balances_, passive_joint_balances_;
  std::vector<std::array<ResidualId, 2>> rod_couplings_;  // per rod: start, end (-1 when free)
  double length_scale_ = 1.0, force_scale_ = 1.0, moment_scale_ = 1.0;
};

}  // namespace pcr
