#pragma once
// Test-only residual blocks and problems with known solutions, shared by the solver tests and bench_solve.
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pcr/solve/problem.hpp"

namespace pcr::test {

/// x^2 + y^2 - r^2 over two scalar variable blocks {x, y}.
class CircleBlock : public ResidualBlock {
 public:
  CircleBlock(VariableId x, VariableId y, double radius)
      : ResidualBlock("test.circle", "circle", 1, {x, y}), r2_(radius * radius) {}
  int expected_variable_size(int) const override { return 1; }
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    c[0] = v[0][0] * v[0][0] + v[1][0] * v[1][0] - r2_;
    if (J && J[0]) J[0][0] = 2.0 * v[0][0];
    if (J && J[1]) J[1][0] = 2.0 * v[1][0];
  }
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const*, const double* w, double* H) const override {
    H[0] = 2.0 * w[0], H[1] = 0.0, H[2] = 0.0, H[3] = 2.0 * w[0];
  }

 private:
  double r2_;
};

/// a y + b x - d over {y, x} (listed in reverse column order on purpose).
class LineBlock : public ResidualBlock {
 public:
  LineBlock(VariableId y, VariableId x, double a, double b, double d, std::string name = "line")
      : ResidualBlock("test.line", std::move(name), 1, {y, x}), a_(a), b_(b), d_(d) {}
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    c[0] = a_ * v[0][0] + b_ * v[1][0] - d_;
    if (J && J[0]) J[0][0] = a_;
    if (J && J[1]) J[1][0] = b_;
  }
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const*, const double*, double* H) const override {
    for (int i = 0; i < 4; ++i) H[i] = 0.0;
  }

 private:
  double a_, b_, d_;
};

/// Row i of the Broyden tridiagonal system (Moré, Garbow, Hillstrom 1981, problem 30):
///   f_i = (3 - 2 x_i) x_i - x_{i-1} - 2 x_{i+1} + 1,  x_0 = x_{n+1} = 0.
/// Touches {x_i, x_{i-1} (if any), x_{i+1} (if any)}.
class BroydenRow : public ResidualBlock {
 public:
  /// scale multiplies the row (a badly scaled variant for scaling studies; the roots do not change).
  BroydenRow(int i, const std::vector<VariableId>& x, double scale = 1.0)
      : ResidualBlock("test.broyden", "broyden_" + std::to_string(i), 1, touched(i, x)),
        has_left_(i > 0),
        has_right_(i + 1 < static_cast<int>(x.size())),
        scale_(scale) {}
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    const double xi = v[0][0];
    const double left = has_left_ ? v[1][0] : 0.0;
    const double right = has_right_ ? v[has_left_ ? 2 : 1][0] : 0.0;
    c[0] = scale_ * ((3.0 - 2.0 * xi) * xi - left - 2.0 * right + 1.0);
    if (!J) return;
    if (J[0]) J[0][0] = scale_ * (3.0 - 4.0 * xi);
    if (has_left_ && J[1]) J[1][0] = -scale_;
    if (has_right_ && J[has_left_ ? 2 : 1]) J[has_left_ ? 2 : 1][0] = -2.0 * scale_;
  }
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const*, const double* w, double* H) const override {
    const int n = 1 + has_left_ + has_right_;
    for (int i = 0; i < n * n; ++i) H[i] = 0.0;
    H[0] = -4.0 * scale_ * w[0];
  }

 private:
  static std::vector<VariableId> touched(int i, const std::vector<VariableId>& x) {
    std::vector<VariableId> ids{x[i]};
    if (i > 0) ids.push_back(x[i - 1]);
    if (i + 1 < static_cast<int>(x.size())) ids.push_back(x[i + 1]);
    return ids;
  }
  bool has_left_, has_right_;
  double scale_;
};

/// Broyden tridiagonal problem of size n, one scalar variable block per unknown, start x = -1 (MGH);
/// every odd row multiplied by odd_row_scale (1: the original problem).
inline Problem broyden_problem(int n, double odd_row_scale = 1.0) {
  Problem p;
  std::vector<VariableId> x;
  for (int i = 0; i < n; ++i)
    x.push_back(p.add_variable_block("x" + std::to_string(i), VecX::Constant(1, -1.0)));
  for (int i = 0; i < n; ++i)
    p.add_residual_block(std::make_shared<BroydenRow>(i, x, i % 2 ? odd_row_scale : 1.0));
  return p;
}

/// Hock & Schittkowski problem 71, objective x1 x4 (x1 + x2 + x3) + x3 over one block of size 4.
class Hs071Objective : public ObjectiveTerm {
 public:
  /// scale multiplies the objective (a badly scaled variant for scaling studies; same minimiser).
  explicit Hs071Objective(VariableId x, double scale = 1.0)
      : ObjectiveTerm("hs071.objective", {x}), s_(scale) {}
  int expected_variable_size(int) const override { return 4; }
  double evaluate(const double* const* v, double* const* g) const override {
    const double* x = v[0];
    if (g && g[0]) {
      g[0][0] = s_ * x[3] * (2.0 * x[0] + x[1] + x[2]);
      g[0][1] = s_ * x[0] * x[3];
      g[0][2] = s_ * (x[0] * x[3] + 1.0);
      g[0][3] = s_ * x[0] * (x[0] + x[1] + x[2]);
    }
    return s_ * (x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2]);
  }
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const* v, double* H) const override {
    const double* x = v[0];
    const double h[16] = {2 * x[3], x[3], x[3], 2 * x[0] + x[1] + x[2], x[3], 0,    0, x[0], x[3],
                          0,        0,    x[0], 2 * x[0] + x[1] + x[2], x[0], x[0], 0};
    for (int i = 0; i < 16; ++i) H[i] = s_ * h[i];
  }

 private:
  double s_;
};

/// x1 x2 x3 x4 >= 25.
class Hs071Product : public ResidualBlock {
 public:
  explicit Hs071Product(VariableId x) : ResidualBlock("hs071.inequality", "product", 1, {x}) {
    set_row_bounds(VecX::Constant(1, 25.0), VecX::Constant(1, std::numeric_limits<double>::infinity()));
  }
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    const double* x = v[0];
    c[0] = x[0] * x[1] * x[2] * x[3];
    if (J && J[0]) {
      J[0][0] = x[1] * x[2] * x[3], J[0][1] = x[0] * x[2] * x[3];
      J[0][2] = x[0] * x[1] * x[3], J[0][3] = x[0] * x[1] * x[2];
    }
  }
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const* v, const double* w, double* H) const override {
    const double* x = v[0];
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        double product = (i == j) ? 0.0 : 1.0;
        for (int k = 0; k < 4; ++k) {
          if (k != i && k != j) product *= x[k];
        }
        H[4 * i + j] = w[0] * product;
      }
    }
  }
};

/// x1^2 + x2^2 + x3^2 + x4^2 = 40.
class Hs071Sphere : public ResidualBlock {
 public:
  explicit Hs071Sphere(VariableId x) : ResidualBlock("hs071.equality", "sphere", 1, {x}) {
    set_row_bounds(VecX::Constant(1, 40.0), VecX::Constant(1, 40.0));
  }
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    const double* x = v[0];
    c[0] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3];
    if (J && J[0]) {
      for (int i = 0; i < 4; ++i) J[0][i] = 2.0 * x[i];
    }
  }
  bool provides_hessian() const override { return true; }
  void evaluate_hessian(const double* const*, const double* w, double* H) const override {
    for (int i = 0; i < 16; ++i) H[i] = (i % 5 == 0) ? 2.0 * w[0] : 0.0;
  }
};

/// HS071 with bounds 1 <= x <= 5 and the published start (1, 5, 5, 1) (infeasible: sum of squares 52);
/// objective_scale multiplies the objective (1: the published problem).
inline Problem hs071_problem(double objective_scale = 1.0) {
  Problem p;
  const VariableId x = p.add_variable_block("x", (VecX(4) << 1, 5, 5, 1).finished(), VecX::Constant(4, 1.0),
                                            VecX::Constant(4, 5.0));
  p.add_objective_term(std::make_shared<Hs071Objective>(x, objective_scale));
  p.add_residual_block(std::make_shared<Hs071Product>(x));
  p.add_residual_block(std::make_shared<Hs071Sphere>(x));
  return p;
}

/// x^2 + 1 over one scalar block: no real root.
class SquarePlusOne : public ResidualBlock {
 public:
  explicit SquarePlusOne(VariableId x) : ResidualBlock("test.square_plus_one", "square_plus_one", 1, {x}) {}
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    c[0] = v[0][0] * v[0][0] + 1.0;
    if (J && J[0]) J[0][0] = 2.0 * v[0][0];
  }
};

/// sqrt(x) - 2: not finite for x < 0 (to test how solvers report non-finite values).
class SquareRootBlock : public ResidualBlock {
 public:
  explicit SquareRootBlock(VariableId x) : ResidualBlock("test.sqrt", "sqrt", 1, {x}) {}
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    c[0] = std::sqrt(v[0][0]) - 2.0;
    if (J && J[0]) J[0][0] = 0.5 / std::sqrt(v[0][0]);
  }
};

/// A rows x n linear block A x - b over one variable block.
class LinearBlock : public ResidualBlock {
 public:
  LinearBlock(VariableId x, const MatX& A, const VecX& b, std::string name = "linear")
      : ResidualBlock("test.linear", std::move(name), static_cast<int>(A.rows()), {x}), A_(A), b_(b) {}
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    const Eigen::Map<const VecX> x(v[0], A_.cols());
    Eigen::Map<VecX>(c, A_.rows()) = A_ * x - b_;
    if (J && J[0]) Eigen::Map<RowMajorMatX>(J[0], A_.rows(), A_.cols()) = A_;
  }

 private:
  MatX A_;
  VecX b_;
};

/// sum_k a_k x_k - d over scalar variable blocks x_k.
class SumBlock : public ResidualBlock {
 public:
  SumBlock(std::vector<VariableId> x, std::vector<double> a, double d)
      : ResidualBlock("test.sum", "sum", 1, std::move(x)), a_(std::move(a)), d_(d) {}
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    c[0] = -d_;
    for (size_t k = 0; k < a_.size(); ++k) {
      c[0] += a_[k] * v[k][0];
      if (J && J[k]) J[k][0] = a_[k];
    }
  }

 private:
  std::vector<double> a_;
  double d_;
};

}  // namespace pcr::test
