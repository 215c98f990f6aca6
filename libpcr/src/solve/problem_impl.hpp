#pragma once
// Problem's data (internal header of pcr::core): the description (blocks, fixed flags) and the structure
// derived from it (row layout, Jacobian and Hessian patterns with the scatter maps of the blocks).
// The derived structure is kept current by the non-const functions of Problem (problem.cpp,
// problem_structure.cpp); the const functions (problem_evaluate.cpp) only read it, so they may run in
// several threads at once on one Problem.
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "pcr/core/error.hpp"
#include "pcr/solve/problem.hpp"

namespace pcr {

using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// Rows of the active residual blocks, stacked in block order.
struct RowLayout {
  int num_rows = 0;
  std::vector<int> row_offset;     // per residual block, -1 when inactive
  std::vector<int> row_owner;      // per row, its residual block
  std::vector<int> kind_of_block;  // per residual block, index into kinds (-1 when inactive)
  std::vector<std::string> kinds;  // kinds of active blocks in order of first appearance
};

/// A compressed row-major pattern (column indices sorted within each row) and, per block, the positions
/// its dense entries are written to.
struct JacobianStructure {
  std::vector<int> outer{0};  // row pointers, num_rows + 1
  std::vector<int> inner;     // column of each non-zero
  // Scatter of each block's stacked dense row-major Jacobians into J: pairs (index in the dense array,
  // index into J's values) for its structurally nonzero entries, from scatter[scatter_offset[b]] to
  // scatter[scatter_offset[b + 1]] (empty for inactive blocks).
  std::vector<int> scatter_offset{0};
  std::vector<std::pair<int, int>> scatter;
};

/// Lower triangle (col <= row) of the union of the dense touched-variable squares of the active blocks
/// and objective terms; kept only while every one of them provides its Hessian (Problem::provides_hessian).
/// A block whose entries cannot be appended (they come before existing ones in row-major order, as a
/// coupling between a rod and a platform added after both) marks it stale: it is rebuilt from all blocks
/// when first used (Impl::hessian_pattern), once, instead of at every such addition.
struct HessianStructure {
  bool current = true;        // an empty problem provides its (empty) Hessian
  bool stale = false;         // outer, inner and the maps must be rebuilt before use
  std::vector<int> outer{0};  // row pointers, num_variables + 1
  std::vector<int> inner;
  // Per residual block / objective term: position in H of each local (i, j) entry of its dense square,
  // -1 in the strict upper triangle (empty for inactive blocks).
  std::vector<std::vector<int>> residual_map, objective_map;
};

struct NewtonPatternAnalysis;  // problem_system.hpp

/// Newton solvers' analyses of the structure (free-column pattern, the structured LU's symbolic analysis)
/// handed on between solvers over one Problem: a solver leaves its analysis here when it ends, and the
/// next solver of the same structure takes it instead of analysing again (an FK's default-equilibrium
/// solver, then its own). Guarded by a mutex: solvers in several threads may share one Problem.
/// Defined in problem_system.cpp.
class SolverAnalyses {
 public:
  /// The analysis left for this structure version and linear solver, removed from here (nullptr: none).
  std::shared_ptr<NewtonPatternAnalysis> take(std::uint64_t version, int linear_solver);
  /// Leaves an analysis for the next solver (replacing any other).
  void leave(std::shared_ptr<NewtonPatternAnalysis> analysis);

 private:
  std::mutex mutex_;
  std::shared_ptr<NewtonPatternAnalysis> newton_;
};

/// A Problem's SolverAnalyses. Solvers refer to it weakly (a solver may outlive its Problem); a copy of
/// the Problem starts with its own, empty one.
struct SolverAnalysesRef {
  std::shared_ptr<SolverAnalyses> ptr = std::make_shared<SolverAnalyses>();
  SolverAnalysesRef() = default;
  SolverAnalysesRef(const SolverAnalysesRef&) : SolverAnalysesRef() {}
  SolverAnalysesRef& operator=(const SolverAnalysesRef&) {
    ptr = std::make_shared<SolverAnalyses>();
    return *this;
  }
};

/// A mutex that a copy of its owner does not share (a copied Problem starts with its own).
struct OwnMutex {
  std::mutex mutex;
  OwnMutex() = default;
  OwnMutex(const OwnMutex&) {}
  OwnMutex& operator=(const OwnMutex&) { return *this; }
};

struct Problem::Impl {
  // ---- Description. ----
  std::vector<VariableBlock> variables;
  std::vector<char> fixed;
  int num_variables = 0;
  std::vector<std::shared_ptr<const ResidualBlock>> residuals;
  std::vector<char> active;
  std::vector<std::shared_ptr<const ObjectiveTerm>> objectives;
  std::uint64_t version = 1;  // bumped by every structural change

  // ---- Derived structure (current after every non-const call; the Hessian's when first used). ----
  RowLayout rows;
  JacobianStructure jacobian;
  HessianStructure hessian;
  mutable OwnMutex hessian_mutex;  // const evaluations in several threads may find it stale
  int blocks_without_hessian = 0;  // active residual blocks and objective terms that provide none
  // Scratch sizes an evaluation needs: touched variable blocks, dense Jacobian / gradient entries and
  // dense Hessian squares of the largest block.
  size_t max_block_variables = 1, max_dense = 1, max_square = 1;
  // ---- Solvers' analyses of the structure, handed on between them (keyed by version). ----
  SolverAnalysesRef analyses;

  int local_size(const std::vector<VariableId>& ids) const {
    int n = 0;
    for (VariableId v : ids) n += variables[v].size;
    return n;
  }
  void check_variable(VariableId id, const char* what) const {
    require(id >= 0 && id < static_cast<int>(variables.size()), what, ": variable id ", id,
            " out of range [0, ", variables.size(), ")");
  }
  void check_residual(ResidualId id, const char* what) const {
    require(id >= 0 && id < static_cast<int>(residuals.size()), what, ": residual id ", id,
            " out of range [0, ", residuals.size(), ")");
  }

  // problem_structure.cpp
  /// After add_variable_block: extends the patterns by the new (empty) rows / columns.
  void extend_variables();
  /// After add_residual_block: appends its rows and pattern entries.
  void append_residual(ResidualId b);
  /// After add_objective_term.
  void append_objective(int t);
  /// After an activity change: everything derived, from scratch.
  void rebuild();
  /// The Hessian pattern, rebuilt first if stale (thread-safe; Problem::provides_hessian() assumed).
  const HessianStructure& hessian_pattern() const;

 private:
  void add_rows(ResidualId b);
  void append_jacobian_rows(ResidualId b);
  void rebuild_hessian();
  bool append_hessian_square(const std::vector<VariableId>& ids, std::vector<int>& map);
  void update_hessian_after_addition(const std::vector<VariableId>& ids, std::vector<int>& map);
  void note_scratch(const std::vector<VariableId>& ids, size_t dense);
};

}  // namespace pcr
