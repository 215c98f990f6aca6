// held_rod_index (held_rod.hpp): nodes, segment stiffnesses, end spaces, the count.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include "node_chain.hpp"
#include "pcr/rods/stability/held_rod.hpp"

namespace pcr {

namespace {

using stability::ChainInertia;
using stability::EndSpace;
using stability::Mat12;

/// Longest segment that holds no conjugate point with a margin (docs/design.md §4), from the largest
/// force, moment and curvature along the rod (sampled at 2 min_segments + 1 points):
///  - sqrt(EI / |n|): a compressed column's clamped-clamped conjugate distance is 2 pi sqrt(EI / P);
///  - EI / |m|: a twisted rod's is about 9 EI / |m| (Greenhill);
///  - 1 / |u|: a radian of turning per segment, so that the RK4 steps resolve the rotation;
/// EI the smallest of the bending and torsion stiffnesses.
/// Also the largest strain mismatch of the samples.
double longest_segment(const HeldRod& rod, const JacobiStateAt& state, int samples, double& mismatch) {
  double n = 0.0, m = 0.0, u = 0.0;
  mismatch = 0.0;
  for (int i = 0; i < samples; ++i) {
    const JacobiState y = state(rod.length * i / (samples - 1));
    n = std::max(n, y.force.norm());
    m = std::max(m, y.moment.norm());
    u = std::max(u, y.curvature);
    mismatch = std::max(mismatch, y.strain_mismatch);
  }
  const double EI = rod.bending_torsion_stiffness.minCoeff();
  double h = rod.length;
  if (n > 0.0) h = std::min(h, std::sqrt(EI / n));
  if (m > 0.0) h = std::min(h, EI / m);
  if (u > 0.0) h = std::min(h, 1.0 / u);
  return h;
}

/// Admitted variations of an end node and the coupling's curvature form (docs/design.md §4):
/// clamped none; collar and revolute a rotation about their fixed axis; spherical any rotation; free
/// any motion; universal the rotations about its two axes, R_e(phi) = exp(phi1 [a1]x) exp(phi2 [a2]x) R_e0,
/// whose rotation vector is phi1 a1 + phi2 a2 + 1/2 phi1 phi2 a1 x a2 + O(3) (Baker-Campbell-Hausdorff):
/// with the energy's gradient sigma m_e along the end rotation (sigma = +1 at s = L, -1 at s = 0) this adds
/// sigma m_e . (a1 x a2) phi1 phi2 to the second variation. The other kinds turn about fixed axes, whose
/// exponential coordinates are exact (no term).
EndSpace end_space(const HeldEnd& end, const JacobiState& y, double sigma, double moment_scale) {
  EndSpace e;
  switch (end.kind) {
    case RodEndKind::Clamped: break;
    case RodEndKind::Collar:
      e.Z = MatX::Zero(6, 1);
      e.Z.block<3, 1>(3, 0) = y.rotation.col(2);
      break;
    case RodEndKind::Revolute:
      e.Z = MatX::Zero(6, 1);
      e.Z.block<3, 1>(3, 0) = end.axis.normalized();
      break;
    case RodEndKind::Spherical:
      e.Z = MatX::Zero(6, 3);
      e.Z.block<3, 3>(3, 0).setIdentity();
      break;
    case RodEndKind::Universal: {
      const Vec3 a1 = end.axis.normalized(), a2 = end.second_axis.normalized();
      e.Z = MatX::Zero(6, 2);
      e.Z.block<3, 1>(3, 0) = a1;
      e.Z.block<3, 1>(3, 1) = a2;
      const double b = 0.5 * sigma * (y.moment / moment_scale).dot(a1.cross(a2));
      e.B = MatX::Zero(2, 2);
      e.B(0, 1) = e.B(1, 0) = b;
      break;
    }
    case RodEndKind::Free: e.Z = MatX::Identity(6, 6); break;
  }
  if (e.B.rows() != e.Z.cols()) e.B = MatX::Zero(e.Z.cols(), e.Z.cols());
  return e;
}

/// A segment stiffness is symmetric but for the integration error and the error of the state; above this
/// its segment is halved (the RK4 error, and with it the asymmetry, falls by about 16). Not below 0.01
/// times the state's strain mismatch: the neutral tolerance (below) is then 0.1 x mismatch whatever the
/// asymmetry, and halving further cannot make it smaller (on random Stewart-Gough states the mismatch is
/// 1e-6 - 3e-2, and a target of 1e-6 halved the segments of the most bent rods up to 12 times).
double target_asymmetry(double strain_mismatch) {
  return std::max(1e-6, 0.01 * strain_mismatch);
}

/// Segment stiffnesses of [s_a, s_b], split in halves where a piece reaches a conjugate point of its start
/// or is integrated less accurately than `target` (at most `depth` times). False when a conjugate
/// point remains.
bool add_segments(const HeldRod& rod, const JacobiStateAt& state, double s_a, double s_b, int substeps,
                  int depth, double target, std::vector<Mat12>& K, double& asymmetry) {
  Mat12 k;
  double a = 0.0;
  const bool regular = stability::segment_stiffness(rod, state, s_a, s_b, substeps, k, a);
  if (regular && (a <= target || depth == 0)) {
    K.push_back(k);
    asymmetry = std::max(asymmetry, a);
    return true;
  }
  if (depth == 0) return false;
  const double s_m = 0.5 * (s_a + s_b);
  return add_segments(rod, state, s_a, s_m, substeps, depth - 1, target, K, asymmetry) &&
         add_segments(rod, state, s_m, s_b, substeps, depth - 1, target, K, asymmetry);
}

/// Neutral tolerance of the probe eigenvalues (dimensionless, bending stiffnesses are O(1)): at least 1e-8,
/// 10 times the integration error (which the segments' asymmetry measures) and 0.1 times the state's
/// strain mismatch (an exact zero eigenvalue, the round post-buckled column's symmetry, measured at
/// 0.4-1 % of the mismatch of its collocation state: 1.5e-6 at 3.3e-4 with 4 elements of degree 5,
/// 8e-8 at 8.6e-6 with 8; test_stability_verdict).
double neutral_tolerance(double asymmetry, double strain_mismatch) {
  return std::max({1e-8, 10.0 * asymmetry, 0.1 * strain_mismatch});
}

/// Largest ratio of a shear/extension stiffness to the bending stiffness scale EI_max / L^2 for which
/// the segment stiffnesses keep enough digits. Measured on a cantilever under a transverse tip load
/// (10 EI / L^2, bench_all's R2 at other stiffnesses, degree 5, 4-64 elements, mixed and condensed): the
/// verdict is the same on every mesh up to 1e10 and scatters (stable or 1-2 unstable modes with
/// margins of -1e2 to -1e5) from 3e10 on; 1e9 keeps a factor 30. Practical rods lie far below: a solid
/// round section has EA L^2 / EI = 4 (L / r)^2, 4e6 at L / r = 1,000.
constexpr double kMaxStiffnessRatio = 1e9;

/// False, with the reason, when a stiffness ratio of the rod is beyond kMaxStiffnessRatio.
bool stiffness_ratio_in_range(const HeldRod& rod, std::string& failure) {
  const double bending_scale = rod.bending_torsion_stiffness.maxCoeff() / (rod.length * rod.length);
  const double ratio = rod.shear_extension_stiffness.maxCoeff() / bending_scale;
  if (ratio <= kMaxStiffnessRatio) return true;
  std::ostringstream msg;
  msg << "shear/extension stiffness " << ratio << " times EI / L^2: beyond the " << kMaxStiffnessRatio
      << " up to which the Jacobi segment stiffnesses are reliable (a nearly inextensible rod, "
         "docs/design.md §4)";
  failure = msg.str();
  return false;
}

}  // namespace

HeldRodIndex held_rod_index(const HeldRod& rod, const JacobiStateAt& equilibrium,
                            const HeldRodOptions& options) {
  HeldRodIndex out;
  if (!stiffness_ratio_in_range(rod, out.failure)) return out;
  // The states by s, evaluated once: neighbouring segments share their end node, and a halved segment
  // meets about half of its sample points again. Keys: s / L in units of 2^-36 (the points differ by
  // round-off only when they are the same; distinct ones lie at least L / 2^14 apart).
  std::unordered_map<long long, JacobiState> known;
  const JacobiStateAt state = [&](double s) {
    const long long key = std::llround(std::ldexp(s / rod.length, 36));
    const auto found = known.find(key);
    if (found != known.end()) return found->second;
    return known.emplace(key, equilibrium(s)).first->second;
  };
  const int substeps = std::max(1, options.rk4_substeps);
  const int min_segments = std::max(1, options.min_segments);
  double mismatch = 0.0;
  const double h_max = longest_segment(rod, state, 2 * min_segments + 1, mismatch);
  const int base_segments = std::max(min_segments, static_cast<int>(std::ceil(rod.length / h_max)));
  const double moment_scale = rod.bending_torsion_stiffness.maxCoeff() / rod.length;
  const EndSpace base = end_space(rod.base, state(0.0), -1.0, moment_scale);
  const EndSpace tip = end_space(rod.tip, state(rod.length), 1.0, moment_scale);
  // A pivot nearly singular away from the probe: a conjugate point of a partial problem sits on its node.
  // The count does not depend on where the nodes are: move them (one segment more) and count again.
  constexpr int kNodeMoves = 3;
  for (int move = 0; move <= kNodeMoves; ++move) {
    const int N = base_segments + move;
    std::vector<Mat12> K;
    K.reserve(N);
    double asymmetry = 0.0;
    for (int j = 0; j < N; ++j) {
      if (!add_segments(rod, state, rod.length * j / N, rod.length * (j + 1) / N, substeps, 6,
                        target_asymmetry(mismatch), K, asymmetry)) {
        std::ostringstream msg;
        msg << "no segment near s = " << rod.length * j / N
            << " m is free of conjugate points (transfer matrix singular)";
        out.failure = msg.str();
        return out;
      }
    }
    const double tolerance = neutral_tolerance(asymmetry, mismatch);
    const int probe = stability::probe_node(static_cast<int>(K.size()), base, tip);
    const ChainInertia c = stability::chain_inertia(K, base, tip, probe, tolerance);
    if (c.near_singular_pivot) continue;
    out.ok = true;
    out.unstable_modes = c.negative;
    out.neutral_modes = c.neutral;
    out.margin = c.probe_min;
    out.length_scale = rod.length;
    out.energy_scale = moment_scale;
    out.asymmetry = asymmetry;
    out.neutral_tolerance = tolerance;
    out.strain_mismatch = mismatch;
    out.segments = static_cast<int>(K.size());
    return out;
  }
  out.failure = "a pivot of the node elimination stays nearly singular wherever the nodes are put";
  return out;
}

}  // namespace pcr
