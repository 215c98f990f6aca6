#pragma once
// Inertia of the second variation assembled on the nodes of a rod (held_rod.hpp, docs/design.md §4):
// the block-tridiagonal symmetric form with diagonal blocks D_j (the two segment stiffnesses meeting at
// node j) and coupling blocks E_j (segment j between nodes j and j + 1), the end nodes restricted to
// x_e = Z_e phi_e with the coupling's form phi^T B_e phi. Block LDL^T elimination from both ends towards
// a probe node p:
//   forward   P_0 = D_0,  P_j = D_j - E_{j-1}^T P_{j-1}^-1 E_{j-1}            (j < p)
//   backward  Q_N = D_N,  Q_j = D_j - E_j Q_{j+1}^-1 E_j^T                    (j > p)
//   probe     P_p = D_p - E_{p-1}^T P_{p-1}^-1 E_{p-1} - E_p Q_{p+1}^-1 E_p^T
// By Haynsworth's inertia additivity (Linear Algebra Appl. 1:73-81, 1968) the form has as many negative
// eigenvalues as all pivots together, and it is singular exactly when P_p is (the other pivots regular).
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/rods/stability/held_rod.hpp"

namespace pcr::stability {

/// Variations an end node admits: x_e = Z phi (Z: 6 x k, k = 0 for a clamped end) and the form B (k x k).
struct EndSpace {
  MatX Z = MatX::Zero(6, 0);
  MatX B = MatX::Zero(0, 0);
  int size() const { return static_cast<int>(Z.cols()); }
};

struct ChainInertia {
  int negative = 0;                  ///< pivots' negative eigenvalues (the probe's: below -tolerance)
  int neutral = 0;                   ///< probe eigenvalues within [-tolerance, tolerance]
  double probe_min = 0.0;            ///< smallest eigenvalue of the probe pivot (0 if it is empty)
  bool near_singular_pivot = false;  ///< a pivot other than the probe nearly singular: move the nodes
};

/// The probe node: the tip when it moves, else the base when it moves, else the middle node.
int probe_node(int segments, const EndSpace& base, const EndSpace& tip);

/// Inertia of the form of the segment stiffnesses K[j] (between nodes j and j + 1).
ChainInertia chain_inertia(const std::vector<Mat12>& K, const EndSpace& base, const EndSpace& tip, int probe,
                           double tolerance);

}  // namespace pcr::stability
