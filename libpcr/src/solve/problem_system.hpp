#pragma once
// Private to NewtonSolver: a square, equality-only Problem as a NonlinearSystem (nonlinear_system.hpp)
// for the Newton loop. Unknowns: the free variables (a fixed variable keeps the value it has in x);
// residual r = c(x) - c_l; J0: the free columns of the problem's Jacobian, factorised by the bordered
// block LU when the problem tags variable groups (else, or when that fails, the sparse LU).
#include <memory>

#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/newton_solver.hpp"
#include "pcr/solve/nonlinear_system.hpp"
#include "pcr/solve/sparse_lu.hpp"

namespace pcr {

class SolverAnalyses;  // problem_impl.hpp

/// What ProblemSystem derives from the problem's structure, handed on to the next solver over the
/// problem when a solver ends (Problem::Impl::analyses): the same structure gives the same analysis, and
/// every factorisation overwrites the numeric parts (J_free's values, the structured LU's blocks).
struct NewtonPatternAnalysis {
  std::uint64_t version = 0;           // the Problem::structure_version() analysed
  NewtonLinearSolver linear_solver{};  // the NewtonOptions::linear_solver it was analysed for
  std::vector<int> value_map;
  Eigen::SparseMatrix<double> J_free;  // the free-column pattern
  BorderedBlockLu blocks;              // analysed; default-constructed (unusable) when not structured
};

class ProblemSystem : public NonlinearSystem {
 public:
  ProblemSystem(const Problem& problem, const NewtonOptions& options);
  /// Leaves the analysis of the structure to the next solver over the problem.
  ~ProblemSystem() override;
  ProblemSystem(const ProblemSystem&) = delete;
  ProblemSystem& operator=(const ProblemSystem&) = delete;
  /// Validates the problem for Newton and sizes the workspace (only when its structure changed).
  void prepare();
  /// The point the next solve starts from and moves (the caller's vector, swapped with the trial point).
  void bind(VecX& x) { x_ = &x; }
  /// c(x) at the current point (after an evaluation).
  const VecX& constraints() const { return c_; }
  /// "bordered blocks", "sparse" or "none".
  const char* factorization_kind() const;

  int size() const override { return static_cast<int>(target_.size()); }
  bool evaluate_start(bool with_jacobian, VecX& r) override;
  bool evaluate_trial(const VecX& dx, bool with_jacobian, VecX& r) override;
  void accept_trial() override;
  SystemStatus factorize(VecX& r) override;
  bool has_factorization() const override { return factored_ != Factored::None; }
  void solve(const VecX& b, VecX& y) override;
  SystemStatus newton_direction(const VecX& r, VecX& dx) override;
  /// residuals_within_round_off (newton_solver.hpp) with the last evaluated Jacobian.
  bool within_round_off(const VecX& r, double tolerance, double& bound) const override;

 private:
  /// J_free_, value_map_ and blocks_ from J_'s pattern: the analysis a solver over the problem left for
  /// this structure when there is one, else analysed here.
  void build_free_pattern();
  bool take_left_analysis();
  /// Factorises J_free_ (the structured LU unless sparse_only or it fails); false when singular.
  bool factorize_free(bool sparse_only);

  const Problem& problem_;
  const NewtonOptions& options_;
  std::weak_ptr<SolverAnalyses> analyses_;  // the problem's (Problem::Impl::analyses)
  std::uint64_t version_ = 0;               // problem structure the workspace was built for
  VecX* x_ = nullptr;

  std::vector<int> reduced_column_;                 // global column -> free column, -1 for a fixed one
  VecX target_;                                     // c_l = c_u of every row
  Eigen::SparseMatrix<double, Eigen::RowMajor> J_;  // full Jacobian in the problem's pattern
  Eigen::SparseMatrix<double> J_free_;              // free columns, column-major for the sparse LU
  std::vector<int> value_map_;      // J value index -> J_free value index, -1 for fixed columns
  std::vector<int> column_groups_;  // VariableBlock::group of each free column
  BorderedBlockLu blocks_;
  SparseLu lu_;
  bool sparse_analyzed_ = false;
  enum class Factored { None, Sparse, Blocks } factored_ = Factored::None;  // what holds J0
  VecX c_, c_trial_, x_trial_, linear_check_;
};

}  // namespace pcr
