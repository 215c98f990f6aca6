// Per-solve time of Ipopt and Newton on the Broyden tridiagonal system (Moré, Garbow, Hillstrom 1981),
// cold (MGH start x = -1) and warm (previous solution perturbed by 1e-3 sin(0.1 i)), with the unscaled
// residual reached. Ipopt: exact Hessian, scaling none or gradient-based; "badly scaled" multiplies every
// odd row by 1e4 (gradients above Ipopt's nlp_scaling_max_gradient = 100 trigger gradient-based scaling).
//   build/release/benchmarks/bench_solve
#include <benchmark/benchmark.h>

#include <cmath>

#include "../../tests/solve/test_problems.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"

using namespace pcr;

namespace {

constexpr double kBadScale = 1e4;

// Start point: x0 for cold, or the solution perturbed by 1e-3 sin(0.1 i) for warm.
template <typename Solver>
VecX start_point(const Problem& p, Solver& solver, bool warm) {
  VecX x = p.initial_values();
  if (!warm) return x;
  solver.solve(x);  // also leaves the multipliers of this solution in an Ipopt solver
  for (int i = 0; i < x.size(); ++i) x[i] += 1e-3 * std::sin(0.1 * i);
  return x;
}

void report(benchmark::State& state, const SolveSummary& s) {
  state.counters["residual"] = s.residual_max_abs;
  state.counters["iterations"] = s.iterations;
  state.counters["converged"] = s.converged() ? 1 : 0;
}

// Times solver.solve from `start` (a copy per solve) and reports the last summary; returns the last solution.
template <typename Solver>
VecX time_solves(benchmark::State& state, Solver& solver, const VecX& start) {
  SolveSummary s;
  VecX x;
  for (auto _ : state) {
    x = start;
    s = solver.solve(x);
    benchmark::DoNotOptimize(x.data());
  }
  report(state, s);
  return x;
}

// Args: n, warm (0/1), bad scaling (0/1).
void BM_Newton(benchmark::State& state) {
  const Problem p = test::broyden_problem(static_cast<int>(state.range(0)), state.range(2) ? kBadScale : 1.0);
  NewtonSolver solver(p);
  const VecX start = start_point(p, solver, state.range(1) != 0);
  time_solves(state, solver, start);
}

// Args: n, warm (0/1), bad scaling (0/1), Ipopt scaling (0 none, 1 gradient-based).
void BM_Ipopt(benchmark::State& state) {
  const Problem p = test::broyden_problem(static_cast<int>(state.range(0)), state.range(2) ? kBadScale : 1.0);
  IpoptOptions options;
  options.scaling = state.range(3) ? IpoptScaling::GradientBased : IpoptScaling::None;
  options.warm_start = state.range(1) != 0;
  IpoptSolver solver(p, options);
  const VecX start = start_point(p, solver, state.range(1) != 0);
  time_solves(state, solver, start);
}

// HS071 (Hock & Schittkowski 1981) from its published start, objective multiplied by 1 or 1e4: the
// case where Ipopt's scaling changes the iterates (objective gradients up to ~1e5 > 100).
// Args: objective scale exponent (0 or 4), Ipopt scaling (0 none, 1 gradient-based).
void BM_IpoptHs071(benchmark::State& state) {
  const Problem p = test::hs071_problem(std::pow(10.0, static_cast<double>(state.range(0))));
  IpoptOptions options;
  options.scaling = state.range(1) ? IpoptScaling::GradientBased : IpoptScaling::None;
  options.warm_start = false;
  IpoptSolver solver(p, options);
  const VecX x = time_solves(state, solver, p.initial_values());
  // Distance to the published minimiser (1, 4.7429994, 3.8211503, 1.3794082).
  state.counters["x_error"] =
      (x - (VecX(4) << 1.0, 4.7429994, 3.8211503, 1.3794082).finished()).cwiseAbs().maxCoeff();
}

// The set-up an IpoptSolver saves by reusing its IpoptApplication: construct one per solve.
void BM_IpoptFreshApplication(benchmark::State& state) {
  const Problem p = test::broyden_problem(static_cast<int>(state.range(0)));
  SolveSummary s;
  for (auto _ : state) {
    IpoptSolver solver(p);
    VecX x = p.initial_values();
    s = solver.solve(x);
    benchmark::DoNotOptimize(x.data());
  }
  report(state, s);
}

}  // namespace

BENCHMARK(BM_Newton)
    ->ArgsProduct({{100, 1000, 10000}, {0, 1}, {0, 1}})
    ->ArgNames({"n", "warm", "bad"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ipopt)
    ->ArgsProduct({{100, 1000, 10000}, {0, 1}, {0, 1}, {0, 1}})
    ->ArgNames({"n", "warm", "bad", "gscale"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IpoptHs071)
    ->ArgsProduct({{0, 4}, {0, 1}})
    ->ArgNames({"objexp", "gscale"})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IpoptFreshApplication)->Arg(100)->Arg(1000)->ArgNames({"n"})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
