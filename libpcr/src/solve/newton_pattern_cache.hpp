#pragma once
// Private to NewtonSolver: the analyses of Newton patterns (NewtonPatternAnalysis: the free-column
// pattern, its value map and the structured LU's analysis), kept process-wide and keyed by the pattern
// itself, so that a new Problem of a structure solved before (e.g. a rod of the same formulation, degree,
// element count and end kinds, with other stiffnesses, loads or end frames) skips the analysis. The
// analysis is a function of the key alone (ProblemSystem::build_free_pattern), so a hit gives what the
// analysis would. Thread-safe; bounded in entries and stored nonzeros (the oldest entries leave first).
#include <memory>
#include <vector>

#include "problem_system.hpp"

namespace pcr {

/// What the analysis depends on: the row-major Jacobian pattern, the free column of each column (-1
/// fixed), the variable group of each free column and the linear solver option.
struct NewtonPatternKey {
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& J;
  const std::vector<int>& reduced_column;
  const std::vector<int>& column_groups;
  NewtonLinearSolver linear_solver;
};

/// The cached analysis of exactly this key, or null.
std::shared_ptr<const NewtonPatternAnalysis> find_newton_pattern(const NewtonPatternKey& key);

/// Keeps `analysis` (value_map, J_free, blocks) for `key`; patterns too large for the cache are not kept.
void keep_newton_pattern(const NewtonPatternKey& key, const NewtonPatternAnalysis& analysis);

}  // namespace pcr
