// Run time against error of the collocation robot solver (issue "benchmarks"):
//  - R5a (models/stewart_gough.urdf): cold FK at the default inputs and cold IK to the scene target;
//  - R5b (models/stewart_gough_teleop.urdf): warm-started IK along the teleoperation path (from
//    (0, 0.02, 0.48) m in 100 steps of (0, 0.001, 0.001) m and back), solves per second, and the cost
//    of the operations a warm solve is made of (printed).
// Error: max over the inputs (IK) or platform position (FK) against a reference computed in the same
// run with 32 elements of degree 5 (converged to < 1e-9 m, docs/benchmarks.md). The mixed form at the default
// degree and midpoints (method collocation-mixed-newton) over the element counts and, as baselines of
// those choices, degree 5 and the Greville points of Weeger et al. (collocation-mixed-greville-newton;
// MixedPoints). Scenes:
// benchmarks/common/robot_scenes.hpp. CSV columns as the other
// benchmarks: scene,method,settings,error,time_median_s,time_min_s,time_max_s,iterations,time_mean_s.
// R6 (models/six_rus.urdf, the 6-RUS robot): benchmarks/robots/six_rus_rows.hpp.
// usage: bench_robots [out.csv] [six_rus]   (six_rus: only the R6 rows)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "common/bench_csv.hpp"
#include "common/robot_scenes.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "six_rus_rows.hpp"

using namespace pcr;
using namespace pcr::bench;
using Clock = std::chrono::steady_clock;

namespace {

struct Mesh {
  int degree;
  int elements;
  MixedPoints points;
  bool sparse_lu = false;    // baseline: the general sparse LU instead of the default structured one
  double tolerance = 1e-10;  // Newton tolerance (KinematicsOptions; 1e-10 the default)
  RodFormulation formulation = RodFormulation::Mixed;
};

std::string settings_of(const Mesh& mesh) {
  std::string s = "p=" + std::to_string(mesh.degree) + ";E=" + std::to_string(mesh.elements);
  if (mesh.tolerance != 1e-10) {
    char t[32];
    std::snprintf(t, sizeof t, ";tol=%g", mesh.tolerance);
    s += t;
  }
  return s;
}

std::string method_of(const Mesh& mesh) {
  const std::string base = mesh.formulation == RodFormulation::Condensed ? "collocation-condensed-newton"
                           : mesh.points == MixedPoints::Midpoints       ? "collocation-mixed-newton"
                                                                   : "collocation-mixed-greville-newton";
  return mesh.sparse_lu ? base + "-sparse-lu" : base;
}

const char* label_of(const Mesh& mesh) {
  if (mesh.sparse_lu) return "sparse LU";
  if (mesh.formulation == RodFormulation::Condensed) return "condensed";
  return to_string(mesh.points);
}

KinematicsOptions options(int degree, int elements, double tolerance = 1e-10,
                          MixedPoints points = MixedPoints::Midpoints, bool sparse_lu = false,
                          RodFormulation formulation = RodFormulation::Mixed) {
  KinematicsOptions o;
  o.assembly.discretization = {formulation, degree, elements, points};
  o.assembly.formulation_by_slenderness = false;  // R5a, R5b: slender rods, mixed by slenderness anyway
  o.assembly.condense_mixed_rods = false;         // exactly the formulation asked for
  o.tolerance = tolerance;
  if (sparse_lu) o.linear_solver = NewtonLinearSolver::Sparse;
  return o;
}

// What one Newton step of a warm R5b IK solve is made of, at the path's start solution: one residual
// evaluation and one solve with the LU factors of the free Jacobian, plus, when a fresh Jacobian is
// taken, its evaluation (dual numbers) and a numeric factorisation on the kept symbolic analysis; for
// the default structured LU (BorderedBlockLu, one group per rod) and the sparse LU (SparseLu, the
// baseline), on the same matrix. Printed only (no error to put beside it).
void print_operation_costs(const InverseKinematics& ik) {
  const Problem& problem = ik.problem();
  const VecX& x = ik.state();
  VecX c(problem.num_rows());
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  problem.evaluate_residuals_and_jacobian(x, c, J);
  const FreeJacobian free = free_jacobian(problem, J);
  SparseLu lu;
  lu.compute(free.matrix);
  BorderedBlockLu blocks;
  if (!blocks.analyze_pattern(free.matrix, free.groups) || !blocks.factorize(free.matrix)) {
    std::printf("  structured LU failed: %s\n", blocks.error_message().c_str());
    return;
  }
  const VecX rhs = c;
  VecX dx;
  const Repeats many{20, 2000, 0.2}, few{5, 200, 0.2};
  const Timing residual = time_repeated([&] { problem.evaluate_residuals(x, c); }, many);
  const Timing jacobian = time_repeated([&] { problem.evaluate_residuals_and_jacobian(x, c, J); }, few);
  const Timing factorize = time_repeated([&] { lu.factorize(free.matrix); }, few);
  const Timing solve = time_repeated([&] { lu.solve(rhs, dx); }, many);
  const Timing block_factorize = time_repeated([&] { blocks.factorize(free.matrix); }, few);
  const Timing block_solve = time_repeated([&] { blocks.solve(rhs, dx); }, many);
  std::printf(
      "  per operation (median): residual %.1f us, Jacobian %.2f ms; structured LU (border %d): solve %.1f "
      "us, "
      "factorisation %.2f ms, %ld factor entries; sparse LU: solve %.1f us, factorisation %.2f ms, %ld + %ld "
      "factor nonzeros\n",
      residual.median * 1e6, jacobian.median * 1e3, blocks.border_size(), block_solve.median * 1e6,
      block_factorize.median * 1e3, blocks.factor_nonzeros(), solve.median * 1e6, factorize.median * 1e3,
      lu.nonzeros_l(), lu.nonzeros_u());
}

// R5a: cold FK at the default inputs and cold IK to the scene target (a new solver object per solve) for each
// mesh, against references at 32 elements of degree 5; prints the assembly time of each mesh. False when a
// reference does not converge.
bool run_r5a_cold(BenchCsv& csv, const std::shared_ptr<const RobotModel>& r5a,
                  const std::vector<Mesh>& meshes) {
  const Pose target = r5a_target();
  InverseKinematics ik_ref(r5a, {platform_target()}, options(5, 32, 1e-11));
  const RobotSolution ik_reference = ik_ref.solve({target});
  ForwardKinematics fk_ref(r5a, options(5, 32, 1e-11));
  const RobotSolution fk_reference = fk_ref.solve(r5a->default_input_values());
  if (!ik_reference.summary.converged() || !fk_reference.summary.converged()) {
    std::cerr << "bench_robots: reference did not converge\n";
    return false;
  }
  for (const Mesh& mesh : meshes) {
    const char* points = label_of(mesh);
    // The cold solves' first part: building the solver (assembly of the rods' collocation blocks and the
    // couplings). Printed only, there is no error to put beside it.
    const KinematicsOptions o =
        options(mesh.degree, mesh.elements, 1e-10, mesh.points, mesh.sparse_lu, mesh.formulation);
    const Timing assembly = time_repeated([&] { ForwardKinematics fk(r5a, o); }, {5, 50, 0.2});
    std::printf("R5a assembly %-8s %-9s  median %.2f ms\n", settings_of(mesh).c_str(), points,
                assembly.median * 1e3);
    for (const std::string problem : {"FK", "IK"}) {
      double error = 0;
      int iterations = 0;
      const Timing t = time_repeated(
          [&] {
            RobotSolution s;
            if (problem == "FK") {
              ForwardKinematics fk(r5a, o);
              s = fk.solve(r5a->default_input_values());
              error = (s.platforms[0].position - fk_reference.platforms[0].position).norm();
            } else {
              InverseKinematics ik(r5a, {platform_target()}, o);
              s = ik.solve({target});
              error = (s.inputs - ik_reference.inputs).lpNorm<Eigen::Infinity>();
            }
            iterations = s.summary.iterations;
            if (!s.summary.converged()) error = NAN;
          },
          {5, 5, 0.0});
      csv.row("R5a_" + problem + "_cold", method_of(mesh), settings_of(mesh), error, t, iterations);
      std::printf("R5a %s cold  %-8s %-9s  error %.2e m  median %.2f ms\n", problem.c_str(),
                  settings_of(mesh).c_str(), points, error, t.median * 1e3);
    }
  }
  return true;
}

// R5b reference inputs along the path at 32 elements of degree 5 (empty when a solve fails).
std::vector<VecX> r5b_reference(const std::shared_ptr<const RobotModel>& r5b, const std::vector<Pose>& path) {
  std::vector<VecX> reference;
  InverseKinematics ik(r5b, {platform_target()}, options(5, 32, 1e-11));
  for (const Pose& p : path) {
    const RobotSolution s = ik.solve({p});
    if (!s.summary.converged()) {
      std::cerr << "bench_robots: R5b reference failed at " << p.position.transpose() << "\n";
      return {};
    }
    reference.push_back(s.inputs);
  }
  return reference;
}

// R5b: warm-started IK along the path, five passes (1,000 solves: the fresh Jacobians, 1 in ~50, average
// out), timed per solve; the error is the largest input error against the reference over all passes.
void run_r5b_path(BenchCsv& csv, const std::shared_ptr<const RobotModel>& r5b, const std::vector<Pose>& path,
                  const std::vector<VecX>& reference, const Mesh& mesh) {
  InverseKinematics ik(
      r5b, {platform_target()},
      options(mesh.degree, mesh.elements, mesh.tolerance, mesh.points, mesh.sparse_lu, mesh.formulation));
  ik.solve({path[0]});  // start of the path (cold), not timed
  std::vector<double> times;
  double error = 0;
  int iterations = 0, failures = 0, jacobians = 0;
  std::string passes;  // solves/s and fresh Jacobians of each pass (the first starts from a cold solve)
  for (int pass = 0; pass < 5; ++pass) {
    double pass_time = 0.0;
    const int pass_jacobians = jacobians;
    for (size_t k = 1; k < path.size(); ++k) {
      const auto t0 = Clock::now();
      const RobotSolution s = ik.solve({path[k]});
      times.push_back(seconds_since(t0));
      pass_time += times.back();
      iterations += s.summary.iterations;
      jacobians += s.summary.jacobian_evaluations;
      if (!s.summary.converged()) ++failures;
      error = std::max(error, (s.inputs - reference[k]).lpNorm<Eigen::Infinity>());
    }
    char text[64];
    std::snprintf(text, sizeof text, "%s%.0f/s (%d)", pass == 0 ? "" : ", ", (path.size() - 1) / pass_time,
                  jacobians - pass_jacobians);
    passes += text;
  }
  const Timing t = summarise(times);
  if (failures > 0) error = NAN;
  csv.row("R5b_teleop_IK_warm", method_of(mesh), settings_of(mesh), error, t,
          double(iterations) / times.size());
  std::printf(
      "R5b warm IK %-17s %-9s  max input error %.2e m  median %.3f ms/solve, mean %.3f ms/solve (%.0f "
      "solves/s), %.2f it/solve, %d fresh Jacobians in %zu solves%s\n",
      settings_of(mesh).c_str(), label_of(mesh), error, t.median * 1e3, t.mean * 1e3, 1.0 / t.mean,
      double(iterations) / times.size(), jacobians, times.size(), failures ? "  FAILURES" : "");
  std::printf("  per pass: %s (fresh Jacobians)\n", passes.c_str());
}

// R5a cold rows: the default degree (AssemblyOptions) over the element counts, and at 8 elements the
// baselines of the default's choice: degree 5, degree 5 at the Greville points. Rows named "condensed":
// the condensed form (the default for these rods; R5a's rods carry gravity, so n, m also read the
// integral of p); the mixed rows are its baseline.
std::vector<Mesh> r5a_meshes() {
  const int p = AssemblyOptions().discretization.degree;
  const MixedPoints mid = MixedPoints::Midpoints;
  const RodFormulation condensed = RodFormulation::Condensed;
  return {{p, 2, mid},
          {p, 4, mid},
          {p, 8, mid},
          {p, 8, mid, true},
          {p, 16, mid},
          {5, 8, mid},
          {5, 8, MixedPoints::Greville},
          {p, 2, mid, false, 1e-10, condensed},
          {p, 4, mid, false, 1e-10, condensed},
          {p, 8, mid, false, 1e-10, condensed},
          {p, 16, mid, false, 1e-10, condensed},
          {5, 8, mid, false, 1e-10, condensed}};
}

// R5b teleoperation: the size of the square IK system (structural zeros of the blocks left out) and the
// cost of a warm solve's operations.
void print_r5b_operation_costs(const std::shared_ptr<const RobotModel>& r5b, const std::vector<Pose>& path) {
  const int p = AssemblyOptions().discretization.degree;
  const MixedPoints mid = MixedPoints::Midpoints;
  const RodFormulation condensed = RodFormulation::Condensed;
  for (const Mesh& mesh :
       {Mesh{p, 8, mid}, Mesh{5, 8, mid}, Mesh{p, 16, mid}, Mesh{p, 8, mid, false, 1e-10, condensed},
        Mesh{5, 16, mid, false, 1e-10, condensed}}) {
    InverseKinematics ik(r5b, {platform_target()},
                         options(mesh.degree, mesh.elements, 1e-10, mesh.points, false, mesh.formulation));
    const Problem& problem = ik.problem();
    std::printf("R5b IK %s %s: %d rows, %d Jacobian nonzeros\n", settings_of(mesh).c_str(),
                to_string(mesh.formulation), problem.num_rows(), problem.jacobian_nonzeros());
    if (ik.solve({path[0]}).summary.converged()) print_operation_costs(ik);
  }
}

// R5b timed warm solves. Greville points only at 8 elements (at 4, warm Newton solves fail along the
// path and each failure goes to Ipopt, minutes).
std::vector<Mesh> r5b_path_meshes() {
  const int p = AssemblyOptions().discretization.degree;
  const MixedPoints mid = MixedPoints::Midpoints;
  const RodFormulation condensed = RodFormulation::Condensed;
  return {{p, 2, mid},
          {p, 4, mid},
          {p, 8, mid},
          {p, 8, mid, true},  // sparse LU baseline
          {p, 16, mid},
          {5, 8, mid},
          {5, 16, mid},
          {5, 16, mid, true},  // sparse LU baseline
          {5, 8, MixedPoints::Greville},
          // a looser Newton tolerance (docs/cli.md: T = 100 x the accuracy)
          {p, 8, mid, false, 1e-6},
          {p, 8, mid, true, 1e-6},
          {5, 16, mid, false, 1e-6},
          {5, 16, mid, true, 1e-6},
          // the condensed form (rods without distributed loads): 7 instead of 13 unknowns per control point
          {p, 8, mid, false, 1e-10, condensed},
          {p, 16, mid, false, 1e-10, condensed},
          {p, 8, mid, false, 1e-6, condensed},
          {7, 6, mid, false, 1e-6, condensed},
          {5, 8, mid, false, 1e-6, condensed},
          {5, 16, mid, false, 1e-6, condensed},
          {7, 12, mid, false, 1e-6, condensed},
          // 1e-7: below 1e-8 m on 14 and 16 elements (the path predictor amplifies the convergence error
          // of the last solutions, so 1e-6 leaves ~8e-8 m there)
          {5, 14, mid, false, 1e-7, condensed},
          {5, 16, mid, false, 1e-7, condensed}};
}

}  // namespace

int main(int argc, char** argv) {
  BenchCsv csv(argc > 1 ? argv[1] : "benchmarks/results/robots.csv");
  if (!csv.ok()) {
    std::cerr << "bench_robots: cannot write " << csv.path() << "\n";
    return 2;
  }
  if (argc > 2 && std::string(argv[2]) == "six_rus") return bench_six_rus(csv);
  const auto r5a = load_r5a();
  const auto r5b = load_r5b();
  if (!run_r5a_cold(csv, r5a, r5a_meshes())) return 1;
  // R5b teleoperation: the cost of a warm solve's operations, reference inputs along the path at 32
  // elements, then timed warm solves.
  const std::vector<Pose> path = r5b_path();
  print_r5b_operation_costs(r5b, path);
  const std::vector<VecX> reference = r5b_reference(r5b, path);
  if (reference.empty()) return 1;
  for (const Mesh& mesh : r5b_path_meshes()) run_r5b_path(csv, r5b, path, reference, mesh);
  if (bench_six_rus(csv) != 0) return 1;
  std::cout << "wrote " << csv.path() << "\n";
  return 0;
}
