#include "pcr/math/tangent_space_spectrum.hpp"

#include <Eigen/QR>
#include <sstream>
#include <stdexcept>

#include "pcr/math/dense_decompositions.hpp"

namespace pcr {

namespace {

using SpMat = Eigen::SparseMatrix<double>;
using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// The blocks completed to a partition of [0, n) (each column in no block a block of its own), and the
/// block of each column.
struct Partition {
  std::vector<VariableRange> parts;
  std::vector<int> owner;
};

Partition partition_of(int n, const std::vector<VariableRange>& blocks) {
  Partition p{{}, std::vector<int>(static_cast<std::size_t>(n), -1)};
  for (const VariableRange& b : blocks) {
    for (int c = b.offset; c < b.offset + b.size; ++c) {
      if (b.size <= 0 || c < 0 || c >= n || p.owner[c] >= 0) {
        std::ostringstream msg;
        msg << "tangent_space_eigenvalues: variable block [" << b.offset << ", " << b.offset + b.size
            << ") is empty, outside [0, " << n << ") or overlaps another block";
        throw std::invalid_argument(msg.str());
      }
      p.owner[c] = static_cast<int>(p.parts.size());
    }
    p.parts.push_back(b);
  }
  for (int c = 0; c < n; ++c) {
    if (p.owner[c] >= 0) continue;
    p.owner[c] = static_cast<int>(p.parts.size());
    p.parts.push_back({c, 1});
  }
  return p;
}

/// The rows of A split into those within one block (per block) and the others.
struct RowSplit {
  std::vector<std::vector<int>> local;  // per block
  std::vector<int> global;
};

RowSplit split_rows(const RowMat& A, const Partition& p) {
  RowSplit s{std::vector<std::vector<int>>(p.parts.size()), {}};
  for (int r = 0; r < A.rows(); ++r) {
    int block = -1;
    bool one_block = true;
    for (RowMat::InnerIterator it(A, r); it; ++it) {
      const int b = p.owner[it.col()];
      if (block >= 0 && b != block) one_block = false;
      block = b;
    }
    if (block < 0) continue;  // an empty row constrains nothing
    if (one_block)
      s.local[block].push_back(r);
    else
      s.global.push_back(r);
  }
  return s;
}

/// Z_b: per block an orthonormal basis of the null space of its local rows (the last columns of the
/// Householder Q of the rows' transpose), the identity where it has none.
SpMat blockwise_null_basis(const RowMat& A, const Partition& p, const RowSplit& s) {
  std::vector<Eigen::Triplet<double>> t;
  int column = 0;
  for (std::size_t k = 0; k < p.parts.size(); ++k) {
    const VariableRange b = p.parts[k];
    if (s.local[k].empty()) {
      for (int i = 0; i < b.size; ++i) t.emplace_back(b.offset + i, column++, 1.0);
      continue;
    }
    MatX rows = MatX::Zero(static_cast<Eigen::Index>(s.local[k].size()), b.size);
    for (std::size_t i = 0; i < s.local[k].size(); ++i)
      for (RowMat::InnerIterator it(A, s.local[k][i]); it; ++it)
        rows(static_cast<Eigen::Index>(i), it.col() - b.offset) = it.value();
    const Eigen::ColPivHouseholderQR<MatX> qr(rows.transpose());
    const MatX Q = qr.householderQ();
    for (Eigen::Index j = qr.rank(); j < b.size; ++j, ++column)
      for (int i = 0; i < b.size; ++i)
        if (Q(i, j) != 0.0) t.emplace_back(b.offset + i, column, Q(i, j));
  }
  SpMat Z(A.cols(), column);
  Z.setFromTriplets(t.begin(), t.end());
  return Z;
}

}  // namespace

VecX tangent_space_eigenvalues(const SpMat& H, const SpMat& A, const std::vector<VariableRange>& blocks) {
  const int n = static_cast<int>(H.rows());
  if (H.cols() != n || A.cols() != n) {
    std::ostringstream msg;
    msg << "tangent_space_eigenvalues: H is " << H.rows() << " x " << H.cols() << ", A has " << A.cols()
        << " columns";
    throw std::invalid_argument(msg.str());
  }
  const Partition p = partition_of(n, blocks);
  const RowMat Ar(A);
  const RowSplit s = split_rows(Ar, p);
  const SpMat Zb = blockwise_null_basis(Ar, p, s);
  MatX M = MatX(SpMat(Zb.transpose() * H * Zb));
  if (!s.global.empty()) {
    MatX G = MatX::Zero(static_cast<Eigen::Index>(s.global.size()), n);
    for (std::size_t i = 0; i < s.global.size(); ++i)
      for (RowMat::InnerIterator it(Ar, s.global[i]); it; ++it)
        G(static_cast<Eigen::Index>(i), it.col()) = it.value();
    const MatX GZ = G * Zb;
    // (G Z_b)^T = Q R P^T: its null space is spanned by Q's columns after the rank; Q^T M Q's trailing
    // block is Z_g^T M Z_g.
    const Eigen::ColPivHouseholderQR<MatX> qr(GZ.transpose());
    M.applyOnTheLeft(qr.householderQ().adjoint());
    M.applyOnTheRight(qr.householderQ());
    const Eigen::Index k = M.rows() - qr.rank();
    M = MatX(M.bottomRightCorner(k, k));
  }
  return symmetric_eigenvalues(M);
}

}  // namespace pcr
