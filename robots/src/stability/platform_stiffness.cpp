// The platforms' reduced stiffness from their full compliance (robot_stability_parts.hpp): with the FK
// Jacobian J at the solution (inputs fixed), an external wrench w on platform p adds dR/dw = (1 / F0,
// 1 / M0) to its balance rows, so dX/dw = -J^-1 dR/dw (implicit function theorem), read as (dx, world
// rotation vector dtheta = 2 vec(dQ (x) conj(Q)) / |Q|^2) for every platform: the compliance C, whose
// inverse is K_red (docs/design.md §4). One LU of J (band per rod and Schur complement, else sparse)
// and 6 solves per platform.
#include <sstream>

#include "pcr/math/quaternion.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/sparse_lu.hpp"
#include "robot_stability_parts.hpp"

namespace pcr::stability {

namespace {

/// Solves J_free dX = rhs column by column with the structured LU, falling back to the sparse one;
/// false when J is singular.
bool solve_free(const FreeJacobian& J, const MatX& rhs, MatX& solution) {
  solution.resize(J.matrix.cols(), rhs.cols());
  BorderedBlockLu blocks;
  if (blocks.analyze_pattern(J.matrix, J.groups) && blocks.factorize(J.matrix)) {
    VecX column;
    for (int c = 0; c < rhs.cols(); ++c) {
      blocks.solve(rhs.col(c), column);
      solution.col(c) = column;
    }
    return solution.allFinite();
  }
  SparseLu lu;
  if (!lu.compute(J.matrix)) return false;
  solution = lu.solve(rhs);
  return solution.allFinite();
}

}  // namespace

PlatformStiffness platform_stiffness(const RobotAssembly& a, const VecX& x) {
  PlatformStiffness out;
  const Problem& problem = a.problem();
  const int np = static_cast<int>(a.model().platforms().size());
  VecX c;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J_all;
  problem.evaluate_residuals_and_jacobian(x, c, J_all);
  const FreeJacobian J = free_jacobian(problem, J_all);
  MatX rhs = MatX::Zero(problem.num_rows(), 6 * np);  // -dR/dw
  for (int p = 0; p < np; ++p) {
    const int row = problem.row_offset(a.platform_balance(p));
    for (int k = 0; k < 3; ++k) {
      rhs(row + k, 6 * p + k) = -1.0 / a.force_scale();
      rhs(row + 3 + k, 6 * p + 3 + k) = -1.0 / a.moment_scale();
    }
  }
  MatX dfree;
  if (J.matrix.rows() != J.matrix.cols() || !solve_free(J, rhs, dfree)) {
    out.failure = "the FK Jacobian is singular at the solution";
    return out;
  }
  // Dimensionless compliance C_hat = M0 D^-1 C D^-1 (the inverse of K_hat = D K_red D / M0).
  const double L0 = a.length_scale(), M0 = a.moment_scale();
  std::vector<int> position_of(problem.num_variables(), -1);  // row of dfree of each variable
  for (size_t k = 0; k < J.columns.size(); ++k) position_of[J.columns[k]] = static_cast<int>(k);
  MatX C(6 * np, 6 * np);
  for (int p = 0; p < np; ++p) {
    const int o = problem.variable(a.platform_variable(p)).offset;
    const Quat Q = x.segment<4>(o + 3);
    for (int col = 0; col < 6 * np; ++col) {
      Vec3 dx;
      Quat dQ;
      for (int k = 0; k < 3; ++k) dx[k] = dfree(position_of[o + k], col);
      for (int k = 0; k < 4; ++k) dQ[k] = dfree(position_of[o + 3 + k], col);
      const double column_scale = col % 6 < 3 ? L0 : 1.0;  // D^-1 on the right: a force of M0 / L0
      C.block<3, 1>(6 * p, col) = M0 * dx / (L0 * column_scale);
      C.block<3, 1>(6 * p + 3, col) =
          M0 * 2.0 * quat_multiply(dQ, quat_conjugate(Q)).tail<3>() / (Q.squaredNorm() * column_scale);
    }
  }
  const Eigen::FullPivLU<MatX> lu(C);
  if (!lu.isInvertible() || !(lu.rcond() > 1e-14)) {
    std::ostringstream msg;
    msg << "the platforms' compliance is singular (reciprocal condition " << lu.rcond()
        << "): a rod at a conjugate point with its links held?";
    out.failure = msg.str();
    return out;
  }
  out.stiffness = lu.inverse();
  out.ok = out.stiffness.allFinite();
  if (!out.ok) out.failure = "the platforms' reduced stiffness is not finite";
  return out;
}

}  // namespace pcr::stability
