// Quaternions and SO(3): identities, derivatives against central finite differences, exp/log; second-order
// automatic differentiation against closed-form derivatives; eigenvalues on a constraint's null space
// against a dense SVD basis.
#define BOOST_TEST_MODULE math
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "pcr/core/error.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/math/hyper_dual.hpp"
#include "pcr/math/quaternion.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/math/tangent_space_spectrum.hpp"

using namespace pcr;

namespace {

Quat random_quat(std::mt19937& rng, double scale_min = 0.3, double scale_max = 3.0) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> s(scale_min, scale_max);
  Quat q(n(rng), n(rng), n(rng), n(rng));
  return s(rng) * q.normalized();
}

// Double precision: orthonormality of R(q) holds to a few ulps times the matrix size.
constexpr double kRoundoff = 1e-14;

}  // namespace

BOOST_AUTO_TEST_CASE(rotation_is_orthonormal_for_any_nonzero_quaternion) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    const Quat q = random_quat(rng);
    const Mat3 R = rotation_matrix(q);
    BOOST_TEST((R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff() < kRoundoff);
    BOOST_TEST(std::abs(R.determinant() - 1.0) < kRoundoff);
    BOOST_TEST((rotation_matrix(-q) - R).cwiseAbs().maxCoeff() < kRoundoff);
  }
}

BOOST_AUTO_TEST_CASE(product_composes_rotations) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 100; ++trial) {
    const Quat a = random_quat(rng), b = random_quat(rng);
    const Mat3 lhs = rotation_matrix(quat_multiply(a, b));
    const Mat3 rhs = rotation_matrix(a) * rotation_matrix(b);
    BOOST_TEST((lhs - rhs).cwiseAbs().maxCoeff() < kRoundoff);
    const Quat an = a.normalized();
    BOOST_TEST((quat_multiply(an, quat_conjugate(an)) - quat_identity()).cwiseAbs().maxCoeff() < kRoundoff);
  }
}

BOOST_AUTO_TEST_CASE(zero_quaternion_is_rejected) {
  BOOST_CHECK_THROW(rotation_matrix(Quat::Zero()), InputError);
}

BOOST_AUTO_TEST_CASE(first_and_second_derivatives_match_central_differences) {
  std::mt19937 rng(3);
  // Central differences with h = 1e-6 on |q| ~ 1: truncation O(h^2) ~ 1e-12 times the third
  // derivative, round-off ~ eps / h ~ 1e-10; 1e-8 leaves a margin of 100 over both.
  const double h = 1e-6, tol = 1e-8;
  for (int trial = 0; trial < 50; ++trial) {
    const Quat q = random_quat(rng, 0.5, 2.0);
    Mat3 R;
    QuatRotationJacobian dR;
    QuatRotationHessian d2R;
    rotation_matrix_second_derivatives(q, R, dR, d2R);
    Mat3 R1;
    QuatRotationJacobian dR1;
    rotation_matrix_derivatives(q, R1, dR1);
    BOOST_TEST((R - rotation_matrix(q)).cwiseAbs().maxCoeff() < kRoundoff);
    for (int k = 0; k < 4; ++k) {
      BOOST_TEST((dR1[k] - dR[k]).cwiseAbs().maxCoeff() < kRoundoff);
      const Quat e = h * Quat::Unit(k);
      const Mat3 fd = (rotation_matrix(q + e) - rotation_matrix(q - e)) / (2 * h);
      BOOST_TEST((fd - dR[k]).cwiseAbs().maxCoeff() < tol);
      Mat3 Rp, Rm;
      QuatRotationJacobian dRp, dRm;
      rotation_matrix_derivatives(q + e, Rp, dRp);
      rotation_matrix_derivatives(q - e, Rm, dRm);
      for (int l = 0; l < 4; ++l) {
        const Mat3 fd2 = (dRp[l] - dRm[l]) / (2 * h);
        BOOST_TEST((fd2 - d2R[k][l]).cwiseAbs().maxCoeff() < tol);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(hat_vee_round_trip) {
  const Vec3 v(0.3, -1.2, 2.5), w(-0.7, 0.1, 0.4);
  BOOST_TEST((hat(v) * w - v.cross(w)).norm() < kRoundoff);
  BOOST_TEST((vee(hat(v)) - v).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(exp_log_round_trip_including_near_zero_and_near_pi) {
  std::mt19937 rng(4);
  std::normal_distribution<double> n(0.0, 1.0);
  const double angles[] = {0.0, 1e-12, 1e-8,        1e-5,        1e-3,        0.5, 1.0,
                           2.0, 3.0,   M_PI - 1e-2, M_PI - 1e-4, M_PI - 1e-7, M_PI};
  for (double angle : angles) {
    for (int trial = 0; trial < 20; ++trial) {
      const Vec3 axis = Vec3(n(rng), n(rng), n(rng)).normalized();
      const Vec3 theta = angle * axis;
      const Mat3 R = so3_exp(theta);
      BOOST_TEST((R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff() < kRoundoff);
      // exp(log(R)) = R: near pi, log loses digits in the axis as sqrt(eps) ~ 1e-8 at worst in
      // the rotation; elsewhere round-off only.
      const double tol = angle > M_PI - 1e-3 ? 1e-7 : 1e-13;
      BOOST_TEST((so3_exp(so3_log(R)) - R).cwiseAbs().maxCoeff() < tol);
      // The rotation vector itself is unique for angles below pi.
      if (angle < M_PI - 1e-3) BOOST_TEST((so3_log(R) - theta).norm() < 1e-12);
      // Quaternion of the same rotation agrees.
      const Quat q = quat_from_rotation_vector(theta);
      BOOST_TEST((rotation_matrix(q) - R).cwiseAbs().maxCoeff() < 1e-14);
      BOOST_TEST((rotation_matrix(quat_from_rotation(R)) - R).cwiseAbs().maxCoeff() < 1e-14);
    }
  }
}

BOOST_AUTO_TEST_CASE(rotation_error_measures) {
  const Mat3 Ra = rotation_from_rpy(0.1, -0.2, 0.3);
  const Mat3 Rb = Ra * rotation_z(0.25);
  BOOST_TEST(std::abs(rotation_angle_between(Ra, Rb) - 0.25) < 1e-14);
  BOOST_TEST(std::abs(rotation_angle_between(Ra, Ra)) < 1e-14);
  // rpy convention of URDF: Rz(yaw) Ry(pitch) Rx(roll), checked on a vector.
  const Vec3 ex = rotation_from_rpy(0.0, 0.0, M_PI / 2) * Vec3::UnitX();
  BOOST_TEST((ex - Vec3::UnitY()).norm() < 1e-15);
}

// f(x, y) = x^2 y / (1 + y^2) + sqrt(x y) - 3 x at (1.3, 0.7): value, gradient and Hessian against their
// closed forms (differentiated by hand), to round-off. With r = 1 + y^2, w = sqrt(x y):
// f_x = 2 x y / r + y / (2 w) - 3, f_y = x^2 (1 - y^2) / r^2 + x / (2 w),
// f_xx = 2 y / r - y^2 / (4 w^3), f_xy = 2 x (1 - y^2) / r^2 + 1 / (4 w),
// f_yy = x^2 (2 y^3 - 6 y) / r^3 - x^2 / (4 w^3).
BOOST_AUTO_TEST_CASE(hyper_dual_second_derivatives_match_closed_forms) {
  using H = HyperDual<2>;
  const double x = 1.3, y = 0.7, r = 1.0 + y * y, w = std::sqrt(x * y);
  const H X = H::variable(x, 0), Y = H::variable(y, 1);
  H f = X * X * Y / (1.0 + Y * Y) + sqrt(X * Y);
  f -= 3.0 * X;
  BOOST_TEST(f.a == x * x * y / r + w - 3.0 * x, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(f.g[0] == 2 * x * y / r + y / (2 * w) - 3.0, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(f.g[1] == x * x * (1 - y * y) / (r * r) + x / (2 * w), boost::test_tools::tolerance(1e-14));
  BOOST_TEST(f.H(0, 0) == 2 * y / r - y * y / (4 * w * w * w), boost::test_tools::tolerance(1e-14));
  BOOST_TEST(f.H(0, 1) == 2 * x * (1 - y * y) / (r * r) + 1 / (4 * w), boost::test_tools::tolerance(1e-14));
  BOOST_TEST(f.H(1, 0) == f.H(0, 1));
  BOOST_TEST(f.H(1, 1) == x * x * (2 * y * y * y - 6 * y) / (r * r * r) - x * x / (4 * w * w * w),
             boost::test_tools::tolerance(1e-14));
}

namespace {

/// The reference: eigenvalues of Z^T H Z with Z the right singular vectors of the dense A beyond its
/// numerical rank (singular values above 1e-10 of the largest), an independent construction of an
/// orthonormal null basis.
VecX null_space_eigenvalues_by_svd(const MatX& H, const MatX& A) {
  const RightSingularVectors svd = right_singular_vectors(A);
  int rank = 0;
  while (rank < svd.sigma.size() && svd.sigma[rank] > 1e-10 * svd.sigma[0]) ++rank;
  const MatX Z = svd.V.rightCols(A.cols() - rank);
  return symmetric_eigenvalues(Z.transpose() * H * Z);
}

}  // namespace

// Five 7-blocks [P, Q] with a unit-quaternion-like row each (on Q only), two singleton columns, three
// rows across blocks, one row that repeats a block's row (dependent), one empty row; H random symmetric.
BOOST_AUTO_TEST_CASE(tangent_space_eigenvalues_match_a_dense_null_basis) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int blocks = 5, n = 7 * blocks + 2;
  MatX H(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) H(i, j) = normal(rng);
  H = (H + H.transpose()).eval();
  H.diagonal().head(3) *= 1e4;  // a stiff direction beside soft ones, as the rods' axial terms
  MatX A = MatX::Zero(blocks + 5, n);
  std::vector<VariableRange> ranges;
  for (int b = 0; b < blocks; ++b) {
    ranges.push_back({7 * b, 7});
    for (int k = 3; k < 7; ++k) A(b, 7 * b + k) = normal(rng);
  }
  for (int r = blocks; r < blocks + 3; ++r)
    for (int c = 0; c < n; c += 2) A(r, c) = normal(rng);
  A.row(blocks + 3) = 2.0 * A.row(1);  // dependent on block 1's row: local, dropped by the rank
  const VecX reference = null_space_eigenvalues_by_svd(H, A);
  const VecX lambda = tangent_space_eigenvalues(H.sparseView(), A.sparseView(), ranges);
  // 35 + 2 unknowns, 5 + 3 independent rows: a 29-dimensional tangent space.
  BOOST_TEST_REQUIRE(lambda.size() == n - blocks - 3);
  BOOST_TEST_REQUIRE(reference.size() == lambda.size());
  // Both are backward stable: each eigenvalue moves by at most the backward error's norm (Weyl), about
  // n eps |H| per construction (|H| ~ 4e4: 3e-10; measured 1e-10); 10x that.
  const double tolerance = 10.0 * n * std::numeric_limits<double>::epsilon() * H.cwiseAbs().maxCoeff();
  BOOST_TEST((lambda - reference).cwiseAbs().maxCoeff() < tolerance);
  // Without the block structure (every column its own block: all rows global) the same values.
  const VecX unstructured = tangent_space_eigenvalues(H.sparseView(), A.sparseView(), {});
  BOOST_TEST((unstructured - reference).cwiseAbs().maxCoeff() < tolerance);
}

BOOST_AUTO_TEST_CASE(tangent_space_eigenvalues_reject_overlapping_blocks) {
  const MatX H = MatX::Identity(4, 4), A = MatX::Ones(1, 4);
  BOOST_CHECK_THROW(tangent_space_eigenvalues(H.sparseView(), A.sparseView(), {{0, 3}, {2, 2}}),
                    std::invalid_argument);
  BOOST_CHECK_THROW(tangent_space_eigenvalues(H.sparseView(), A.sparseView(), {{3, 2}}),
                    std::invalid_argument);
  // Without constraints the spectrum of H itself (the identity's).
  const VecX free = tangent_space_eigenvalues(H.sparseView(), MatX(0, 4).sparseView(), {{0, 4}});
  BOOST_TEST(free.size() == 4);
  BOOST_TEST((free.array() - 1.0).abs().maxCoeff() < 1e-15);
}
