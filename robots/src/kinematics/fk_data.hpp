#pragma once
// Forward kinematics model and data (internal header of pcr::robots; kinematics.hpp "Model and data"):
// FkModel is what an FK object solves on, immutable and shared; FkData is one object's per-solve state.
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "default_equilibrium.hpp"
#include "path_predictor.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/rods/stability/stability.hpp"
#include "pcr/solve/ipopt_solver.hpp"
#include "pcr/solve/newton_solver.hpp"

namespace pcr::kinematics {

/// Tolerance (max-abs of the dimensionless residuals) of the intermediate steps of a continuation in the
/// inputs: they only carry the state along; Newton to 1e-10 there took about half of the quasi-Newton
/// iterations of a random Stewart-Gough solve, to 1e-6 still 40 % more than to 1e-3, with the same
/// equilibria reached on 120 random inputs (docs/benchmarks.md "Random FK sweeps"). The state errors
/// it leaves are far below the predictor's (input_continuation.hpp LineSteps::predictor_error).
constexpr double kIntermediateTolerance = 1e-3;

class SharedCoarseMesh;  // coarse_continuation.hpp
struct CoarseStage;
std::shared_ptr<SharedCoarseMesh> new_shared_coarse_mesh();
struct FkModel;
/// The default equilibrium of the coarse mesh of `fine` (if it has one), its work added to `work`.
void solve_coarse_default_equilibrium(const FkModel& fine, SolveSummary& work);

struct FkModel {
  FkModel(std::shared_ptr<const RobotAssembly> assembly, const KinematicsOptions& options);
  std::shared_ptr<const RobotAssembly> assembly;  ///< its problem is the FK system (inputs fixed)
  KinematicsOptions options;
  std::vector<std::vector<BasisDerivatives>> sample_bases;  ///< read_solution

  /// The equilibrium at the model's default inputs, solved on first use (default_equilibrium.hpp: once
  /// per model and options, shared by every FK over them and thread-safe; its own solver, so the state
  /// is the same bits whichever FK asks first).
  const DefaultEquilibrium& default_equilibrium(bool* solved_here = nullptr) const {
    return default_start->get(*assembly, options, solved_here,
                              [this](SolveSummary& s) { solve_coarse_default_equilibrium(*this, s); });
  }
  /// Unstable modes of the default equilibrium (counted on first use, shared as it is; -1: unknown).
  int default_unstable_modes() const { return default_start->unstable_modes(*assembly); }
  /// The coarse mesh of the same rods (coarse_continuation.hpp), built on first use; nullptr in the coarse
  /// mesh's own FkModel.
  std::shared_ptr<SharedCoarseMesh> coarse_mesh = new_shared_coarse_mesh();

 private:
  std::shared_ptr<SharedDefaultEquilibrium> default_start;
};

struct FkData {
  explicit FkData(std::shared_ptr<const FkModel> model);
  FkData(const FkData&) = delete;
  FkData& operator=(const FkData&) = delete;

  /// One Newton (or Ipopt) solve at inputs u from x (u written into x first); Newton stops after
  /// max_jacobian_evaluations fresh Jacobians. intermediate: a continuation step that is not the end of
  /// the path, solved by Newton to kIntermediateTolerance only (the next step corrects the rest).
  SolveSummary solve_at(const VecX& u, VecX& x,
                        int max_jacobian_evaluations = std::numeric_limits<int>::max(),
                        bool intermediate = false);

  const std::shared_ptr<const FkModel> model;  // first: outlives the solvers that refer into it
  VecX x;                                      // the last converged solution (initial guess before)
  bool has_solution = false;
  int last_unstable_modes = -1;  // of x where its verdict was computed (stable or unstable), else -1
  int failed_jumps = 0;        // direct attempts from the last solution off a path that failed in a row
  int last_jacobian_sign = 0;  // of the last checked converged solve (check_stability)
  PathPredictor predictor;     // start point along a path of inputs
  std::unique_ptr<NewtonSolver> newton;               // on model->assembly->problem(), made on first use
  std::unique_ptr<NewtonSolver> newton_intermediate;  // the same, to kIntermediateTolerance
  std::unique_ptr<IpoptSolver> ipopt;                 // SolverKind::Ipopt, made on first use
  std::shared_ptr<CoarseStage> coarse;                // the coarse-mesh stage's data, made on first use
};

/// The attempts of ForwardKinematics::solve at `inputs` (fk_strategies.cpp): x out, the summary of the
/// attempt that converged (or of the last direct attempt, with what the fallbacks reached appended);
/// `verdict` (if given): the stability verdict of x when the attempt that converged computed it (the
/// energy minimisation accepts only stable equilibria), else empty.
SolveSummary solve_with_fallbacks(FkData& data, const VecX& inputs, VecX& x,
                                  std::optional<Stability>* verdict = nullptr);

}  // namespace pcr::kinematics
