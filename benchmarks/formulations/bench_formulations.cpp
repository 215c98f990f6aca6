// Cost of the rod formulations over the element count: the condensed form (n, m from the closed-form
// balance) against the mixed form (n, m as splines), each exactly as asked (no formulation choice), on
// the two shipped Stewart-Gough robots: models/stewart_gough.urdf (gravity: the condensed rods carry
// distributed loads) and models/stewart_gough_teleop.urdf (no gravity), degree 6.
//   cold: a fresh ForwardKinematics (the assembly of the rods) and its first solve at the inputs below,
//         as `pcr fk` pays it;
//   warm: solves cycling through three input sets about 1 mm apart (as bench_scaling), each started
//         from the last solution.
// Times are process CPU time (the machine is shared; FK is single-threaded), medians over the repeats.
// The last column says which formulation is cheaper per cold FK and per warm solve. The same run
// also reports the condensed form with the general sparse LU (NewtonLinearSolver::Sparse), the
// baseline of the structured LU the rods use by default.
// usage: bench_formulations [repeats=5] [max_elements=1000]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

#include "common/robot_scenes.hpp"

using namespace pcr;

namespace {

double cpu_ms() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Cost {
  double cold_ms = NAN, warm_ms = NAN;
  int unknowns = 0;
  bool ok = true;
};

// The cold FK at u_cold and the warm solves through u_warm (see the file comment).
Cost measure(const std::shared_ptr<const RobotModel>& model, RodFormulation formulation, int elements,
             bool sparse_lu, int repeats, const VecX& u_cold, const VecX (&u_warm)[3]) {
  KinematicsOptions o;
  o.assembly.discretization = {formulation, 6, elements, MixedPoints::Midpoints};
  o.assembly.formulation_by_slenderness = false;
  o.assembly.condense_mixed_rods = false;  // exactly the formulation asked for
  if (sparse_lu) o.linear_solver = NewtonLinearSolver::Sparse;
  Cost cost;
  std::vector<double> cold, warm;
  for (int r = 0; r < repeats && cost.ok; ++r) {
    const double t0 = cpu_ms();
    ForwardKinematics fk(model, o);
    const RobotSolution s = fk.solve(u_cold);
    cold.push_back(cpu_ms() - t0);
    cost.unknowns = static_cast<int>(fk.state().size());
    cost.ok = s.summary.converged();
    for (int k = 0; k < 9 && cost.ok; ++k) {
      const double t = cpu_ms();
      const RobotSolution w = fk.solve(u_warm[(k + 1) % 3]);
      warm.push_back(cpu_ms() - t);
      cost.ok = w.summary.converged();
    }
  }
  cost.cold_ms = median(cold);
  cost.warm_ms = median(warm);
  return cost;
}

const char* cheaper(double condensed, double mixed) {
  return condensed <= mixed ? "condensed" : "mixed";
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const int max_elements = argc > 2 ? std::max(2, std::atoi(argv[2])) : 1000;
  std::printf("bench_formulations %d %d (repeats, max elements); degree 6, CPU ms, medians\n\n", repeats,
              max_elements);
  std::printf(
      "| model | gravity | E | unknowns condensed / mixed | cold FK condensed [ms] | cold FK mixed [ms] | "
      "warm condensed [ms] | warm mixed [ms] | condensed, sparse LU: cold / warm [ms] | cheaper cold / warm "
      "|\n|---|---|---|---|---|---|---|---|---|---|\n");
  const std::shared_ptr<const RobotModel> models[] = {bench::load_r5a(), bench::load_r5b()};
  for (const auto& model : models) {
    const bool gravity = !model->gravity().isZero(0.0);
    const VecX u0 = model->default_input_values();
    VecX u_cold = u0;
    for (int i = 0; i < u0.size(); ++i) u_cold[i] += (i % 2 == 0 ? 2e-3 : -1e-3);
    VecX u_warm[3] = {u_cold, u_cold, u_cold};
    for (int i = 0; i < u0.size(); ++i) {
      u_warm[1][i] += (i % 2 == 0 ? 1e-3 : -1e-3);
      u_warm[2][i] += 1e-3;
    }
    for (int elements : {2, 4, 8, 16, 32, 64, 128, 256, 512, 1000}) {
      if (elements > max_elements) break;
      // Fewer repeats where one FK takes long (medians of at least 3).
      const int r = elements >= 256 ? std::min(repeats, 3) : repeats;
      const Cost c = measure(model, RodFormulation::Condensed, elements, false, r, u_cold, u_warm);
      const Cost m = measure(model, RodFormulation::Mixed, elements, false, r, u_cold, u_warm);
      const Cost s = measure(model, RodFormulation::Condensed, elements, true, r, u_cold, u_warm);
      if (!c.ok || !m.ok || !s.ok) {
        std::printf("| %s | %s | %d | solve failed (condensed %d, mixed %d, sparse %d) |\n",
                    model->name().c_str(), gravity ? "yes" : "no", elements, c.ok, m.ok, s.ok);
        continue;
      }
      std::printf("| %s | %s | %d | %d / %d | %.2f | %.2f | %.3f | %.3f | %.2f / %.3f | %s / %s |\n",
                  model->name().c_str(), gravity ? "yes" : "no", elements, c.unknowns, m.unknowns, c.cold_ms,
                  m.cold_ms, c.warm_ms, m.warm_ms, s.cold_ms, s.warm_ms, cheaper(c.cold_ms, m.cold_ms),
                  cheaper(c.warm_ms, m.warm_ms));
      std::fflush(stdout);
    }
  }
  return 0;
}
