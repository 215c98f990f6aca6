#include "pcr/solve/sparse_lu.hpp"

#include <Eigen/SparseLU>

namespace pcr {

// Natural column order: pcr's unknowns come rod by rod, control point after control point, so the
// Jacobians are banded per rod with a few coupling columns; in that order the LU keeps the band.
// COLAMD gave as much fill or more, up to 4x with the mixed form's midpoint collocation at 32-64
// elements per rod (R5b, 64 elements: 1.44e6 against 0.36e6 factor nonzeros; docs/benchmarks.md,
// "Midpoints against Greville points").
struct SparseLu::Impl {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::NaturalOrdering<int>> lu;
  bool factorized = false;
};

SparseLu::SparseLu() : impl_(std::make_unique<Impl>()) {}
SparseLu::~SparseLu() = default;
SparseLu::SparseLu(SparseLu&&) noexcept = default;
SparseLu& SparseLu::operator=(SparseLu&&) noexcept = default;

void SparseLu::analyze_pattern(const Eigen::SparseMatrix<double>& A) {
  impl_->factorized = false;
  impl_->lu.analyzePattern(A);
}

bool SparseLu::factorize(const Eigen::SparseMatrix<double>& A) {
  impl_->lu.factorize(A);
  impl_->factorized = impl_->lu.info() == Eigen::Success;
  return impl_->factorized;
}

bool SparseLu::compute(const Eigen::SparseMatrix<double>& A) {
  analyze_pattern(A);
  return factorize(A);
}

bool SparseLu::ok() const {
  return impl_->factorized;
}

std::string SparseLu::error_message() const {
  return impl_->lu.lastErrorMessage();
}

void SparseLu::solve(const VecX& b, VecX& x) const {
  x = impl_->lu.solve(b);
}

VecX SparseLu::solve(const VecX& b) const {
  return impl_->lu.solve(b);
}

MatX SparseLu::solve(const MatX& B) const {
  // No right-hand sides (e.g. the input Jacobian of a robot without inputs): an n x 0 solution, without
  // calling Eigen's SparseLU, which asserts on an empty right-hand side.
  if (B.cols() == 0) return MatX::Zero(impl_->lu.cols(), 0);
  return impl_->lu.solve(B);
}

int SparseLu::determinant_sign() const {
  if (!impl_->factorized) return 0;
  const double sign = impl_->lu.signDeterminant();  // diagonal of U and both permutations
  return sign > 0.0 ? 1 : (sign < 0.0 ? -1 : 0);
}

long SparseLu::nonzeros_l() const {
  return static_cast<long>(impl_->lu.nnzL());
}
long SparseLu::nonzeros_u() const {
  return static_cast<long>(impl_->lu.nnzU());
}

}  // namespace pcr
