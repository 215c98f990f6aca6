#include "pcr/math/dense_decompositions.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace pcr {

SymmetricEigen symmetric_eigen(const MatX& A) {
  const Eigen::SelfAdjointEigenSolver<MatX> eig(A);
  return {eig.eigenvalues(), eig.eigenvectors()};
}

VecX symmetric_eigenvalues(const MatX& A) {
  return Eigen::SelfAdjointEigenSolver<MatX>(A, Eigen::EigenvaluesOnly).eigenvalues();
}

RightSingularVectors right_singular_vectors(const MatX& C) {
  const Eigen::JacobiSVD<MatX> svd(C, Eigen::ComputeFullV);
  return {svd.singularValues(), svd.matrixV()};
}

VecX singular_values(const MatX& C) { return Eigen::JacobiSVD<MatX>(C).singularValues(); }

}  // namespace pcr
