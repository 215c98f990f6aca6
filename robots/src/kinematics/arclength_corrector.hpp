#pragma once
// Pseudo-arclength continuation of the FK system along a straight line of inputs (internal header of
// pcr::robots; docs/paths_through_folds.md). The unknowns are y = (x, lambda): the free assembly
// variables x and the line parameter lambda, inputs u(lambda) = u_a + lambda (u_b - u_a). A point on the
// curve R(x, u(lambda)) = 0 is found by Newton on the bordered system (Keller 1977)
//
//   [ R_x    R_lambda ] [dx     ]     [ R                       ]
//   [ a^T W           ] [dlambda] = - [ <a, y - y_k>_W - sigma  ],   R_lambda = R_u (u_b - u_a),
//
// a the normal of the hyperplane the point must lie on: the tangent t_k (arclength sigma from y_k) or
// e_lambda (a given lambda). The matrix is regular at folds (R_x singular, [R_x R_lambda] of full rank),
// so the curve is followed through them. The tangent at a converged point solves the same matrix with
// the right-hand side (0, 1): t = z / |z|_W, oriented by <t_k, t>_W > 0.
// Factorised with BorderedBlockLu (lambda one more border column, the hyperplane row one more border
// row; the rods' bands are those of the FK Newton systems), the sparse LU where a block is singular.
#include <Eigen/SparseCore>
#include <cstdint>
#include <memory>
#include <string>

#include "pcr/robots/robot_assembly.hpp"
#include "pcr/solve/grouped_lu.hpp"

namespace pcr::kinematics {

/// A point of the continuation: the full assembly state (inputs written in), lambda, the unit tangent
/// (size free + 1, W-norm 1; its last entry is dlambda / dsigma).
struct ArcPoint {
  VecX x;
  double lambda = 0.0;
  VecX tangent;
  double tau() const { return tangent[tangent.size() - 1]; }
};

class ArcCorrector {
 public:
  /// The line from inputs u_a to u_b on the assembly's FK system; tolerance on the max-abs residual.
  ArcCorrector(const RobotAssembly& assembly, const VecX& u_a, const VecX& u_b, double tolerance);

  /// The start point: x converged at u_a (lambda = 0); its tangent towards increasing lambda. Sets the
  /// weights W (see weights_). False when the matrix is singular.
  bool start(const VecX& x, ArcPoint& out);
  /// Newton from y_k + sigma t_k onto the hyperplane <t_k, y - y_k>_W = sigma; out gets the point and
  /// its tangent. False when Newton does not converge within max_iterations.
  bool arclength_step(const ArcPoint& from, double sigma, ArcPoint& out, int max_iterations = 8);
  /// Newton from `guess` onto lambda = target (the tangent of `orient` orients the result's).
  bool at_lambda(const ArcPoint& guess, const VecX& orient, double target, ArcPoint& out,
                 int max_iterations = 12);

  /// Scales the unknowns' weights W down (never up) so that the tangent of p has equal parts in x and
  /// lambda, as start() does at the segment's start, and renormalises p's tangent. At a snap's landing
  /// the branch may move much faster in x per input than the start did (a leg buckled: its deflection
  /// grows like sqrt(L dL)); with the start's W the steps of max_step would then advance lambda by
  /// |tau| max_step each, a thousand times less than at the start.
  void rebalance(ArcPoint& p);
  /// y + sigma t, not corrected.
  ArcPoint predictor(const ArcPoint& from, double sigma) const;

  VecX inputs_at(double lambda) const { return u_a_ + lambda * (u_b_ - u_a_); }
  double weighted_dot(const VecX& a, const VecX& b) const;
  /// The free part of a full state followed by lambda.
  VecX free_vector(const VecX& x, double lambda) const;
  int jacobian_evaluations() const { return jacobians_; }
  int iterations() const { return iterations_; }

 private:
  /// Newton on R = 0 and <normal, y - y0>_W = offset from y (in: start, out: result).
  bool correct(const VecX& normal, const VecX& y0, double offset, VecX& y, VecX& tangent_out,
               int max_iterations);
  /// Evaluates R and the bordered matrix at y with the hyperplane row normal^T W; false if not finite.
  bool evaluate(const VecX& y, const VecX& normal, VecX& residual);
  using RowJacobian = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  /// The bordered matrix's pattern from J's (its values set by evaluate) and the slot of each of J's
  /// entries in it.
  void build_pattern(const RowJacobian& J);
  bool factorize();
  VecX solve(const VecX& rhs) const;
  void write_state(const VecX& y, VecX& x) const;

  const RobotAssembly& assembly_;
  VecX u_a_, u_b_;
  double tolerance_;
  VecX x_template_;                     // full state holding the fixed variables
  std::vector<int> free_;               // global index of each free column
  std::vector<int> inputs_;             // global index of each input variable
  VecX row_lower_;                      // c_l of the rows (equality rows: c(x) = c_l)
  VecX weights_;                        // W: free columns then lambda (size free + 1)
  RowJacobian jacobian_;                // J of the last evaluation (its pattern kept)
  Eigen::SparseMatrix<double> matrix_;  // the bordered matrix
  std::uint64_t pattern_version_ = 0;   // the problem's structure_version() the pattern was built for
  std::vector<int> slot_;               // per entry of J: its value's index in matrix_, -1 when not there
  std::vector<double> factor_;          // per entry of J: 1 (a free column) or du_i (input i: R_lambda)
  std::vector<int> normal_slot_;        // the hyperplane row's value indices, per column
  GroupedLu lu_;                        // columns grouped by variable group, lambda a border column
  int jacobians_ = 0, iterations_ = 0;
};

}  // namespace pcr::kinematics
