// Continuation in the actuation inputs (robots/src/kinematics/input_continuation.hpp) on a model problem
// whose answers are known: the "equilibrium" at inputs u is x*(u) = u, a solve converges when it starts
// within 0.3 of x*(u) (its contraction region) and fails for u in a blocked region (no equilibrium
// reachable there, like the region behind a fold). Paths that run through the region must stop, paths
// around it must arrive at x*(u1) exactly.
#define BOOST_TEST_MODULE input_continuation
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../../robots/src/kinematics/coarse_continuation.hpp"
#include "../../robots/src/kinematics/continuation_weights.hpp"
#include "../../robots/src/kinematics/input_continuation.hpp"
#include "../robot_fixtures.hpp"

using namespace pcr;
using namespace pcr::kinematics;
using Vec2 = Eigen::Vector2d;

namespace {

struct ModelProblem {
  explicit ModelProblem(std::function<bool(const VecX&)> is_blocked) : blocked(std::move(is_blocked)) {}
  std::function<bool(const VecX&)> blocked;
  std::vector<VecX> solved_at;     // inputs of every converged solve, to check the path taken
  std::vector<VecX> tried_at;      // inputs of every solve
  std::vector<bool> intermediate;  // of every solve: whether it was flagged short of the line's end

  SolveSummary solve(const VecX& u, VecX& x, int max_jacobians) {
    SolveSummary s;
    s.iterations = 3;
    if (!blocked(u) && (x - u).norm() < 0.3 && max_jacobians >= 1) {
      x = u;
      s.status = SolveStatus::Converged;
      solved_at.push_back(u);
    } else {
      x.setConstant(1e3);  // a failed solve leaves an arbitrary iterate
      s.status = SolveStatus::MaxIterations;
      s.message = "model problem: outside the contraction region or blocked";
    }
    return s;
  }
  SolveAtInputs solver() {
    return [this](const VecX& u, VecX& x, int j, bool short_of_end) {
      tried_at.push_back(u);
      intermediate.push_back(short_of_end);
      return solve(u, x, j);
    };
  }
  bool passed_through(const Vec2& u) const {
    for (const VecX& v : solved_at)
      if ((v - u).norm() == 0.0) return true;
    return false;
  }
};

const Vec2 kStart(0.0, 0.0), kEnd(1.0, 1.0);
bool nothing_blocked(const VecX&) {
  return false;
}
/// A band along the diagonal, entered at t = 0.1 and left at t = 0.9: too long to step over.
bool diagonal_band(const VecX& u) {
  return std::abs(u[0] - u[1]) < 0.1 && u[0] + u[1] > 0.2 && u[0] + u[1] < 1.8;
}
/// A band along the u0 axis that contains the corner (1, 0).
bool axis_band(const VecX& u) {
  return std::abs(u[1]) < 0.1 && u[0] > 0.2 && u[0] < 1.5;
}

/// From kStart to `end` one input at a time (direct legs with 10 fresh Jacobians, steps with 8); x: the
/// state reached (kStart when it fails).
ContinuationResult one_input_at_a_time(ModelProblem& problem, const Vec2& end, int max_orders, VecX& x) {
  x = kStart;
  return continue_one_input_at_a_time(problem.solver(), kStart, end, 10, 8, max_orders, x);
}

}  // namespace

BOOST_AUTO_TEST_CASE(straight_line_reaches_the_end_in_steps_and_leaves_x_on_failure) {
  ModelProblem free_plane(nothing_blocked);
  VecX x = kStart;
  const ContinuationResult r = continue_along_line(free_plane.solver(), kStart, kEnd, 8, x);
  BOOST_TEST(r.converged);
  BOOST_TEST((x - kEnd).norm() == 0.0);
  // |u1 - u0| = 1.41 and each start must lie within 0.3 of the answer: several steps, the last at t = 1.
  BOOST_TEST(r.steps >= 5);
  BOOST_TEST(r.iterations == 3 * r.steps);
  BOOST_TEST(r.stopped_at.empty());

  ModelProblem blocked(diagonal_band);
  x = kStart;
  const ContinuationResult s = continue_along_line(blocked.solver(), kStart, kEnd, 8, x);
  BOOST_TEST(!s.converged);
  BOOST_TEST((x - kStart).norm() == 0.0);  // unchanged on failure
  BOOST_TEST(s.stopped_at.find("t = 0.") == 0u, s.stopped_at);
  // It stops before the band: every converged step lies on the diagonal short of it.
  for (const VecX& u : blocked.solved_at) BOOST_TEST(u[0] + u[1] <= 0.2);
}

BOOST_AUTO_TEST_CASE(one_input_at_a_time_goes_around_a_blocked_diagonal) {
  ModelProblem blocked(diagonal_band);
  VecX x;
  const ContinuationResult r = one_input_at_a_time(blocked, kEnd, 3, x);
  BOOST_TEST(r.converged);
  BOOST_TEST((x - kEnd).norm() == 0.0);
  BOOST_TEST(blocked.passed_through(Vec2(1.0, 0.0)));  // first order: input 0 first
}

BOOST_AUTO_TEST_CASE(a_blocked_first_order_is_followed_by_the_next) {
  // The band blocks the first leg of order (0, 1) and its end (1, 0); order (1, 0) via (0, 1) is free.
  ModelProblem blocked(axis_band);
  VecX x;
  const ContinuationResult r = one_input_at_a_time(blocked, kEnd, 3, x);
  BOOST_TEST(r.converged);
  BOOST_TEST((x - kEnd).norm() == 0.0);
  BOOST_TEST(blocked.passed_through(Vec2(0.0, 1.0)));  // second order: input 1 first
  // With one order only it fails and says where.
  ModelProblem again(axis_band);
  const ContinuationResult s = one_input_at_a_time(again, kEnd, 1, x);
  BOOST_TEST(!s.converged);
  BOOST_TEST((x - kStart).norm() == 0.0);
  BOOST_TEST(s.stopped_at.find("input 0 at t = ") == 0u, s.stopped_at);
}

BOOST_AUTO_TEST_CASE(a_long_leg_is_solved_directly_when_it_can_be) {
  // Inputs 0.2 apart: each leg is within the contraction region, so one direct solve per leg.
  ModelProblem free_plane(nothing_blocked);
  VecX x;
  const ContinuationResult r = one_input_at_a_time(free_plane, Vec2(0.2, 0.2), 3, x);
  BOOST_TEST(r.converged);
  BOOST_TEST(r.steps == 2);
  BOOST_TEST((x - Vec2(0.2, 0.2)).norm() == 0.0);
  // Equal end points: no leg, solved at u1 along the (zero-length) line.
  const ContinuationResult same = one_input_at_a_time(free_plane, kStart, 3, x);
  BOOST_TEST(same.converged);
  BOOST_TEST(same.steps >= 1);
  BOOST_TEST((x - kStart).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(line_steps_set_the_first_step_and_the_cut_and_only_the_end_is_solved_tightly) {
  ModelProblem free_plane(nothing_blocked);
  VecX x = kStart;
  const Vec2 end(2.0, 0.0);  // 2 long: a first step of 0.5 (1.0) fails (contraction region 0.3)
  const ContinuationResult r =
      continue_along_line(free_plane.solver(), kStart, end, 8, x, LineSteps{0.1, 0.3});
  BOOST_TEST(r.converged);
  BOOST_TEST((x - end).norm() == 0.0);
  // First step: 0.1 of the line = 0.2 from the start, within the region: converged there.
  BOOST_TEST((free_plane.tried_at.front() - Vec2(0.2, 0.0)).norm() == 0.0);
  // Every solve short of u1 is flagged intermediate, the one at u1 is not (and is the last).
  BOOST_TEST(free_plane.tried_at.size() == free_plane.intermediate.size());
  for (size_t k = 0; k < free_plane.tried_at.size(); ++k)
    BOOST_TEST(free_plane.intermediate[k] == ((free_plane.tried_at[k] - end).norm() > 0.0), "solve " << k);
  BOOST_TEST(!free_plane.intermediate.back());

  // A failed first step is cut to 0.3 of its length: 0.5 of the line (1.0 from the start) fails, the
  // next try is 0.15 of the line (0.3 from the start, on the region's boundary: fails), then 0.045
  // (tolerance 1e-15: round-off of u0 + t (u1 - u0) with t a product of two or three factors, a few ulp).
  ModelProblem again(nothing_blocked);
  x = kStart;
  const ContinuationResult s2 = continue_along_line(again.solver(), kStart, end, 8, x, LineSteps{0.5, 0.3});
  BOOST_TEST(s2.converged);
  BOOST_TEST(again.tried_at.size() >= 3u);
  BOOST_TEST(std::abs(again.tried_at[0][0] - 1.0) < 1e-15);   // 0.5 of 2
  BOOST_TEST(std::abs(again.tried_at[1][0] - 0.3) < 1e-15);   // 0.5 * 0.3 of 2
  BOOST_TEST(std::abs(again.tried_at[2][0] - 0.09) < 1e-15);  // 0.5 * 0.3^2 of 2
}

namespace {

/// A curved path: x*(u) = (u0, u1, 0.5 sqrt(u0 + 0.001)) (steep near u0 = 0, nearly straight further on);
/// a solve converges to x*(u) when it starts within 0.02 of it (max-norm), and records how far its start
/// was (the predictor's error) and where it was tried.
struct CurvedPath {
  static VecX answer(const VecX& u) {
    VecX x(3);
    x << u[0], u[1], 0.5 * std::sqrt(u[0] + 0.001);
    return x;
  }
  std::vector<double> tried_t;  // u0 of every solve (= t on the line from (0, 0) to (1, 1))
  std::vector<bool> converged;
  SolveAtInputs solver() {
    return [this](const VecX& u, VecX& x, int, bool) {
      tried_t.push_back(u[0]);
      SolveSummary s;
      s.iterations = 3;
      const VecX xs = answer(u);
      const bool ok = (x - xs).cwiseAbs().maxCoeff() < 0.02;
      converged.push_back(ok);
      s.status = ok ? SolveStatus::Converged : SolveStatus::MaxIterations;
      x = ok ? xs : VecX::Constant(3, 1e3);
      return s;
    };
  }
  int failures() const { return static_cast<int>(std::count(converged.begin(), converged.end(), false)); }
};

}  // namespace

// LineSteps::predictor_error: the next step from the error of the converged step's predictor (weights 1),
// short where the path bends (near u0 = 0) and long where it is straight; the target half the
// contraction region's radius. Against the growth factors from the same first step: both arrive exactly,
// the error control with fewer failed solves (each costs the step's budget of fresh Jacobians).
BOOST_AUTO_TEST_CASE(predictor_error_sets_the_steps_where_the_path_bends) {
  const Vec2 end(1.0, 1.0);
  const VecX weights = VecX::Ones(3);
  CurvedPath controlled, grown;
  VecX x = CurvedPath::answer(kStart);
  const ContinuationResult r =
      continue_along_line(controlled.solver(), kStart, end, 4, x, LineSteps{0.03, 0.3, 0.01}, weights);
  BOOST_TEST(r.converged);
  BOOST_TEST((x - CurvedPath::answer(end)).norm() == 0.0);
  VecX y = CurvedPath::answer(kStart);
  const ContinuationResult g = continue_along_line(grown.solver(), kStart, end, 4, y, LineSteps{0.03, 0.3});
  BOOST_TEST(g.converged);
  BOOST_TEST((y - CurvedPath::answer(end)).norm() == 0.0);
  BOOST_TEST_MESSAGE("solves " << r.steps << " (failed " << controlled.failures() << "), growth factors "
                               << g.steps << " (failed " << grown.failures() << ")");
  BOOST_TEST(controlled.failures() < grown.failures());
  // The converged steps grow along the line (the path straightens): the last one is longer than the first.
  std::vector<double> t_converged{0.0};
  for (size_t k = 0; k < controlled.tried_t.size(); ++k)
    if (controlled.converged[k]) t_converged.push_back(controlled.tried_t[k]);
  const size_t n = t_converged.size();
  BOOST_REQUIRE(n >= 4u);
  BOOST_TEST(t_converged[n - 2] - t_converged[n - 3] > 4.0 * (t_converged[2] - t_converged[1]));
  // Right after a failed solve the next converged step is not followed by a longer try (a fold ahead).
  auto start_of = [&controlled](size_t i) {  // t of the last converged solve before solve i
    double t = 0.0;
    for (size_t k = 0; k < i; ++k)
      if (controlled.converged[k]) t = controlled.tried_t[k];
    return t;
  };
  for (size_t k = 0; k + 2 < controlled.tried_t.size(); ++k) {
    if (controlled.converged[k] || !controlled.converged[k + 1]) continue;
    const double taken = controlled.tried_t[k + 1] - start_of(k + 1);
    BOOST_TEST(controlled.tried_t[k + 2] - controlled.tried_t[k + 1] <= taken * (1.0 + 1e-12), "solve " << k);
  }
}

// The coarse-mesh stage (robots/src/kinematics/coarse_continuation.hpp) on the Stewart-Gough robot: the
// continuation on the coarse mesh, carried to the requested mesh and finished there by Newton, must give
// the equilibrium the continuation on the requested mesh reaches (the same root of the same system), and
// where the Newton on the requested mesh fails, FK must fall back to that continuation.
namespace {

struct StewartGough {
  StewartGough()
      : robot(test::load_model("stewart_gough")),
        model(std::make_shared<const FkModel>(std::make_shared<const RobotAssembly>(robot, options.assembly),
                                              options)) {}
  KinematicsOptions options;  // defaults: Newton, tolerance 1e-10, degree 6 with 8 elements
  std::shared_ptr<const RobotModel> robot;
  std::shared_ptr<const FkModel> model;

  /// The first random inputs of the Stewart-Gough sweep (test_random_sweeps, seed 1).
  std::vector<VecX> random_inputs(int count) const {
    std::mt19937 rng(1);
    std::vector<std::uniform_real_distribution<double>> draw;
    for (const ActuationInput& in : robot->inputs()) draw.emplace_back(in.lower, in.upper);
    std::vector<VecX> out;
    for (int k = 0; k < count; ++k) {
      VecX u(static_cast<int>(draw.size()));
      for (int i = 0; i < u.size(); ++i) u[i] = draw[i](rng);
      out.push_back(u);
    }
    return out;
  }
  Vec3 platform(const VecX& x) const { return model->assembly->platform_pose(x, 0).position; }
};

/// The fast continuation of fk_strategies.cpp (4 fresh Jacobians per step, its step control).
constexpr LineSteps kFastLine{0.03, 0.3, 0.02};

}  // namespace

BOOST_AUTO_TEST_CASE(coarse_mesh_stage_reaches_the_equilibrium_of_the_continuation_on_the_requested_mesh) {
  const StewartGough sg;
  FkData data(sg.model);
  const DefaultEquilibrium& start = sg.model->default_equilibrium();
  BOOST_TEST_REQUIRE(start.converged);
  const VecX u0 = sg.robot->default_input_values();
  const ContinuationWeights weights = continuation_weights(*sg.model->assembly);
  for (const VecX& u : sg.random_inputs(3)) {
    VecX x_coarse;
    const CoarseOutcome coarse = coarse_then_fine(
        data, u0, nullptr, u, x_coarse,
        [&u](FkData& c, const ContinuationWeights& w, const VecX& from, VecX& x) {
          return continue_along_line(
              [&c](const VecX& v, VecX& xs, int j, bool) { return c.solve_at(v, xs, j, true); }, from, u, 4,
              x, kFastLine, w);
        });
    BOOST_TEST_REQUIRE(coarse.converged);
    // Then the continuation on the requested mesh (after the coarse stage: the Newton solver keeps its last
    // factorisation, which must not be that of the same inputs).
    VecX x_fine = start.x;
    const ContinuationResult fine =
        continue_along_line([&data](const VecX& v, VecX& x, int j,
                                    bool intermediate) { return data.solve_at(v, x, j, intermediate); },
                            u0, u, 4, x_fine, kFastLine, weights);
    BOOST_TEST_REQUIRE(fine.converged);
    BOOST_TEST(coarse.last.residual_max_abs <= sg.options.tolerance);
    BOOST_TEST(coarse.fine_jacobians <= kFineNewtonJacobians);
    BOOST_TEST((sg.model->assembly->inputs(x_coarse) - u).norm() == 0.0);
    // Both states solve the same system to |r|max <= 1e-10: one root, within 1e-6 m (the sweeps' bound of
    // "the same equilibrium"; the equilibria of other branches at these inputs are cm away).
    BOOST_TEST((sg.platform(x_coarse) - sg.platform(x_fine)).norm() <= 1e-6);
    BOOST_TEST_MESSAGE("coarse stage: " << coarse.steps << " coarse steps, " << coarse.fine_jacobians
                                        << " fresh Jacobians on the requested mesh; platform "
                                        << (sg.platform(x_coarse) - sg.platform(x_fine)).norm()
                                        << " m from the continuation's");
  }
}

BOOST_AUTO_TEST_CASE(fk_falls_back_to_the_continuation_on_the_requested_mesh_when_the_transfer_fails) {
  const StewartGough sg;
  const VecX u = sg.random_inputs(1).front();
  const CoarseMesh* mesh = sg.model->coarse_mesh->get(*sg.model);
  BOOST_TEST_REQUIRE(mesh != nullptr);
  // As FK solves it: by the coarse stage.
  FkData with_coarse(sg.model);
  VecX x_coarse;
  const SolveSummary s_coarse = solve_with_fallbacks(with_coarse, u, x_coarse);
  BOOST_TEST_REQUIRE(s_coarse.converged());
  BOOST_TEST(s_coarse.message.find("coarse-mesh continuation") != std::string::npos, s_coarse.message);
  // The Newton on the requested mesh given no fresh Jacobian: it fails after every coarse stage, and the
  // continuation on the requested mesh gives the result.
  FkData forced(sg.model);
  forced.coarse = std::make_shared<CoarseStage>(mesh->model);
  forced.coarse->fine_jacobians = 0;
  VecX x_fallback;
  const SolveSummary s_fallback = solve_with_fallbacks(forced, u, x_fallback);
  BOOST_TEST_REQUIRE(s_fallback.converged());
  BOOST_TEST(s_fallback.message.find("converged by continuation in the inputs from the default inputs") == 0,
             s_fallback.message);
  BOOST_TEST(forced.coarse->fine_result.size() == 0);  // no coarse stage returned a state
  BOOST_TEST(s_fallback.residual_max_abs <= sg.options.tolerance);
  // The same root (bound as above).
  BOOST_TEST((sg.platform(x_coarse) - sg.platform(x_fallback)).norm() <= 1e-6);
}
