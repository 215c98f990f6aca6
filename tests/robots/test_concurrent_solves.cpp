// One Problem evaluated by two threads at once gives what serial evaluations give. Model/data split of the
// kinematics (kinematics.hpp "Model and data"): objects that share one assembly
// (FK, IK) or one IK model (with_fresh_state) solve in two threads at once with results bitwise equal to
// the same solves run one after the other; moved objects go on solving exactly as unmoved ones.
// The sanitizer pass of scripts/test.sh runs this test (ASan/UBSan); it also runs under ThreadSanitizer.
#define BOOST_TEST_MODULE concurrent_solves
#include <boost/test/unit_test.hpp>

#include <atomic>
#include <cmath>
#include <thread>
#include <type_traits>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "solve/test_problems.hpp"

using namespace pcr;

namespace {

static_assert(!std::is_copy_constructible_v<ForwardKinematics> &&
              !std::is_copy_assignable_v<ForwardKinematics>);
static_assert(std::is_nothrow_move_constructible_v<ForwardKinematics> &&
              std::is_nothrow_move_assignable_v<ForwardKinematics>);
static_assert(!std::is_copy_constructible_v<InverseKinematics> &&
              !std::is_copy_assignable_v<InverseKinematics>);
static_assert(std::is_nothrow_move_constructible_v<InverseKinematics> &&
              std::is_nothrow_move_assignable_v<InverseKinematics>);

std::shared_ptr<const RobotModel> stewart_gough() {
  return std::make_shared<const RobotModel>(
      load_robot_model(std::string(PCR_MODEL_DIR) + "/stewart_gough.urdf"));
}

/// A path of `count` input vectors from the defaults, each input moved by up to `fraction` of its range
/// (pattern differs per input so the platform tilts and translates).
std::vector<VecX> input_path(const RobotModel& m, int count, double fraction, double phase) {
  std::vector<VecX> path;
  for (int k = 1; k <= count; ++k) {
    VecX u = m.default_input_values();
    for (int i = 0; i < u.size(); ++i) {
      const ActuationInput& in = m.inputs()[i];
      u[i] += fraction * (in.upper - in.lower) * std::sin(phase + 1.3 * i) * k / count;
    }
    path.push_back(u);
  }
  return path;
}

/// What a solve hands back, for bitwise comparison: the state and the solution's figures.
struct Outcome {
  VecX state, inputs;
  std::vector<Pose> platforms;
  int iterations = 0, jacobians = 0;
  bool converged = false;
};

bool same(const Outcome& a, const Outcome& b) {
  if (a.platforms.size() != b.platforms.size()) return false;
  for (size_t p = 0; p < a.platforms.size(); ++p)
    if (a.platforms[p].position != b.platforms[p].position ||
        a.platforms[p].orientation != b.platforms[p].orientation)
      return false;
  return a.state == b.state && a.inputs == b.inputs && a.iterations == b.iterations &&
         a.jacobians == b.jacobians && a.converged == b.converged;
}

Outcome outcome(const RobotSolution& s, const VecX& state) {
  return {state,
          s.inputs,
          s.platforms,
          s.summary.iterations,
          s.summary.jacobian_evaluations,
          s.summary.converged()};
}

std::vector<Outcome> run_fk(ForwardKinematics& fk, const std::vector<VecX>& path) {
  std::vector<Outcome> out;
  for (const VecX& u : path) {
    const RobotSolution s = fk.solve(u);
    out.push_back(outcome(s, fk.state()));
  }
  return out;
}

std::vector<Outcome> run_ik(InverseKinematics& ik, const std::vector<Pose>& path) {
  std::vector<Outcome> out;
  for (const Pose& p : path) {
    const RobotSolution s = ik.solve({p});
    out.push_back(outcome(s, ik.state()));
  }
  return out;
}

/// Runs a and b in two threads started together.
template <class A, class B>
void in_parallel(A&& a, B&& b) {
  std::atomic<int> ready{0};
  auto start = [&ready] {
    ready.fetch_add(1);
    while (ready.load() < 2) std::this_thread::yield();
  };
  std::thread other([&] {
    start();
    b();
  });
  start();
  a();
  other.join();
}

void check_all_converged_and_equal(const std::vector<Outcome>& parallel, const std::vector<Outcome>& serial,
                                   const char* what) {
  BOOST_REQUIRE_EQUAL(parallel.size(), serial.size());
  for (size_t k = 0; k < serial.size(); ++k) {
    BOOST_TEST(serial[k].converged, what << " solve " << k);
    BOOST_TEST(same(parallel[k], serial[k]), what << " solve " << k << ": parallel differs from serial");
  }
}

/// Platform poses along an input path (FK), as reachable IK targets.
std::vector<Pose> reachable_poses(const std::shared_ptr<const RobotAssembly>& assembly,
                                  const std::vector<VecX>& path) {
  ForwardKinematics fk(assembly);
  std::vector<Pose> poses;
  for (const VecX& u : path) {
    const RobotSolution s = fk.solve(u);
    BOOST_REQUIRE(s.summary.converged());
    poses.push_back(s.platforms[0]);
  }
  return poses;
}

LinkTarget platform_target() {
  LinkTarget t;
  t.link = "platform";
  return t;
}

}  // namespace

BOOST_AUTO_TEST_CASE(one_problem_evaluated_by_two_threads_as_serially) {
  const Problem p = test::broyden_problem(200);
  using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  struct Values {
    VecX c, c_only;
    SparseRowMajor J, H;
  };
  // Residuals, Jacobian and Hessian at `count` points along x(t) = -1 + phase + 0.01 t sin(i).
  auto evaluate_along = [&p](double phase, int count) {
    std::vector<Values> out(count);
    const VecX lambda = VecX::LinSpaced(p.num_rows(), -1.0, 1.0);
    for (int k = 0; k < count; ++k) {
      VecX x(p.num_variables());
      for (int i = 0; i < x.size(); ++i) x[i] = -1.0 + phase + 0.01 * k * std::sin(i);
      p.evaluate_residuals(x, out[k].c_only);
      p.evaluate_residuals_and_jacobian(x, out[k].c, out[k].J);
      p.evaluate_hessian(x, 1.0, lambda, out[k].H);
    }
    return out;
  };
  const std::vector<Values> serial_a = evaluate_along(0.1, 30), serial_b = evaluate_along(0.3, 30);
  std::vector<Values> a, b;
  in_parallel([&] { a = evaluate_along(0.1, 30); }, [&] { b = evaluate_along(0.3, 30); });
  for (const auto& [got, expected] : {std::pair{&a, &serial_a}, std::pair{&b, &serial_b}}) {
    for (size_t k = 0; k < expected->size(); ++k) {
      const Values &g = (*got)[k], &e = (*expected)[k];
      BOOST_TEST((g.c == e.c && g.c_only == e.c_only), "point " << k);
      BOOST_TEST((MatX(g.J) == MatX(e.J) && MatX(g.H) == MatX(e.H)), "point " << k);
    }
  }
}

BOOST_AUTO_TEST_CASE(fk_objects_sharing_an_assembly_solve_in_parallel_as_serially) {
  const auto model = stewart_gough();
  const auto assembly = std::make_shared<const RobotAssembly>(model);
  const std::vector<VecX> path_a = input_path(*model, 4, 0.08, 0.0), path_b = input_path(*model, 4, 0.1, 2.0);
  ForwardKinematics serial_a(assembly), serial_b(assembly);
  // The shared default equilibrium solved before the runs: no first solve counts its work (which solve
  // does is a race in the parallel run; test_shared_cold_start checks that it is counted once).
  BOOST_TEST(serial_a.default_equilibrium().converged);
  const std::vector<Outcome> expected_a = run_fk(serial_a, path_a), expected_b = run_fk(serial_b, path_b);
  ForwardKinematics fk_a(assembly), fk_b(assembly);
  std::vector<Outcome> got_a, got_b;
  in_parallel([&] { got_a = run_fk(fk_a, path_a); }, [&] { got_b = run_fk(fk_b, path_b); });
  check_all_converged_and_equal(got_a, expected_a, "FK path a");
  check_all_converged_and_equal(got_b, expected_b, "FK path b");
  // The derivatives at the solution read the shared assembly too.
  MatX da, db;
  in_parallel([&] { da = fk_a.input_jacobian(); }, [&] { db = fk_b.input_jacobian(); });
  BOOST_TEST((da == serial_a.input_jacobian()));
  BOOST_TEST((db == serial_b.input_jacobian()));
}

BOOST_AUTO_TEST_CASE(ik_objects_sharing_a_model_solve_in_parallel_as_serially) {
  const auto model = stewart_gough();
  const auto assembly = std::make_shared<const RobotAssembly>(model);
  const std::vector<Pose> path_a = reachable_poses(assembly, input_path(*model, 3, 0.06, 0.5));
  const std::vector<Pose> path_b = reachable_poses(assembly, input_path(*model, 3, 0.06, 2.5));
  // Over one IK model (with_fresh_state), and an IK over the shared assembly against it.
  const InverseKinematics base(assembly, {platform_target()});
  BOOST_TEST(base.square());
  InverseKinematics serial_a = base.with_fresh_state(), serial_b = base.with_fresh_state();
  const std::vector<Outcome> expected_a = run_ik(serial_a, path_a), expected_b = run_ik(serial_b, path_b);
  InverseKinematics ik_a = base.with_fresh_state();
  InverseKinematics ik_b(assembly, {platform_target()});
  std::vector<Outcome> got_a, got_b;
  in_parallel([&] { got_a = run_ik(ik_a, path_a); }, [&] { got_b = run_ik(ik_b, path_b); });
  check_all_converged_and_equal(got_a, expected_a, "IK path a");
  check_all_converged_and_equal(got_b, expected_b, "IK path b");
}

BOOST_AUTO_TEST_CASE(moved_objects_solve_as_unmoved_ones) {
  const auto model = stewart_gough();
  const auto assembly = std::make_shared<const RobotAssembly>(model);
  const std::vector<VecX> path = input_path(*model, 4, 0.08, 1.0);
  const std::vector<VecX> first(path.begin(), path.begin() + 2), rest(path.begin() + 2, path.end());
  ForwardKinematics reference(assembly);
  BOOST_TEST(reference.default_equilibrium().converged);  // solved before either run (see above)
  const std::vector<Outcome> expected = run_fk(reference, path);
  // Halfway along the path the object moves (construction, then assignment): the Newton workspace and
  // the predictor's history go with it, so the rest of the path is solved exactly as without the move.
  ForwardKinematics fk(assembly);
  std::vector<Outcome> got = run_fk(fk, first);
  ForwardKinematics moved(std::move(fk));
  ForwardKinematics assigned = reference.with_fresh_state();
  assigned = std::move(moved);
  for (const Outcome& o : run_fk(assigned, rest)) got.push_back(o);
  check_all_converged_and_equal(got, expected, "moved FK");
  BOOST_CHECK_THROW(fk.solve(path[0]), std::logic_error);  // a moved-from object says so
  // A fresh state starts as a new object does, whatever the original solved before.
  ForwardKinematics fresh = assigned.with_fresh_state();
  BOOST_TEST(fresh.state() == ForwardKinematics(assembly).state());
  BOOST_TEST(!fresh.has_solution());

  const std::vector<Pose> poses = reachable_poses(assembly, path);
  InverseKinematics ik_reference(assembly, {platform_target()});
  const std::vector<Outcome> ik_expected = run_ik(ik_reference, poses);
  InverseKinematics ik(assembly, {platform_target()});
  std::vector<Outcome> ik_got = run_ik(ik, {poses[0], poses[1]});
  InverseKinematics ik_moved(std::move(ik));
  for (const Outcome& o : run_ik(ik_moved, {poses[2], poses[3]})) ik_got.push_back(o);
  check_all_converged_and_equal(ik_got, ik_expected, "moved IK");
}
