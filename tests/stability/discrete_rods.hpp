#pragma once
// An independent stability check for the tests (docs/design.md §4): a variational discretisation of
// Cosserat rods and rigid platforms, its total potential energy V_h, and the inertia of its Hessian.
//
// Staggered discrete Cosserat rod (Lang, Linn & Arnold, Multibody Syst. Dyn. 25, 2011; Jung, Leyendecker,
// Linn & Ortiz, IJNME 85, 2011): N equal segments of length h, nodes p_0..p_N, one frame q_i (unit
// quaternion) per segment,
//   V_h = sum_i h W_se(v_i) + sum_i h W_bt(u_i) + (h/2) W_bt(u_base) [+ (h/2) W_bt(u_tip)] - dead loads,
//   v_i = R(q_i)^T (p_{i+1} - p_i) / h,   u = (2 / d) vec(conj(q_a) (x) q_b) between frames d apart,
//   W_se = 1/2 (v - e3)^T K_SE (v - e3),   W_bt = 1/2 u^T K_BT u,
// the clamped base frame coupled to q_0 over h/2, an attached tip's frame (clamped: the platform frame
// times the attachment; collar: times a free twist about its z axis; spherical: none) to q_{N-1} over
// h/2; distributed dead forces lumped on the nodes (trapezoid), an attached tip node moving with its
// platform. Couplings are eliminated by this parametrisation (no multipliers); every rotation is
// perturbed as q = normalise([1, phi / 2]) (x) q0 (a retraction that agrees with exp to second order),
// platforms as (x + dx, normalise([1, phi / 2]) (x) Q). The Hessian comes from second-order forward AD
// (hyper_dual.hpp) of each local term; at a stationary point (relax()) its number of negative
// eigenvalues is the discrete model's number of unstable modes.
#include <functional>
#include <vector>

#include "pcr/core/types.hpp"

namespace pcr::test {

enum class DiscreteTip { Free, Clamped, Collar, Spherical };

struct DiscreteRodSpec {
  double length = 1.0;
  Vec3 k_se = Vec3::Zero(), k_bt = Vec3::Zero();
  Vec3 distributed_force = Vec3::Zero();  ///< dead, per length [N/m]
  Vec3 base_position = Vec3::Zero();      ///< the base is clamped in the world
  Mat3 base_rotation = Mat3::Identity();
  int base_hinge = -1;  ///< the passive hinge (DiscreteHingeSpec) the base turns with, or -1: fixed
  DiscreteTip tip = DiscreteTip::Free;
  Vec3 tip_force = Vec3::Zero();            ///< free tip: dead force
  int platform = -1;                        ///< attached tip: its platform
  Vec3 attachment_position = Vec3::Zero();  ///< in the platform frame
  Mat3 attachment_rotation = Mat3::Identity();
  int segments = 32;
};

/// Dead forces on a platform: (point in the platform frame, force in the world frame).
struct DiscretePlatformSpec {
  std::vector<std::pair<Vec3, Vec3>> forces;
};

/// A passive revolute joint between the world and clamped rod bases: the bases (position and frame, given
/// at the joint's value) and the dead forces on its link turn by the angle change t about the world axis
/// through `origin`; its spring adds 1/2 k (value + t - rest)^2. A rotation is perturbed as
/// normalise([1, t a / 2]) (x) (its rotation so far), which turns by 2 atan(t / 2) = t + O(t^3): the same
/// gradient and Hessian at t = 0 as the exact angle.
struct DiscreteHingeSpec {
  Vec3 origin = Vec3::Zero(), axis = Vec3::UnitY();  ///< world frame, unit axis
  double stiffness = 0.0, rest = 0.0, value = 0.0;   ///< [N m/rad], [rad], [rad]
  std::vector<std::pair<Vec3, Vec3>> forces;         ///< (world point at `value`, world force)
};

class DiscreteRods {
 public:
  DiscreteRods(std::vector<DiscreteRodSpec> rods, std::vector<DiscretePlatformSpec> platforms,
               std::vector<DiscreteHingeSpec> hinges = {});

  /// Start state of rod r from a continuous one: positions at the nodes, frames at the segment centres.
  void set_rod(int r, const std::function<void(double s, Vec3& p, Mat3& R)>& state);
  void set_platform(int p, const Vec3& x, const Mat3& R);
  /// Newton on grad V_h = 0 from the current state (quadratic convergence with the exact Hessian);
  /// true when the last step moved no node by more than 1e-11 L and no frame by more than 1e-11 rad.
  bool relax(int max_iterations = 30);

  struct Inertia {
    int negative = 0;       ///< eigenvalues below -zero_tolerance (of the Jacobi-scaled Hessian)
    int zero = 0;           ///< within +-zero_tolerance
    double smallest = 0.0;  ///< smallest eigenvalue of the Jacobi-scaled Hessian
  };
  Inertia inertia(double zero_tolerance = 1e-9) const;
  int num_variables() const { return num_variables_; }
  Vec3 tip_position(int r) const { return rods_[r].p.back(); }

 private:
  struct Rod {
    DiscreteRodSpec spec;
    std::vector<Vec3> p;             // nodes 0..N
    std::vector<Eigen::Vector4d> q;  // segments 0..N-1
    Eigen::Vector4d base_q,
        twist_q;  // clamp frame; collar twist (tip frame = platform q (x) attachment (x) twist)
    std::vector<int> p_index, q_index;  // first variable, -1 fixed, -2 the platform-attached tip node,
                                        // -3 the base node on a hinge
    int twist_index = -1;
  };
  struct Platform {
    DiscretePlatformSpec spec;
    Vec3 x = Vec3::Zero();
    Eigen::Vector4d Q = Eigen::Vector4d(1, 0, 0, 0);
    int index = -1;
  };
  struct Hinge {
    DiscreteHingeSpec spec;
    Eigen::Vector4d turn = Eigen::Vector4d(1, 0, 0, 0);  // rotation since `value`
    double angle = 0.0;                                  // its angle about the axis
    int index = -1;
  };
  std::vector<Rod> rods_;
  std::vector<Platform> platforms_;
  std::vector<Hinge> hinges_;
  int num_variables_ = 0;

  double assemble(VecX* gradient, MatX* hessian) const;
  void step(const VecX& dy);
  friend struct DiscreteTerms;
};

}  // namespace pcr::test
