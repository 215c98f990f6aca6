// The start of cold forward kinematics solves, the equilibrium at the model's default inputs
// (DefaultEquilibrium, kinematics.hpp), is solved once per model and options and shared by every
// ForwardKinematics over them: a later FK object solves exactly as the first, an FK over another model
// object (loaded from the same file: nothing shared) gives the same bits, and two threads that need it
// at once both get the one solve. Part of test_concurrent_solves (run by the sanitizer pass too).
#include <boost/test/unit_test.hpp>

#include <atomic>
#include <thread>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"

using namespace pcr;

namespace {

std::shared_ptr<const RobotModel> load_stewart_gough() {
  return std::make_shared<const RobotModel>(
      load_robot_model(std::string(PCR_MODEL_DIR) + "/stewart_gough.urdf"));
}

/// Inputs moved from the defaults by up to `fraction` of each input's range, a different sign pattern
/// per input (the platform tilts and translates).
VecX moved_inputs(const RobotModel& m, double fraction) {
  VecX u = m.default_input_values();
  for (int i = 0; i < u.size(); ++i)
    u[i] += fraction * (m.inputs()[i].upper - m.inputs()[i].lower) * ((i % 3) - 1.0);
  return u;
}

/// A cold solve's figures, for bitwise comparison.
struct ColdSolve {
  VecX state, platform_position, platform_orientation;
  int iterations = 0, jacobians = 0;
  bool converged = false;
};

ColdSolve cold_solve(ForwardKinematics& fk, const VecX& u) {
  const RobotSolution s = fk.solve(u);
  return {fk.state(),           s.platforms[0].position,        s.platforms[0].orientation,
          s.summary.iterations, s.summary.jacobian_evaluations, s.summary.converged()};
}

/// The same result, bit for bit. The work counts differ by the default equilibrium's solve, which the
/// summary of the solve that did it counts (the first over a model); compared separately.
bool same(const ColdSolve& a, const ColdSolve& b) {
  return a.state == b.state && a.platform_position == b.platform_position &&
         a.platform_orientation == b.platform_orientation && a.converged == b.converged;
}

bool same_work(const ColdSolve& a, const ColdSolve& b) {
  return a.iterations == b.iterations && a.jacobians == b.jacobians;
}

}  // namespace

BOOST_AUTO_TEST_CASE(fk_objects_over_one_model_share_one_default_equilibrium) {
  std::shared_ptr<const RobotModel> model = load_stewart_gough();
  const std::weak_ptr<const RobotModel> model_alive = model;
  const VecX u = moved_inputs(*model, 0.05);
  ColdSolve first;
  const DefaultEquilibrium* shared = nullptr;
  {
    ForwardKinematics fk(model);
    first = cold_solve(fk, u);
    shared = &fk.default_equilibrium();
  }
  BOOST_TEST(first.converged);
  // The first FK is gone; a later one over the model (and one over an assembly built from it with the
  // same options) starts from the same object, so it was solved once, and solves bit for bit as the first.
  ForwardKinematics later(model);
  ForwardKinematics over_assembly(std::make_shared<const RobotAssembly>(model));
  BOOST_TEST(&later.default_equilibrium() == shared);
  BOOST_TEST(&over_assembly.default_equilibrium() == shared);
  const ColdSolve later_solve = cold_solve(later, u);
  BOOST_TEST(same(later_solve, first));
  const ColdSolve over_assembly_solve = cold_solve(over_assembly, u);
  BOOST_TEST(same(over_assembly_solve, first));
  BOOST_TEST(same_work(over_assembly_solve, later_solve));
  // The first solve counted the default equilibrium's work (it did that solve), the later ones do not.
  const SolveSummary& d_summary = later.default_equilibrium().summary;
  BOOST_TEST(d_summary.iterations > 0);
  BOOST_TEST(first.iterations == later_solve.iterations + d_summary.iterations);
  BOOST_TEST(first.jacobians == later_solve.jacobians + d_summary.jacobian_evaluations);

  // It is an equilibrium: the FK system's residuals vanish to the solve's tolerance there (the default
  // KinematicsOptions::tolerance, 1e-10, bounds the max-abs of the dimensionless rows).
  const DefaultEquilibrium& d = later.default_equilibrium();
  BOOST_TEST(d.converged);
  BOOST_TEST(d.summary.converged());
  VecX c;
  later.assembly().problem().evaluate_residuals(d.x, c);
  BOOST_TEST((c - later.assembly().problem().row_lower()).cwiseAbs().maxCoeff() <= 1e-10);
  BOOST_TEST((later.assembly().inputs(d.x) == model->default_input_values()));

  // The unshared path: another model object from the same file has its own default equilibrium, solved
  // again, with the same bits, and the same cold solve.
  const auto reloaded = load_stewart_gough();
  ForwardKinematics unshared(reloaded);
  BOOST_TEST(&unshared.default_equilibrium() != shared);
  BOOST_TEST((unshared.default_equilibrium().x == d.x));
  BOOST_TEST(same(cold_solve(unshared, u), first));  // its equilibrium solved by default_equilibrium()

  // Options that shape it (the mesh, the tolerance) get their own; those that do not (results' sampling,
  // stability monitoring) share it.
  KinematicsOptions finer;
  finer.assembly.discretization.elements = 6;
  KinematicsOptions looser;
  looser.tolerance = 1e-8;
  KinematicsOptions sampled;
  sampled.centerline_points = 5;
  sampled.check_stability = true;
  BOOST_TEST(&ForwardKinematics(model, finer).default_equilibrium() != shared);
  BOOST_TEST(&ForwardKinematics(model, looser).default_equilibrium() != shared);
  BOOST_TEST(&ForwardKinematics(model, sampled).default_equilibrium() == shared);

  // The registry holds no model: once the last user lets go, the model is gone.
  later = ForwardKinematics(reloaded);
  over_assembly = ForwardKinematics(reloaded);
  model.reset();
  BOOST_TEST(model_alive.expired());
}

BOOST_AUTO_TEST_CASE(models_under_one_owner_keep_their_own_default_equilibria) {
  // Two models owned by one object, reached through aliasing pointers (one control block): each gets
  // its own default equilibrium, of its own assembly's size, with its model's default inputs.
  struct TwoModels {
    RobotModel stewart_gough, planar;
  };
  const auto both = std::make_shared<const TwoModels>(
      TwoModels{load_robot_model(std::string(PCR_MODEL_DIR) + "/stewart_gough.urdf"),
                load_robot_model(std::string(PCR_MODEL_DIR) + "/planar_three_rod.urdf")});
  ForwardKinematics fk_sg(std::shared_ptr<const RobotModel>(both, &both->stewart_gough));
  ForwardKinematics fk_planar(std::shared_ptr<const RobotModel>(both, &both->planar));
  BOOST_TEST(&fk_sg.default_equilibrium() != &fk_planar.default_equilibrium());
  for (const ForwardKinematics* fk : {&fk_sg, &fk_planar}) {
    const DefaultEquilibrium& d = fk->default_equilibrium();
    BOOST_TEST(d.converged);
    BOOST_TEST(d.x.size() == fk->assembly().problem().num_variables());
    BOOST_TEST((fk->assembly().inputs(d.x) == fk->assembly().model().default_input_values()));
  }
}

BOOST_AUTO_TEST_CASE(cold_solves_in_two_threads_share_one_default_equilibrium_solve) {
  // Serial reference on its own model object (its own default equilibrium).
  const auto reference_model = load_stewart_gough();
  const VecX u_a = moved_inputs(*reference_model, 0.04), u_b = moved_inputs(*reference_model, -0.06);
  ForwardKinematics serial_a(reference_model), serial_b(reference_model);
  const ColdSolve expected_a = cold_solve(serial_a, u_a), expected_b = cold_solve(serial_b, u_b);
  BOOST_TEST(expected_a.converged);
  BOOST_TEST(expected_b.converged);

  // A fresh model: both threads need its default equilibrium at once; one solves it, the other waits.
  const auto model = load_stewart_gough();
  ForwardKinematics fk_a(model), fk_b(model);
  ColdSolve got_a, got_b;
  std::atomic<int> ready{0};
  auto start_together = [&ready] {
    ready.fetch_add(1);
    while (ready.load() < 2) std::this_thread::yield();
  };
  std::thread other([&] {
    start_together();
    got_b = cold_solve(fk_b, u_b);
  });
  start_together();
  got_a = cold_solve(fk_a, u_a);
  other.join();
  BOOST_TEST(same(got_a, expected_a));
  BOOST_TEST(same(got_b, expected_b));
  // Exactly one of the two solves did the shared solve and counts it, as serial_a did.
  BOOST_TEST(got_a.iterations + got_b.iterations == expected_a.iterations + expected_b.iterations);
  BOOST_TEST(got_a.jacobians + got_b.jacobians == expected_a.jacobians + expected_b.jacobians);
  BOOST_TEST(&fk_a.default_equilibrium() == &fk_b.default_equilibrium());
  BOOST_TEST((fk_a.default_equilibrium().x == serial_a.default_equilibrium().x));
}
