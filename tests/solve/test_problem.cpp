// Problem assembly (pattern, offsets, inactive blocks, validation), the Jacobian checker and summaries.
#define BOOST_TEST_MODULE problem
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/solve/jacobian_check.hpp"
#include "pcr/solve/problem.hpp"
#include "pcr/solve/solve_summary.hpp"
#include "solve/test_problems.hpp"

// Heap allocations counted by the operator new of allocation_counter.cpp.
extern long g_allocations;

using namespace pcr;
using pcr::test::BroydenRow;
using pcr::test::CircleBlock;
using pcr::test::LineBlock;

namespace {

using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// A block over {p (size 3), q (size 2)}: c = [p0 q1 + sin(p2); p1^2 q0 - p0]. `wrong` scales one
// derivative by 1.01 (a typical transcription slip) so the checker must flag it.
class MixedBlock : public ResidualBlock {
 public:
  MixedBlock(VariableId p, VariableId q, bool wrong, std::string name = "mixed")
      : ResidualBlock("test.mixed", std::move(name), 2, {p, q}), wrong_(wrong) {}
  int expected_variable_size(int k) const override { return k == 0 ? 3 : 2; }
  void evaluate(const double* const* v, double* c, double* const* J) const override {
    const double *p = v[0], *q = v[1];
    c[0] = p[0] * q[1] + std::sin(p[2]);
    c[1] = p[1] * p[1] * q[0] - p[0];
    if (!J) return;
    if (J[0]) {
      double* Jp = J[0];  // 2 x 3 row-major
      Jp[0] = q[1], Jp[1] = 0.0, Jp[2] = std::cos(p[2]) * (wrong_ ? 1.01 : 1.0);
      Jp[3] = -1.0, Jp[4] = 2.0 * p[1] * q[0], Jp[5] = 0.0;
    }
    if (J[1]) {
      double* Jq = J[1];  // 2 x 2
      Jq[0] = 0.0, Jq[1] = p[0];
      Jq[2] = p[1] * p[1], Jq[3] = 0.0;
    }
  }

 private:
  bool wrong_;
};

// MixedBlock with its structural zeros declared (d c0/d p1, d c1/d p2, d c0/d q0, d c1/d q1). With
// `lie`, d c0/d p2 = cos(p2) (not zero) is declared zero too, which the problem checker must catch.
class DeclaredSparseBlock : public MixedBlock {
 public:
  DeclaredSparseBlock(VariableId p, VariableId q, bool lie) : MixedBlock(p, q, false, "sparse"), lie_(lie) {}
  bool structural_nonzero(int k, int row, int column) const override {
    if (lie_ && k == 0 && row == 0 && column == 2) return false;
    if (k == 0) return !((row == 0 && column == 1) || (row == 1 && column == 2));
    return !((row == 0 && column == 0) || (row == 1 && column == 1));
  }

 private:
  bool lie_;
};

// Three blocks: a (size 3), b (size 2), c (size 1); MixedBlock(a, b) rows 0-1, line(c, a? no) ...
struct SmallProblem {
  Problem p;
  VariableId a, b, s, t;
  ResidualId mixed, circle, line;
  SmallProblem() {
    a = p.add_variable_block("a", (VecX(3) << 0.3, -0.7, 1.1).finished());
    b = p.add_variable_block("b", (VecX(2) << 2.0, 0.5).finished());
    s = p.add_variable_block("s", VecX::Constant(1, 1.5));
    t = p.add_variable_block("t", VecX::Constant(1, -0.25));
    mixed = p.add_residual_block(std::make_shared<MixedBlock>(a, b, false));
    circle = p.add_residual_block(std::make_shared<CircleBlock>(t, s, 2.0));
    line = p.add_residual_block(std::make_shared<LineBlock>(t, s, 1.0, -1.0, 0.0));
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(offsets_rows_and_pattern_match_the_blocks) {
  SmallProblem sp;
  Problem& p = sp.p;
  BOOST_TEST(p.num_variables() == 7);
  BOOST_TEST(p.variable(sp.b).offset == 3);
  BOOST_TEST(p.variable(sp.t).offset == 6);
  BOOST_TEST(p.num_rows() == 4);
  BOOST_TEST(p.row_offset(sp.circle) == 2);
  BOOST_TEST(p.residual_at_row(3) == sp.line);
  // Union of dense patterns: mixed 2 x (3 + 2), circle 1 x 2, line 1 x 2.
  BOOST_TEST(p.jacobian_nonzeros() == 2 * 5 + 2 + 2);

  const VecX x = p.initial_values();
  VecX c;
  SparseRowMajor J;
  p.evaluate_residuals_and_jacobian(x, c, J);
  // Expected values written out by hand from the block formulas.
  const double a0 = 0.3, a1 = -0.7, a2 = 1.1, b0 = 2.0, b1 = 0.5, s = 1.5, t = -0.25;
  MatX expected = MatX::Zero(4, 7);
  expected.row(0) << b1, 0, std::cos(a2), 0, a0, 0, 0;
  expected.row(1) << -1, 2 * a1 * b0, 0, a1 * a1, 0, 0, 0;
  expected.row(2) << 0, 0, 0, 0, 0, 2 * s, 2 * t;
  expected.row(3) << 0, 0, 0, 0, 0, -1, 1;
  // Exact arithmetic on the same operations: only the last bit may differ (1e-15 relative).
  BOOST_TEST((MatX(J) - expected).cwiseAbs().maxCoeff() <= 1e-15);
  BOOST_TEST(c[0] == a0 * b1 + std::sin(a2));
  BOOST_TEST(c[2] == t * t + s * s - 4.0);
  BOOST_TEST(c[3] == t - s);

  VecX c_only;
  p.evaluate_residuals(x, c_only);
  BOOST_TEST((c_only - c).cwiseAbs().maxCoeff() == 0.0);
}

BOOST_AUTO_TEST_CASE(pattern_is_built_once_and_values_are_written_in_place) {
  SmallProblem sp;
  VecX x = sp.p.initial_values(), c;
  SparseRowMajor J;
  sp.p.evaluate_residuals_and_jacobian(x, c, J);
  const double* values = J.valuePtr();
  const int* columns = J.innerIndexPtr();
  x.array() += 0.1;
  sp.p.evaluate_residuals_and_jacobian(x, c, J);
  // Same storage: no triplet rebuild or reallocation between evaluations.
  BOOST_TEST(J.valuePtr() == values);
  BOOST_TEST(J.innerIndexPtr() == columns);
  BOOST_TEST(J.coeff(0, 0) == x[4]);  // d(a0 b1)/d(a0) = b1 at the new point
}

BOOST_AUTO_TEST_CASE(evaluation_does_not_allocate_once_sized) {
  Problem p = pcr::test::hs071_problem();
  VecX x = p.initial_values(), c, g;
  SparseRowMajor J, H;
  const VecX lambda = VecX::Ones(2);
  const long at_start = g_allocations;
  p.evaluate_residuals_and_jacobian(x, c, J);  // first calls size c, J, g, H and build the patterns
  p.evaluate_objective(x, &g);
  p.evaluate_hessian(x, 1.0, lambda, H);
  BOOST_TEST(g_allocations > at_start);  // the counter sees these allocations
  x[1] = 4.5;
  const long before = g_allocations;
  p.evaluate_residuals(x, c);
  p.evaluate_residuals_and_jacobian(x, c, J);
  p.evaluate_objective(x, &g);
  p.evaluate_hessian(x, 1.0, lambda, H);
  BOOST_TEST(g_allocations == before);
}

BOOST_AUTO_TEST_CASE(inactive_blocks_contribute_no_rows) {
  SmallProblem sp;
  Problem& p = sp.p;
  const auto version = p.structure_version();
  p.set_residual_active(sp.circle, false);
  BOOST_TEST(p.structure_version() != version);
  BOOST_TEST(!p.residual_active(sp.circle));
  BOOST_TEST(p.num_rows() == 3);
  BOOST_TEST(p.row_offset(sp.circle) == -1);
  BOOST_TEST(p.row_offset(sp.line) == 2);
  BOOST_TEST(p.jacobian_nonzeros() == 12);
  VecX c;
  SparseRowMajor J;
  p.evaluate_residuals_and_jacobian(p.initial_values(), c, J);
  BOOST_TEST(J.rows() == 3);
  BOOST_TEST(c[2] == -0.25 - 1.5);  // the line row moved up
  const auto kinds = p.violation_by_kind(c);
  BOOST_TEST(kinds.size() == 2u);
  for (const auto& k : kinds) BOOST_TEST(k.first != "test.circle");
  p.set_residual_active(sp.circle, true);
  p.evaluate_residuals_and_jacobian(p.initial_values(), c, J);
  BOOST_TEST(J.rows() == 4);
  BOOST_TEST(p.violation_by_kind(c).size() == 3u);
}

BOOST_AUTO_TEST_CASE(violation_uses_row_bounds) {
  Problem p = pcr::test::hs071_problem();
  const VecX x = p.initial_values();  // (1, 5, 5, 1): product 25 (bound active), squares 52
  VecX c;
  p.evaluate_residuals(x, c);
  BOOST_TEST(c[0] == 25.0);
  BOOST_TEST(p.constraint_violation(c) == 12.0);  // |52 - 40|
  const auto kinds = p.violation_by_kind(c);
  BOOST_TEST(kinds.at(0).first == "hs071.inequality");
  BOOST_TEST(kinds.at(0).second == 0.0);
  BOOST_TEST(kinds.at(1).second == 12.0);
  c[0] = 20.0;  // 5 below the lower bound 25
  BOOST_TEST(p.constraint_violation(c) == 12.0);
  c[1] = 40.0;
  BOOST_TEST(p.constraint_violation(c) == 5.0);
  c[1] = std::nan("");
  BOOST_TEST(std::isinf(p.constraint_violation(c)));
}

BOOST_AUTO_TEST_CASE(bad_input_throws_naming_the_block) {
  Problem p;
  const VariableId a = p.add_variable_block("a", VecX::Zero(3));
  const VariableId b = p.add_variable_block("b", VecX::Zero(2));
  auto message_of = [](auto&& action) -> std::string {
    try {
      action();
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no exception)";
  };
  auto contains = [](const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
  };
  BOOST_TEST(
      contains(message_of([&] { p.add_residual_block(std::make_shared<MixedBlock>(a, 7, false, "ghost")); }),
               "'ghost'"));
  BOOST_TEST(contains(
      message_of([&] { p.add_residual_block(std::make_shared<MixedBlock>(b, a, false, "swapped")); }),
      "'swapped'"));  // expects sizes (3, 2)
  BOOST_TEST(
      contains(message_of([&] { p.add_residual_block(std::make_shared<MixedBlock>(a, a, false, "twice")); }),
               "twice"));
  BOOST_TEST(contains(
      message_of([&] { p.add_variable_block("c", VecX::Zero(2), VecX::Zero(3), VecX::Ones(2)); }), "'c'"));
  BOOST_TEST(contains(message_of([&] { p.set_variable_bounds(a, VecX::Ones(3), VecX::Zero(3)); }), "'a'"));
  BOOST_TEST(contains(message_of([&] { p.fix_variable(b, VecX::Zero(3)); }), "'b'"));
  BOOST_TEST(contains(message_of([&] { p.set_variable_scale(b, VecX::Ones(3)); }), "'b'"));
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::infinity(), std::nan("")})
    BOOST_TEST(contains(message_of([&] { p.set_variable_scale(b, VecX::Constant(2, bad)); }), "'b'"));
  BOOST_TEST(contains(message_of([&] {
                        CircleBlock circle(a, b, 1.0);
                        circle.set_row_bounds(VecX::Zero(2), VecX::Zero(2));
                      }),
                      "'circle'"));
  BOOST_TEST(contains(message_of([&] { p.set_residual_active(5, false); }), "5"));
  // Failed additions leave the problem unchanged.
  BOOST_TEST(p.num_residual_blocks() == 0);
  BOOST_TEST(p.num_variable_blocks() == 2);
  BOOST_TEST(p.num_variables() == 5);
}

BOOST_AUTO_TEST_CASE(fixing_a_variable_sets_its_value_and_bounds) {
  SmallProblem sp;
  sp.p.fix_variable(sp.s, VecX::Constant(1, 3.0));
  BOOST_TEST(sp.p.variable_fixed(sp.s));
  BOOST_TEST(sp.p.initial_values()[5] == 3.0);
  BOOST_TEST(sp.p.variable_lower()[5] == 3.0);
  BOOST_TEST(sp.p.variable_upper()[5] == 3.0);
  sp.p.set_variable_bounds(sp.s, VecX::Constant(1, -1.0), VecX::Constant(1, 4.0));
  BOOST_TEST(!sp.p.variable_fixed(sp.s));
}

BOOST_AUTO_TEST_CASE(variable_scales_are_ones_unless_set_and_stack_in_block_order) {
  SmallProblem sp;
  BOOST_TEST(sp.p.variable_scales() == VecX::Ones(sp.p.num_variables()));
  sp.p.set_variable_scale(sp.s, VecX::Constant(1, 0.25));
  const VecX s = sp.p.variable_scales();
  BOOST_TEST(s[sp.p.variable(sp.s).offset] == 0.25);
  BOOST_TEST(s.sum() == sp.p.num_variables() - 1 + 0.25);
}

BOOST_AUTO_TEST_CASE(copies_are_independent) {
  SmallProblem sp;
  Problem copy = sp.p;
  copy.set_residual_active(sp.mixed, false);
  BOOST_TEST(copy.num_rows() == 2);
  BOOST_TEST(sp.p.num_rows() == 4);
}

BOOST_AUTO_TEST_CASE(checker_passes_a_right_block_and_catches_a_wrong_one) {
  const std::vector<VecX> values{(VecX(3) << 0.3, -0.7, 1.1).finished(), (VecX(2) << 2.0, 0.5).finished()};
  const MixedBlock right(0, 1, false), wrong(0, 1, true, "mixed_wrong");
  const JacobianCheckResult ok = check_block_jacobian(right, values);
  BOOST_TEST(ok.passed, ok.to_string());
  BOOST_TEST(ok.entries_checked == 2 * 5);
  const JacobianCheckResult bad = check_block_jacobian(wrong, values);
  BOOST_TEST(!bad.passed);
  BOOST_TEST(bad.block_name == "mixed_wrong");
  BOOST_TEST(bad.row == 0);
  BOOST_TEST(bad.variable_index == 0);
  BOOST_TEST(bad.column == 2);
  // The numeric derivative is cos(1.1) to O(h^2) = 1e-12 (h = 1e-6 * 1.1), the analytic one 1% off.
  BOOST_TEST(std::abs(bad.numeric - std::cos(1.1)) <= 1e-9);
  BOOST_TEST(bad.analytic == 1.01 * std::cos(1.1));
  BOOST_TEST(bad.to_string().find("FAILED") != std::string::npos);
  BOOST_TEST(bad.to_string().find("mixed_wrong") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(problem_checker_locates_the_wrong_block) {
  SmallProblem sp;
  BOOST_TEST(check_problem_jacobian(sp.p, sp.p.initial_values()).passed);
  const ResidualId bad = sp.p.add_residual_block(std::make_shared<MixedBlock>(sp.a, sp.b, true, "bad_one"));
  const JacobianCheckResult r = check_problem_jacobian(sp.p, sp.p.initial_values());
  BOOST_TEST(!r.passed);
  BOOST_TEST(r.block_name == "bad_one");
  BOOST_TEST(r.global_row == sp.p.row_offset(bad));
  BOOST_TEST(r.variable == sp.a);
  BOOST_TEST(r.variable_name == "a");
  BOOST_TEST(r.column == 2);
  BOOST_TEST(r.to_string().find("'bad_one'") != std::string::npos, r.to_string());
}

BOOST_AUTO_TEST_CASE(problem_checker_covers_the_objective_gradient) {
  Problem p = pcr::test::hs071_problem();
  const VecX x = (VecX(4) << 1.2, 4.1, 3.3, 1.7).finished();
  const JacobianCheckResult r = check_problem_jacobian(p, x);
  BOOST_TEST(r.passed, r.to_string());
  BOOST_TEST(r.entries_checked == 4 * 2 + 4);  // 2 rows + gradient, 4 columns
}

BOOST_AUTO_TEST_CASE(broyden_problem_has_a_tridiagonal_pattern_and_right_jacobian) {
  Problem p = pcr::test::broyden_problem(50);
  BOOST_TEST(p.num_rows() == 50);
  BOOST_TEST(p.jacobian_nonzeros() == 3 * 50 - 2);
  const JacobianCheckResult r = check_problem_jacobian(p, VecX::LinSpaced(50, -1.0, 0.5));
  BOOST_TEST(r.passed, r.to_string());
}

BOOST_AUTO_TEST_CASE(summary_reports_status_and_figures) {
  BOOST_TEST(std::string(to_string(SolveStatus::Converged)) == "converged");
  BOOST_TEST(std::string(to_string(SolveStatus::Singular)) == "singular");
  BOOST_TEST(std::string(to_string(SolveStatus::MaxIterations)) == "max_iterations");
  SolveSummary s;
  s.solver = "newton";
  s.status = SolveStatus::Converged;
  s.iterations = 4;
  s.residual_max_abs = 3.1e-12;
  s.wall_time_seconds = 0.21e-3;
  BOOST_TEST(s.brief_report() == "newton: converged in 4 iterations, |c|max = 3.1e-12, 0.21 ms");
}

BOOST_AUTO_TEST_CASE(hessian_checker_passes_right_and_catches_wrong_hessians) {
  const std::vector<VecX> x{(VecX(4) << 1.2, 4.1, 3.3, 1.7).finished()};
  const pcr::test::Hs071Product product(0);
  const JacobianCheckResult ok = check_block_hessian(product, x, VecX::Constant(1, -0.7));
  BOOST_TEST(ok.passed, ok.to_string());
  BOOST_TEST(ok.entries_checked == 16);
  // A block whose Hessian forgets the weight: wrong unless the weight is 1.
  class UnweightedCircle : public CircleBlock {
   public:
    using CircleBlock::CircleBlock;
    void evaluate_hessian(const double* const*, const double*, double* H) const override {
      H[0] = 2.0, H[1] = 0.0, H[2] = 0.0, H[3] = 2.0;
    }
  };
  const UnweightedCircle circle(0, 1, 2.0);
  const std::vector<VecX> xy{VecX::Constant(1, 0.4), VecX::Constant(1, -1.3)};
  BOOST_TEST(check_block_hessian(circle, xy, VecX::Constant(1, 1.0)).passed);
  const JacobianCheckResult bad = check_block_hessian(circle, xy, VecX::Constant(1, 3.0));
  BOOST_TEST(!bad.passed);
  BOOST_TEST(std::abs(bad.numeric - 6.0) <= 1e-8);  // d(2 w x)/dx = 2 w = 6; FD of a linear function
  BOOST_CHECK_THROW(check_block_hessian(pcr::test::SquarePlusOne(0), {VecX::Ones(1)}, VecX::Ones(1)),
                    InputError);
}

BOOST_AUTO_TEST_CASE(declared_structural_zeros_are_left_out_of_the_pattern) {
  for (bool lie : {false, true}) {
    Problem p;
    const VariableId a = p.add_variable_block("a", (VecX(3) << 0.3, -0.7, 1.1).finished());
    const VariableId b = p.add_variable_block("b", (VecX(2) << 2.0, 0.5).finished());
    p.add_residual_block(std::make_shared<DeclaredSparseBlock>(a, b, lie));
    // 2 rows x 5 columns, less the 4 declared zeros (5 with the false declaration).
    BOOST_TEST(p.jacobian_nonzeros() == (lie ? 5 : 6));
    VecX c;
    SparseRowMajor J;
    const VecX x = p.initial_values();
    p.evaluate_residuals_and_jacobian(x, c, J);
    // Entries kept, from the formulas c0 = p0 q1 + sin p2, c1 = p1^2 q0 - p0 (x = [p, q]).
    BOOST_TEST(J.coeff(0, 0) == 0.5);
    BOOST_TEST(J.coeff(0, 4) == 0.3);
    BOOST_TEST(J.coeff(1, 0) == -1.0);
    BOOST_TEST(J.coeff(1, 1) == 2.0 * -0.7 * 2.0);
    BOOST_TEST(J.coeff(1, 3) == 0.49, boost::test_tools::tolerance(1e-15));
    BOOST_TEST(J.coeff(0, 2) == (lie ? 0.0 : std::cos(1.1)));
    const JacobianCheckResult r = check_problem_jacobian(p, x);
    BOOST_TEST(r.passed == !lie, r.to_string());
    if (lie) BOOST_TEST((r.block_name == "sparse" && r.row == 0 && r.column == 2), r.to_string());
  }
}
