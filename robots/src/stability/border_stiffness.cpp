// The reduced stiffness of the border coordinates (robot_stability.hpp robot_border_stiffness): with the FK
// Jacobian J at the solution (inputs fixed), an external wrench w on platform p adds dR/dw = (1 / F0,
// 1 / M0) to its balance rows, and a generalised force f on passive joint j (a torque about a revolute or
// continuous joint's axis, a force along a prismatic one's) adds 1 / scale_j to that joint's balance row
// (Q - k (q - q0) + f) / scale_j; so dX/d(w, f) = -J^-1 dR/d(w, f) (implicit function theorem), read as
// (dx, world rotation vector dtheta = 2 vec(dQ (x) conj(Q)) / |Q|^2) for every platform and dq for every
// passive joint: the compliance C of the border, whose inverse is K_red (docs/design.md §4). One LU of J
// (band per rod and Schur complement, else sparse) and one solve per border coordinate.
#include <sstream>

#include "pcr/math/quaternion.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pcr/solve/bordered_block_lu.hpp"
#include "pcr/solve/free_jacobian.hpp"
#include "pcr/solve/sparse_lu.hpp"

namespace pcr {

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

/// The border's coordinates: per platform 6 (dx, dtheta), then per passive joint 1 (dq); their residual
/// rows, the scale of each row (F0, M0, or the joint's) and D, the length of each coordinate in the
/// dimensionless form (L0 for displacements, 1 for rotations).
struct Border {
  int size = 0;
  std::vector<int> rows;
  VecX row_scale, D;
};

Border border_of(const RobotAssembly& a) {
  const RobotModel& model = a.model();
  const Problem& problem = a.problem();
  const int np = static_cast<int>(model.platforms().size());
  const int nj = static_cast<int>(model.passive_joints().size());
  Border b;
  b.size = 6 * np + nj;
  b.row_scale.resize(b.size);
  b.D.resize(b.size);
  const double L0 = a.length_scale();
  for (int p = 0; p < np; ++p) {
    const int row = problem.row_offset(a.platform_balance(p));
    for (int k = 0; k < 6; ++k) {
      b.rows.push_back(row + k);
      b.row_scale[6 * p + k] = k < 3 ? a.force_scale() : a.moment_scale();
      b.D[6 * p + k] = k < 3 ? L0 : 1.0;
    }
  }
  for (int j = 0; j < nj; ++j) {
    const bool prismatic = model.joints()[model.passive_joints()[j]].type == JointType::Prismatic;
    b.rows.push_back(problem.row_offset(a.passive_joint_balance(j)));
    b.row_scale[6 * np + j] = prismatic ? a.force_scale() : a.moment_scale();  // as PassiveJointBlock
    b.D[6 * np + j] = prismatic ? L0 : 1.0;
  }
  return b;
}

/// The border coordinates' displacement (dx, dtheta per platform, dq per passive joint) of each column of
/// dfree (rows: the free variables of J).
MatX border_motion(const RobotAssembly& a, const VecX& x, const FreeJacobian& J, const MatX& dfree) {
  const Problem& problem = a.problem();
  const int np = static_cast<int>(a.model().platforms().size());
  const int nj = static_cast<int>(a.model().passive_joints().size());
  std::vector<int> position_of(problem.num_variables(), -1);  // row of dfree of each variable
  for (size_t k = 0; k < J.columns.size(); ++k) position_of[J.columns[k]] = static_cast<int>(k);
  MatX motion(6 * np + nj, dfree.cols());
  for (int p = 0; p < np; ++p) {
    const int o = problem.variable(a.platform_variable(p)).offset;
    const Quat Q = x.segment<4>(o + 3);
    for (int col = 0; col < dfree.cols(); ++col) {
      Quat dQ;
      for (int k = 0; k < 3; ++k) motion(6 * p + k, col) = dfree(position_of[o + k], col);
      for (int k = 0; k < 4; ++k) dQ[k] = dfree(position_of[o + 3 + k], col);
      motion.block<3, 1>(6 * p + 3, col) =
          2.0 * quat_multiply(dQ, quat_conjugate(Q)).tail<3>() / Q.squaredNorm();
    }
  }
  for (int j = 0; j < nj; ++j) {
    const int o = problem.variable(a.passive_joint_variable(j)).offset;
    motion.row(6 * np + j) = dfree.row(position_of[o]);
  }
  return motion;
}

}  // namespace

BorderStiffness robot_border_stiffness(const RobotAssembly& a, const VecX& x) {
  BorderStiffness out;
  const Problem& problem = a.problem();
  const Border border = border_of(a);
  out.length_scale = a.length_scale();
  out.energy_scale = a.moment_scale();
  out.coordinate_scale = border.D;
  if (border.size == 0) {
    out.ok = true;
    return out;
  }
  VecX c;
  Eigen::SparseMatrix<double, Eigen::RowMajor> J_all;
  problem.evaluate_residuals_and_jacobian(x, c, J_all);
  const FreeJacobian J = free_jacobian(problem, J_all);
  MatX rhs = MatX::Zero(problem.num_rows(), border.size);  // -dR/d(w, f)
  for (int k = 0; k < border.size; ++k) rhs(border.rows[k], k) = -1.0 / border.row_scale[k];
  MatX dfree;
  if (J.matrix.rows() != J.matrix.cols() || !solve_free(J, rhs, dfree)) {
    out.failure = "the FK Jacobian is singular at the solution";
    return out;
  }
  // Dimensionless compliance C_hat = M0 D^-1 C D^-1 (the inverse of K_hat = D K_red D / M0).
  const VecX inverse_D = border.D.cwiseInverse();
  const MatX C =
      a.moment_scale() * inverse_D.asDiagonal() * border_motion(a, x, J, dfree) * inverse_D.asDiagonal();
  const Eigen::FullPivLU<MatX> lu(C);
  if (!lu.isInvertible() || !(lu.rcond() > 1e-14)) {
    std::ostringstream msg;
    msg << "the border's compliance is singular (reciprocal condition " << lu.rcond()
        << "): a rod at a conjugate point with its links held?";
    out.failure = msg.str();
    return out;
  }
  out.stiffness = lu.inverse();
  out.ok = out.stiffness.allFinite();
  if (!out.ok) out.failure = "the border's reduced stiffness is not finite";
  return out;
}

}  // namespace pcr
