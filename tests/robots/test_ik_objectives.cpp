// IK objectives (actuation effort, elastic energy), the rod stress limit and the reduced-space IK:
// values against independent computations (strain-form energy, read_solution's axial forces, the
// stress formula on state_at), gradients against finite differences, optima against nearby feasible
// points found independently (null-space moves re-projected onto the target with FK), the stress
// limit active / infeasible, bad options rejected.
#define BOOST_TEST_MODULE ik_objectives
#include <boost/test/unit_test.hpp>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "../../robots/src/kinematics/ik_objectives.hpp"
#include "../../robots/src/kinematics/reduced_ik.hpp"
#include "../rods/rod_fixtures.hpp"
#include "pcr/core/error.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "pcr/rods/rod_solve.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "robot_fixtures.hpp"

#define PCR_CLI_WORK_DIRECTORY "pcr_test_ik_objectives"
#include "cli/cli_runner.hpp"

using namespace pcr;
using test::load_model;
using test::model_path;
using test::moved_inputs;
using test::planar_with_radius;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Elastic energy in the strain form, 1/2 int (kappa^T K_BT kappa + eps^T K_SE eps) ds (the test
/// models have no intrinsic strains), by Simpson's rule on 2000 intervals per rod.
double strain_energy(const RobotAssembly& a, const VecX& x) {
  double energy = 0.0;
  for (int r = 0; r < a.num_rods(); ++r) {
    const CollocationRod& rod = a.rod(r);
    BOOST_REQUIRE(rod.model().intrinsic.is_zero());
    const double L = rod.length(x, a.rod_variables(r));
    const int n = 2000;
    for (int i = 0; i <= n; ++i) {
      const RodState st = rod.state_at(x, a.rod_variables(r), L * i / n);
      const double e =
          0.5 *
          (st.curvature_body.dot(rod.model().bending_torsion_stiffness.cwiseProduct(st.curvature_body)) +
           st.shear_extension_body.dot(
               rod.model().shear_extension_stiffness.cwiseProduct(st.shear_extension_body)));
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      energy += w * e * L / (3.0 * n);
    }
  }
  return energy;
}

/// Outer-fibre stress of a solid circle of radius c: |N| / (pi c^2) + |M_perp| c / (pi c^4 / 4).
double circle_stress(const RodState& st, double c) {
  const Vec3 d3 = st.rotation.col(2);
  const double N = st.force.dot(d3);
  const Vec3 m_perp = st.moment - st.moment.dot(d3) * d3;
  return std::abs(N) / (kPi * c * c) + m_perp.norm() * c / (kPi * std::pow(c, 4) / 4.0);
}

/// Max stress at points_per_rod equally spaced points of every rod (radius 1 mm: stewart_gough).
double max_stress(const RobotAssembly& a, const VecX& x, int points_per_rod, double radius) {
  double s = 0.0;
  for (int r = 0; r < a.num_rods(); ++r) {
    const double L = a.rod(r).length(x, a.rod_variables(r));
    for (int j = 0; j < points_per_rod; ++j)
      s = std::max(
          s, circle_stress(a.rod(r).state_at(x, a.rod_variables(r), L * j / (points_per_rod - 1)), radius));
  }
  return s;
}

/// Central differences of f over every entry of x, h = 1e-6 (1 + |x_i|).
template <class F>
VecX numeric_gradient(F f, VecX x) {
  VecX g(x.size());
  for (int i = 0; i < x.size(); ++i) {
    const double xi = x[i], h = 1e-6 * (1.0 + std::abs(xi));
    x[i] = xi + h;
    const double fp = f(x);
    x[i] = xi - h;
    const double fm = f(x);
    x[i] = xi;
    g[i] = (fp - fm) / (2.0 * h);
  }
  return g;
}

LinkTarget position_target(const Vec3& p) {
  LinkTarget t;
  t.link = "platform";
  t.mode = LinkTarget::Mode::Position;
  t.pose.position = p;
  return t;
}

/// A position-only target near R5a's (3 of 6 inputs redundant), off the symmetry axis: at the
/// symmetric point (0, 0, 0.4) every objective is stationary by symmetry and Ipopt started from equal
/// inputs stays on equal inputs (a saddle of the distance).
const Vec3 kTarget(0.01, -0.015, 0.41);

/// Effort and energy of the FK solution at u (independent of the IK code): sum of squared axial
/// forces at the feed points [N^2] from read_solution, strain-form energy [J].
struct FkObjectives {
  bool converged = false;
  Vec3 position = Vec3::Zero();
  double effort = 0.0, energy = 0.0;
};
FkObjectives fk_objectives(ForwardKinematics& fk, const VecX& u) {
  FkObjectives o;
  const RobotSolution s = fk.solve(u);
  o.converged = s.summary.converged();
  o.position = s.platforms[0].position;
  for (const RodResult& r : s.rods) o.effort += r.axial_force * r.axial_force;
  o.energy = strain_energy(fk.assembly(), fk.state());
  return o;
}

/// Projects u onto {u : platform position(u) = target} by Gauss-Newton with the minimum-norm step
/// u <- u - J^+ (p(u) - target) (J: position rows of FK's input Jacobian); false if FK fails.
bool project_onto_target(ForwardKinematics& fk, VecX& u, const Vec3& target) {
  for (int it = 0; it < 30; ++it) {
    const RobotSolution s = fk.solve(u);
    if (!s.summary.converged()) return false;
    const Vec3 d = s.platforms[0].position - target;
    if (d.norm() < 1e-13) return true;  // 1e-13 m: round-off level of positions ~0.4 m
    const MatX J = fk.input_jacobian().topRows(3);
    u -= J.transpose() * (J * J.transpose()).ldlt().solve(d);
  }
  return false;
}

}  // namespace

BOOST_AUTO_TEST_CASE(objective_and_stress_values_match_independent_computations) {
  // 32 elements: the strain form's shear energy (from p', K_SE ~ 6e5 N) is 3x off at 8 elements
  // (3.4e-3 J vs 1.0e-3 J), within 2e-4 relative at 16 and 32 elements; the bending parts agree to
  // 5e-5 already at 8 (Simpson, 2000 intervals per rod).
  const auto model = load_model("stewart_gough");
  KinematicsOptions o;
  o.assembly.discretization.elements = 32;
  ForwardKinematics fk(model, o);
  const RobotSolution s = fk.solve(moved_inputs(*model, 0.05));
  BOOST_REQUIRE(s.summary.converged());
  const RobotAssembly& a = fk.assembly();
  const VecX& x = fk.state();
  // Effort: the same axial forces as read_solution's (interpolated at s = 0: round-off only, 1e-12).
  double effort = 0.0;
  for (const RodResult& r : s.rods) effort += 0.5 * std::pow(r.axial_force / a.force_scale(), 2);
  BOOST_TEST(kinematics::actuation_effort(a, x, nullptr) == effort, boost::test_tools::tolerance(1e-12));
  // Energy: the complementary form (n, m interpolated) against the strain form (p', q' interpolated);
  // the mixed form satisfies the constitutive law only at the collocation points, so they differ by
  // the discretisation error: measured 1.6e-8 relative here (32 elements); tolerance 1e-5.
  const double e_strain = strain_energy(a, x);
  BOOST_TEST(e_strain > 0.0);
  BOOST_TEST(kinematics::elastic_energy(a, x, nullptr) == e_strain, boost::test_tools::tolerance(1e-5));
  // Stress: the smoothing delta = 1e-9 F0 changes the value by < 1e-9 relative; tolerance 1e-8.
  const auto points = kinematics::stress_points(a, 9);
  const VecX sigma = kinematics::rod_stresses(a, x, points, nullptr);
  for (size_t j = 0; j < points.size(); ++j) {
    const CollocationRod& rod = a.rod(points[j].rod);
    const RodState st = rod.state_at(x, a.rod_variables(points[j].rod),
                                     points[j].u * rod.length(x, a.rod_variables(points[j].rod)));
    BOOST_TEST(sigma[j] == circle_stress(st, 0.001), boost::test_tools::tolerance(1e-8));
  }
}

BOOST_AUTO_TEST_CASE(objective_and_stress_gradients_match_finite_differences) {
  // Mixed rods (analytic chain rule) on R5a, condensed rods (analytic) on R5b (no distributed loads) and
  // R5a (gravity: n, m also read L and the integral of p), primal rods (local central differences) on
  // the planar robot. Central differences with h = 1e-6 (1 + |x|): truncation ~1e-12, round-off
  // ~1e-16 f / h ~1e-10 relative; tolerance 1e-6 of the gradient's max-abs.
  struct Case {
    RodFormulation formulation;
    std::string model;
  };
  for (const Case& k :
       {Case{RodFormulation::Mixed, "stewart_gough"}, Case{RodFormulation::Condensed, "stewart_gough_teleop"},
        Case{RodFormulation::Condensed, "stewart_gough"}, Case{RodFormulation::Primal, ""}}) {
    const RodFormulation formulation = k.formulation;
    const bool primal = formulation == RodFormulation::Primal;
    KinematicsOptions o;
    // Primal rods lock at R5a's slenderness (FK does not converge); 1 cm rods on the planar robot.
    o.assembly.discretization.formulation = formulation;
    if (primal) o.assembly.discretization = RodDiscretization{RodFormulation::Primal, 5, 8};
    o.assembly.formulation_by_slenderness = false;
    o.assembly.condense_mixed_rods = false;
    const auto model = primal ? planar_with_radius(0.01) : load_model(k.model);
    ForwardKinematics fk(model, o);
    BOOST_REQUIRE(fk.solve(moved_inputs(*model, 0.05)).summary.converged());
    const RobotAssembly& a = fk.assembly();
    BOOST_TEST((a.rod(0).discretization().formulation == formulation));
    const VecX x = fk.state();
    const std::string label = std::string(to_string(formulation)) + ", " + (primal ? "planar" : k.model);
    auto check = [&](const std::string& what, const VecX& analytic, const VecX& numeric) {
      const double scale = analytic.cwiseAbs().maxCoeff();
      BOOST_TEST(scale > 0.0);
      BOOST_TEST((analytic - numeric).cwiseAbs().maxCoeff() <= 1e-6 * scale,
                 what << " (" << label << "): error " << (analytic - numeric).cwiseAbs().maxCoeff() << " of "
                      << scale);
    };
    VecX g;
    kinematics::actuation_effort(a, x, &g);
    check("effort", g,
          numeric_gradient([&](const VecX& y) { return kinematics::actuation_effort(a, y, nullptr); }, x));
    kinematics::elastic_energy(a, x, &g);
    check("energy", g,
          numeric_gradient([&](const VecX& y) { return kinematics::elastic_energy(a, y, nullptr); }, x));
    const auto points = kinematics::stress_points(a, 5);
    MatX H;
    kinematics::rod_stresses(a, x, points, &H);
    for (size_t j = 0; j < points.size(); j += 3)
      check("stress " + std::to_string(j), H.row(j).transpose(),
            numeric_gradient(
                [&](const VecX& y) { return kinematics::rod_stresses(a, y, {points[j]}, nullptr)[0]; }, x));
  }
}

BOOST_AUTO_TEST_CASE(reduced_gradients_match_finite_differences_of_fk) {
  // The reduced objective, target rows and stress rows over u (each evaluation an FK solve) against
  // central differences with relative step 1e-6. Measured on the worst stress row (|N| near 0, where
  // its smoothing is strongly curved): error 0.17 at step 1e-4, 1.7e-3 at 1e-5 (O(h^2) truncation,
  // so ~2e-5 at 1e-6, of a derivative ~134), plus FK noise (x(u) to ~1e-12 relative / 1e-6 step);
  // tolerance 2e-5 absolute + relative.
  const auto model = load_model("stewart_gough");
  InverseKinematics ik(model, {position_target(kTarget)});
  const Problem& p = ik.problem();
  BOOST_REQUIRE(p.variable(ik.target_variable(0)).name == "target.platform");
  KinematicsOptions o;
  o.tolerance = 1e-12;
  ForwardKinematics fk(model, o);
  const VecX u = moved_inputs(*model, 0.05);
  BOOST_REQUIRE(fk.solve(u).summary.converged());
  VecX z(7);
  z << kTarget, 1, 0, 0, 0;
  VecX x(p.num_variables());
  x << fk.state(), z;
  for (const IkObjective objective : {IkObjective::ActuationEffort, IkObjective::ElasticEnergy}) {
    o.ik.objective = objective;
    o.ik.distance_weight = 0.1;
    o.ik.max_rod_stress = 1e8;
    kinematics::ReducedIk reduced(std::make_shared<const kinematics::ReducedIkModel>(
        ik.assembly_ptr(), p, std::vector{ik.target_residual(0)}, o));
    reduced.prepare(x, model->default_input_values());  // x holds the target pose z
    JacobianCheckOptions c;
    c.absolute_tolerance = 2e-5;
    c.relative_tolerance = 2e-5;
    const JacobianCheckResult r = check_problem_jacobian(reduced.problem(), u, c);
    BOOST_TEST(r.passed, to_string(objective) << ": " << r.to_string());
    BOOST_TEST(r.entries_checked > 6 * 3);
  }
}

BOOST_AUTO_TEST_CASE(effort_and_energy_optima_beat_nearby_feasible_points) {
  const auto model = load_model("stewart_gough");
  KinematicsOptions fo;
  fo.tolerance = 1e-12;
  ForwardKinematics fk(model, fo);
  const VecX reference = model->default_input_values();
  const double L0 = 0.45;  // any positive scale gives the same comparisons; the assembly's (model length)
  std::map<IkObjective, VecX> optimum;
  for (const IkObjective objective :
       {IkObjective::InputDistance, IkObjective::ActuationEffort, IkObjective::ElasticEnergy}) {
    KinematicsOptions o;
    o.ik.objective = objective;
    InverseKinematics ik(model, {position_target(kTarget)}, o);
    const RobotSolution s = ik.solve({Pose{kTarget, Quat(1, 0, 0, 0)}}, &reference);
    BOOST_REQUIRE_MESSAGE(s.summary.converged(), to_string(objective) << ": " << s.summary.brief_report());
    BOOST_TEST_MESSAGE(to_string(objective) << ": " << s.summary.brief_report());
    // Target reached: target_tolerance 1e-9 on (x - x_t) / L0 (L0 = 0.45 m), plus FK noise.
    BOOST_TEST((s.platforms[0].position - kTarget).norm() < 1e-8);
    optimum[objective] = s.inputs;
    // The objective at the optimum and at nearby feasible points: u* moved by 5 mm along each null
    // vector of the position Jacobian, both ways, re-projected onto the target. A local minimum is
    // no worse than any of them; the margin 1e-7 relative covers Ipopt's tol 1e-8 on the scaled problem.
    auto value = [&](const VecX& u) {
      const FkObjectives f = fk_objectives(fk, u);
      BOOST_REQUIRE(f.converged);
      if (objective == IkObjective::ActuationEffort) return f.effort;
      if (objective == IkObjective::ElasticEnergy) return f.energy;
      return 0.5 * ((u - reference) / L0).squaredNorm();
    };
    const double f_opt = value(s.inputs);
    BOOST_REQUIRE(fk.solve(s.inputs).summary.converged());
    const MatX J = fk.input_jacobian().topRows(3);
    const RightSingularVectors svd = right_singular_vectors(J);
    int compared = 0;
    for (int k = 3; k < 6; ++k)
      for (const double sign : {-1.0, 1.0}) {
        VecX u = s.inputs + sign * 0.005 * svd.V.col(k);
        BOOST_REQUIRE(project_onto_target(fk, u, kTarget));
        const double f_near = value(u);
        BOOST_TEST(f_opt <= f_near * (1.0 + 1e-7), to_string(objective)
                                                       << ": f* = " << f_opt << ", nearby " << f_near);
        ++compared;
      }
    BOOST_TEST(compared == 6);
  }
  // The optima differ: each is strictly better in its own measure than the others' optima (margins
  // 1e-4 relative, far above the optimality tolerance).
  const FkObjectives at_distance = fk_objectives(fk, optimum[IkObjective::InputDistance]);
  const FkObjectives at_effort = fk_objectives(fk, optimum[IkObjective::ActuationEffort]);
  const FkObjectives at_energy = fk_objectives(fk, optimum[IkObjective::ElasticEnergy]);
  BOOST_TEST(at_effort.effort < at_distance.effort * (1.0 - 1e-4));
  BOOST_TEST(at_energy.energy < at_distance.energy * (1.0 - 1e-4));
  BOOST_TEST(at_effort.effort < at_energy.effort * (1.0 - 1e-4));
  BOOST_TEST(at_energy.energy < at_effort.energy * (1.0 - 1e-4));
  BOOST_TEST((optimum[IkObjective::ActuationEffort] - optimum[IkObjective::InputDistance]).norm() > 1e-4);
}

BOOST_AUTO_TEST_CASE(partial_targets_go_to_the_reduced_space_and_agree_with_the_full_space) {
  // Position-only targets leave inputs free: the input distance is minimised in the reduced space by
  // default. On the planar robot (3 inputs, x and z targeted) the full-space Ipopt (IkOptions::
  // full_space) converges as well and must reach the same optimum: both satisfy the equations to the
  // tolerance 1e-10 and Ipopt's optimality to 1e-8 (scaled), so the inputs agree to ~1e-8 L; bound 1e-6 m.
  const auto planar = load_model("planar_three_rod");
  LinkTarget t = position_target(Vec3(0.01, 0.0, 0.29));
  t.components = {true, false, true, false, false, false};  // x, z
  const std::vector<Pose> pose{Pose{t.pose.position, Quat(1, 0, 0, 0)}};
  InverseKinematics reduced(planar, {t});
  KinematicsOptions o;
  o.ik.full_space = true;
  InverseKinematics full(planar, {t}, o);
  const VecX reference = planar->default_input_values();
  const RobotSolution a = reduced.solve(pose, &reference), b = full.solve(pose, &reference);
  BOOST_REQUIRE_MESSAGE(a.summary.converged(), a.summary.brief_report());
  BOOST_REQUIRE_MESSAGE(b.summary.converged(), b.summary.brief_report());
  BOOST_TEST(a.summary.solver == "ipopt (reduced)");
  BOOST_TEST(b.summary.solver == "ipopt");
  BOOST_TEST((a.inputs - b.inputs).lpNorm<Eigen::Infinity>() < 1e-6, a.inputs.transpose()
                                                                         << " | " << b.inputs.transpose());
  // stewart_gough, position only (3 of 6 inputs free): the reduced space converges (the full space did
  // not: IkOptions::full_space) and reaches the target to its tolerance 1e-9 L0 (L0 = 0.45 m) + FK noise.
  const auto sg = load_model("stewart_gough");
  InverseKinematics ik(sg, {position_target(kTarget)});
  const VecX sg_reference = sg->default_input_values();
  const RobotSolution s = ik.solve({Pose{kTarget, Quat(1, 0, 0, 0)}}, &sg_reference);
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  BOOST_TEST((s.platforms[0].position - kTarget).norm() < 1e-8);
}

BOOST_AUTO_TEST_CASE(stress_limit_is_active_and_satisfied) {
  // The limit is 70 % of the max stress at the distance optimum (reduced space). The distance
  // objective has several local optima near the target, with max stresses (measured at the default
  // mesh) of 9.7e8 Pa (the one reached here, input distance 62.42 mm), 9.55e8 Pa (62.48 mm, reached
  // at 32 elements) and 1.25e9 Pa (62.01 mm, reached without IkOptions::max_input_step); 70 % is below
  // all of them, so the limit must bind whichever one Ipopt approaches, and it is reachable (the
  // effort optimum has 4.6e8 Pa).
  const auto model = load_model("stewart_gough");
  const VecX reference = model->default_input_values();
  const std::vector<Pose> target{Pose{kTarget, Quat(1, 0, 0, 0)}};
  InverseKinematics free_ik(model, {position_target(kTarget)});
  const RobotSolution s_free = free_ik.solve(target, &reference);
  BOOST_REQUIRE(s_free.summary.converged());
  const int points = 2 * AssemblyOptions().discretization.elements + 1;  // the default: 2 elements + 1
  const double sigma_free = max_stress(free_ik.assembly(), free_ik.state(), points, 0.001);
  BOOST_TEST_MESSAGE("max stress at the distance optimum: " << sigma_free << " Pa");
  KinematicsOptions o;
  o.ik.max_rod_stress = 0.7 * sigma_free;
  InverseKinematics ik(model, {position_target(kTarget)}, o);
  const RobotSolution s = ik.solve(target, &reference);
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  BOOST_TEST_MESSAGE(s.summary.brief_report());
  const double sigma = max_stress(ik.assembly(), ik.state(), points, 0.001);
  // Satisfied: rows sigma / sigma_max <= 1 within target_tolerance 1e-9 (the smoothing only
  // overestimates); active: the unconstrained optimum violates the limit, so it must bind (to
  // Ipopt's tol 1e-8 on the complementarity); tolerances 1e-8 and 1e-6 relative.
  BOOST_TEST(sigma <= *o.ik.max_rod_stress * (1.0 + 1e-8));
  BOOST_TEST(sigma >= *o.ik.max_rod_stress * (1.0 - 1e-6));
  BOOST_TEST((s.platforms[0].position - kTarget).norm() < 1e-8);
  // The limit costs distance (margin 1e-6 relative, above the optimality tolerance).
  const double d_free = (s_free.inputs - reference).squaredNorm(), d = (s.inputs - reference).squaredNorm();
  BOOST_TEST(d > d_free * (1.0 + 1e-6));
}

BOOST_AUTO_TEST_CASE(infeasible_stress_limit_is_reported) {
  // 1 kPa: gravity alone (platform 0.1 kg on six 1 mm rods) gives axial stresses ~1e5 Pa.
  const auto model = load_model("stewart_gough");
  KinematicsOptions o;
  o.ik.objective = IkObjective::ElasticEnergy;
  o.ik.max_rod_stress = 1e3;
  InverseKinematics ik(model, {position_target(kTarget)}, o);
  const RobotSolution s = ik.solve({Pose{kTarget, Quat(1, 0, 0, 0)}});
  BOOST_TEST(!s.summary.converged(), s.summary.brief_report());
  BOOST_TEST(s.inputs.allFinite());
  BOOST_TEST(s.platforms[0].position.allFinite());
  BOOST_TEST(std::isfinite(s.summary.objective));
}

BOOST_AUTO_TEST_CASE(bad_ik_options_are_rejected_with_names) {
  const auto model = load_model("stewart_gough");
  auto make = [&](const KinematicsOptions& o) { InverseKinematics ik(model, {position_target(kTarget)}, o); };
  KinematicsOptions o;
  o.ik.objective = IkObjective::ActuationEffort;
  o.ik.distance_weight = -1.0;
  BOOST_CHECK_THROW(make(o), InputError);
  o.ik.distance_weight = 0.0;
  o.ik.max_rod_stress = -5.0;
  BOOST_CHECK_THROW(make(o), InputError);
  o.ik.max_rod_stress = 1e8;
  o.ik.max_input_step = 0.0;
  BOOST_CHECK_THROW(make(o), InputError);
  o.ik.max_input_step = 0.05;
  o.ik.stress_points_per_rod = 1;
  BOOST_CHECK_THROW(make(o), InputError);
  try {
    o.ik.stress_points_per_rod = 1;
    make(o);
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("stress_points_per_rod = 1") != std::string::npos, e.what());
  }
  // A robot without fed rods has no effort objective.
  const auto slider = load_model("slider_actuated");
  LinkTarget t = position_target(kTarget);
  KinematicsOptions e;
  e.ik.objective = IkObjective::ActuationEffort;
  BOOST_CHECK_THROW(InverseKinematics(slider, {t}, e), InputError);
}

BOOST_AUTO_TEST_CASE(cli_objective_and_stress_options) {
  const std::string ik = "ik '" + model_path("stewart_gough") + "' --target platform=0.01,-0.015,0.41";
  const Run effort = run_pcr(ik + " --objective effort --json");
  BOOST_TEST(effort.exit_code == 0, effort.err);
  BOOST_TEST(contains(effort.out, "objective effort"), effort.out);
  BOOST_TEST(contains(effort.out, "\"status\": \"converged\""), effort.out);
  // An unreachable stress limit: solve failed (exit code 1), reported as infeasible.
  const Run infeasible = run_pcr(ik + " --objective energy --max-stress 1e3 --json");
  BOOST_TEST(infeasible.exit_code == 1);
  BOOST_TEST(contains(infeasible.out, "infeasible"), infeasible.out);
  // Bad values are usage errors (exit code 2) naming the option.
  const Run bad_objective = run_pcr(ik + " --objective speed");
  BOOST_TEST(bad_objective.exit_code == 2);
  BOOST_TEST(contains(bad_objective.err, "--objective speed"), bad_objective.err);
  const Run bad_stress = run_pcr(ik + " --max-stress -5");
  BOOST_TEST(bad_stress.exit_code == 2);
  BOOST_TEST(contains(bad_stress.err, "--max-stress -5"), bad_stress.err);
  // --formulation condensed solves R5a's rods under gravity (n, m with the integral of p); the
  // agreement with the mixed form is tested in test_kinematics and test_shooting_crosscheck.
  const Run condensed = run_pcr(ik + " --formulation condensed --json");
  BOOST_TEST(condensed.exit_code == 0, condensed.err);
  BOOST_TEST(contains(condensed.out, "\"status\": \"converged\""), condensed.out);
  const Run help = run_pcr("ik --help");
  BOOST_TEST(contains(help.out, "--objective distance|effort|energy"));
  BOOST_TEST(contains(help.out, "--formulation auto|mixed|condensed|primal"));
}

BOOST_AUTO_TEST_CASE(square_target_gives_the_newton_inputs_whatever_the_objective) {
  // R5a full pose target: no freedom left, so the reduced-space solve must land on the inputs of the
  // square Newton path. Both solve to 1e-10 dimensionless residuals; the inputs agree to ~1e-10 m,
  // tolerance 1e-8 m.
  const auto model = load_model("stewart_gough");
  LinkTarget t;
  t.link = "platform";
  t.pose.position = Vec3(0.0, 0.0, 0.4);
  t.pose.orientation = quat_from_rotation_vector(Vec3(0.0, 10.0 * kPi / 180.0, 0.0));
  InverseKinematics newton(model, {t});
  const RobotSolution s_newton = newton.solve({t.pose});
  BOOST_REQUIRE(s_newton.summary.converged());
  BOOST_TEST(s_newton.summary.solver == "newton");
  KinematicsOptions o;
  o.ik.objective = IkObjective::ElasticEnergy;
  InverseKinematics reduced(model, {t}, o);
  const RobotSolution s = reduced.solve({t.pose});
  BOOST_REQUIRE_MESSAGE(s.summary.converged(), s.summary.brief_report());
  BOOST_TEST((s.inputs - s_newton.inputs).cwiseAbs().maxCoeff() < 1e-8);
}
