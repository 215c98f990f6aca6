// The shared Newton loop (newton_loop.hpp) on small dense systems with analytic roots: quadratic
// convergence, Levenberg-Marquardt off a singular start, the line search, chord steps.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "pcr/solve/dense_system.hpp"
#include "pcr/solve/newton_loop.hpp"

using namespace pcr;

namespace {

// r(x) and J(x) given as functions; x moves by x + dx; records max |r| of every point it accepts.
class FunctionSystem : public DenseNonlinearSystem<Eigen::Dynamic> {
 public:
  using Residual = std::function<VecX(const VecX&)>;
  using Jacobian = std::function<MatX(const VecX&)>;
  FunctionSystem(Residual r, Jacobian J, VecX x0) : r_(std::move(r)), J_(std::move(J)), x_(std::move(x0)) {}
  const VecX& x() const { return x_; }
  void move_to(const VecX& x) { x_ = x; }
  std::vector<double> history;  // max |r_i| at each current point the loop checks

  int size() const override { return static_cast<int>(x_.size()); }
  PointUpdate on_new_point(double r_max, VecX&) override {
    history.push_back(r_max);
    return PointUpdate::Unchanged;
  }

 protected:
  bool evaluate_at(const VecX* dx, VecX& r, MatX* J) override {
    trial_ = dx ? VecX(x_ + *dx) : x_;
    r = r_(trial_);
    if (J) *J = J_(trial_);
    return true;
  }
  void accept() override { x_ = trial_; }

 private:
  Residual r_;
  Jacobian J_;
  VecX x_, trial_;
};

// Circle x^2 + y^2 = 4 and line y = x from (1, 0.2): root (sqrt 2, sqrt 2).
FunctionSystem circle_and_line(double x0, double y0) {
  return FunctionSystem(
      [](const VecX& v) {
        return VecX((VecX(2) << v[0] * v[0] + v[1] * v[1] - 4.0, v[1] - v[0]).finished());
      },
      [](const VecX& v) { return MatX((MatX(2, 2) << 2 * v[0], 2 * v[1], -1.0, 1.0).finished()); },
      (VecX(2) << x0, y0).finished());
}

}  // namespace

BOOST_AUTO_TEST_CASE(loop_converges_quadratically_to_the_analytic_root) {
  FunctionSystem system = circle_and_line(1.0, 0.2);
  NewtonLoopOptions o;
  o.tolerance = 1e-14;
  NewtonLoop loop(o);
  const NewtonLoopResult result = loop.run(system, {50}, false);
  BOOST_TEST_REQUIRE((result.status == SolveStatus::Converged), result.message);
  BOOST_TEST(result.jacobian_evaluations == result.iterations);  // plain Newton: one per step
  // |J^-1| ~ 1 at the root: |x - x*| <~ |r| <= 1e-14, plus rounding of the coordinates (~4e-16).
  BOOST_TEST(std::abs(system.x()[0] - std::sqrt(2.0)) <= 1e-13);
  BOOST_TEST(std::abs(system.x()[1] - std::sqrt(2.0)) <= 1e-13);
  // Quadratic convergence: once close (|r| < 0.1), |r_{k+1}| <= C |r_k|^2 with C ~ |F''| |J^-1|^2 ~ 1;
  // bound C <= 10. The last point may sit at round-off, so only pairs with |r_{k+1}| > 1e-15 count.
  int quadratic_pairs = 0;
  for (size_t k = 0; k + 1 < system.history.size(); ++k) {
    const double e = system.history[k], next = system.history[k + 1];
    if (e < 0.1 && next > 1e-15) {
      BOOST_TEST(next <= 10.0 * e * e, "step " << k << ": " << e << " -> " << next);
      ++quadratic_pairs;
    }
  }
  BOOST_TEST(quadratic_pairs >= 2);
}

// r = (x^2 - 1, x + y - 3): J = [[2x, 0], [1, 1]] is singular at the start x = 0, where Newton has no
// step; Levenberg-Marquardt's gradient direction J^T r = (-2, -2) is not zero and leaves the singular
// line, and Newton then finishes at a root (1, 2) or (-1, 4).
BOOST_AUTO_TEST_CASE(levenberg_marquardt_moves_off_a_singular_start) {
  auto make = [] {
    return FunctionSystem(
        [](const VecX& v) { return VecX((VecX(2) << v[0] * v[0] - 1.0, v[0] + v[1] - 3.0).finished()); },
        [](const VecX& v) { return MatX((MatX(2, 2) << 2 * v[0], 0.0, 1.0, 1.0).finished()); },
        (VecX(2) << 0.0, 1.0).finished());
  };
  NewtonLoopOptions o;
  FunctionSystem plain = make();
  const NewtonLoopResult newton_only = NewtonLoop(o).run(plain, {50}, false);
  BOOST_TEST((newton_only.status == SolveStatus::Singular), newton_only.message);
  BOOST_TEST(plain.x()[0] == 0.0);  // no step taken
  o.levenberg_marquardt = true;
  FunctionSystem damped = make();
  const NewtonLoopResult lm = NewtonLoop(o).run(damped, {50}, false);
  BOOST_TEST_REQUIRE((lm.status == SolveStatus::Converged), lm.message);
  const double x = damped.x()[0], y = damped.x()[1];
  // |J^-1| <= 1 at both roots: the coordinates are within a few times the tolerance 1e-10.
  BOOST_TEST(std::abs(std::abs(x) - 1.0) <= 1e-9);
  BOOST_TEST(std::abs(x + y - 3.0) <= 1e-9);
}

// r = atan(x) from x = 2: the full Newton step overshoots to x = -3.54 with |r| larger (Newton without
// damping diverges from |x| > 1.39); the backtracking line search converges to the root 0.
BOOST_AUTO_TEST_CASE(line_search_damps_an_overshooting_newton_step) {
  auto make = [] {
    return FunctionSystem([](const VecX& v) { return VecX::Constant(1, std::atan(v[0])); },
                          [](const VecX& v) { return MatX::Constant(1, 1, 1.0 / (1.0 + v[0] * v[0])); },
                          VecX::Constant(1, 2.0));
  };
  NewtonLoopOptions o;
  FunctionSystem damped = make();
  const NewtonLoopResult result = NewtonLoop(o).run(damped, {50}, false);
  BOOST_TEST_REQUIRE((result.status == SolveStatus::Converged), result.message);
  BOOST_TEST(std::abs(damped.x()[0]) <= 1e-10);  // atan'(0) = 1: |x| = |r| <= 1e-10
  BOOST_TEST(damped.history.size() >= 2u);
  BOOST_TEST(damped.history[1] < damped.history[0]);  // the accepted first step decreased |r|
  // Only full steps (min_step = 1): the first step is rejected and nothing is left to try.
  o.min_step = 1.0;
  FunctionSystem full_steps = make();
  const NewtonLoopResult undamped = NewtonLoop(o).run(full_steps, {50}, false);
  BOOST_TEST((undamped.status == SolveStatus::Failed), undamped.message);
  BOOST_TEST(undamped.message.find("line search") != std::string::npos, undamped.message);
}

// Chord steps: a second solve from a nearby start reuses the first one's factorisation J0 and needs no
// fresh Jacobian (while each step halves |r|); without quasi-Newton steps it takes one per step.
BOOST_AUTO_TEST_CASE(chord_steps_reuse_the_last_factorisation) {
  NewtonLoopOptions o;
  o.quasi_newton = QuasiNewtonKind::Chord;
  NewtonLoop loop(o);
  FunctionSystem system = circle_and_line(1.0, 0.2);
  BOOST_TEST_REQUIRE((loop.run(system, {50}, false).status == SolveStatus::Converged));
  BOOST_TEST_REQUIRE(system.has_factorization());
  // 1e-3 from the root: the chord contraction |I - J0^-1 J(x)| = O(1e-3) (J0 of a point near the root).
  const VecX near = (VecX(2) << std::sqrt(2.0) + 1e-3, std::sqrt(2.0) - 1e-3).finished();
  system.move_to(near);
  const NewtonLoopResult chord = loop.run(system, {50}, true);
  BOOST_TEST_REQUIRE((chord.status == SolveStatus::Converged), chord.message);
  BOOST_TEST(chord.jacobian_evaluations == 0);
  BOOST_TEST(chord.iterations >= 1);
  BOOST_TEST(std::abs(system.x()[0] - std::sqrt(2.0)) <= 1e-9);  // |J^-1| ~ 1, |r| <= 1e-10
  system.move_to(near);
  const NewtonLoopResult newton = loop.run(system, {50}, false);
  BOOST_TEST_REQUIRE((newton.status == SolveStatus::Converged), newton.message);
  BOOST_TEST(newton.jacobian_evaluations == newton.iterations);
}
