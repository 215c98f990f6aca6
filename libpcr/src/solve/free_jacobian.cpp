#include "pcr/solve/free_jacobian.hpp"

#include "pcr/solve/sparse_lu.hpp"

namespace pcr {

FreeJacobian free_jacobian(const Problem& problem, const VecX& x) {
  VecX c;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;
  problem.evaluate_residuals_and_jacobian(x, c, J);
  return free_jacobian(problem, J);
}

FreeJacobian free_jacobian(const Problem& problem, const Eigen::SparseMatrix<double, Eigen::RowMajor>& J) {
  FreeJacobian out;
  std::vector<int> position(problem.num_variables(), -1);
  for (int v = 0; v < problem.num_variable_blocks(); ++v) {
    if (problem.variable_fixed(v)) continue;
    const VariableBlock& b = problem.variable(v);
    for (int k = 0; k < b.size; ++k) {
      position[b.offset + k] = static_cast<int>(out.columns.size());
      out.columns.push_back(b.offset + k);
      out.groups.push_back(b.group);
    }
  }
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(J.nonZeros());
  for (int r = 0; r < J.outerSize(); ++r)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(J, r); it; ++it)
      if (position[it.col()] >= 0) entries.emplace_back(r, position[it.col()], it.value());
  out.matrix.resize(J.rows(), static_cast<int>(out.columns.size()));
  out.matrix.setFromTriplets(entries.begin(), entries.end());
  out.matrix.makeCompressed();
  return out;
}

int jacobian_determinant_sign(const Problem& problem, const VecX& x) {
  const FreeJacobian J = free_jacobian(problem, x);
  if (J.matrix.rows() != J.matrix.cols() || J.matrix.rows() == 0) return 0;
  SparseLu lu;
  return lu.compute(J.matrix) ? lu.determinant_sign() : 0;
}

}  // namespace pcr
