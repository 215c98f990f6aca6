#pragma once
// Frictionless unilateral contact of a collocation rod with rigid obstacles (docs/contact.md).
//
// Discretisation (mixed form collocated at the midpoints u_j of the Greville abscissae, the only
// formulation supported): the force balance at u_j reads n'(u_j) + f + F_j = 0 with one contact force
// density unknown F_j (N/m, world frame; RodVariables::contact_forces) per midpoint, and
//   F_j = sum_k lambda_jk nu_k(p(u_j)),   lambda_jk >= 0,   g_k(p(u_j)) >= 0,   lambda_jk g_k = 0
// for each obstacle k the rod may touch (gap g_k and normal nu_k: obstacle.hpp). The force acts through
// the centerline (no couple: frictionless contact of a round section). The complementarity conditions
// are one equation each, phi(g_k / L0, lambda_jk L0 / F0) = 0, so the system stays square and pcr's
// Newton solves it as a semismooth Newton method:
//  - Fischer-Burmeister: phi(a, b) = a + b - sqrt(a^2 + b^2) (Fischer, Optimization 24 (1992) 269-284);
//    phi = 0 iff a >= 0, b >= 0, a b = 0. At (0, 0) the generalised Jacobian element (1 - 1/sqrt 2) (1, 1)
//    is used.
//  - Min: phi(a, b) = min(a, b), the primal-dual active set method as a semismooth Newton method
//    (Hintermueller, Ito & Kunisch, SIAM J. Optim. 13 (2002) 865-888).
// The collocated densities converge to the contact measure only in the sense of resultants: the point
// forces at the ends of a contact interval (e.g. at a touchdown) are spread over the cells next to them,
// so an interval end is resolved to about one cell L (tau_{j+1} - tau_j).
//
// Sharp obstacles (edges, points: zero radius), and spheres, capsules and cylinders with
// Obstacle::point_contact, touch the rod at one section u_c with a concentrated
// force F = lambda L nu, the limit of a density concentrated at u_c. Their unknowns are u_c, lambda and
// G = F / L; rows (edge_contact_block.cpp): G = lambda nu(p(u_c)); u_c is the section nearest to the
// obstacle (v . p'(u_c) = 0, or an end of the rod); phi(g(p(u_c)) / L0, lambda L0 / F0) = 0. F enters the
// force balance of the two midpoints u_m <= u_c < u_{m+1} around it as the densities w F / (L (tau_{j+1}
// - tau_j)) with the linear-interpolation weights w_m = 1 - t, w_{m+1} = t, t = (u_c - u_m) / (u_{m+1} -
// u_m) (extrapolated beyond the first and last midpoint): the resultant and the first moment of the
// force are those of F at u_c, and every share is continuous in u_c. Distributed gap rows at the
// midpoints would miss a sharp obstacle whenever the midpoints are more than 2 r apart.
//
// A roller with the adhesion law (no slip; Obstacle::law) touches the rod at one section too, but the
// section is prescribed by the no-slip kinematics: the material arcs that pass the contact on the rod and
// on the roller are equal, u_c L = sigma_c = sigma_0 + R (psi - theta) (t . e), with the stuck section
// sigma_0 and the roller's angle theta (Obstacle), the rotation psi of the contact direction about the
// axis since the reference state and the rolling direction e = a x nu (t . e = +-1 for a rod normal to
// the axis); and the force has a tangential part along the rod's unit tangent t: F = (lambda nu + mu t) L
// with one more unknown mu. The nearest-section row becomes mu's equation while the contact is closed
// (the section u_c must be where the rod touches the roller), and mu = 0 while it is open
// (adhesion_block.cpp). Across the rod (along the roller's axis for a rod normal to it) the contact is
// frictionless. The force acts through the centerline: the couple r nu x mu t L of the tangential force
// about it (it acts on the rod's surface) is neglected.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "pcr/rods/collocation_rod.hpp"
#include "pcr/rods/obstacle.hpp"
#include "pcr/solve/problem.hpp"

namespace pcr {

/// GapOnly is not a complementarity function: its row is the scaled gap g / L0 alone, for the Ipopt
/// treatment (contact_ipopt.hpp), which bounds it below by 0 and adds the relaxed product row.
enum class ComplementarityFunction { FischerBurmeister, Min, GapOnly };
const char* to_string(ComplementarityFunction function);

struct RodContactOptions {
  std::vector<Obstacle> obstacles;  ///< world frame, validated
  double radius = 0.0;              ///< contact radius r of the rod [m] (> 0)
  ComplementarityFunction function = ComplementarityFunction::FischerBurmeister;
};

/// What add_rod_contact added: per midpoint j the multipliers lambda_jk of the K distributed obstacles
/// (one block of K values; none when K = 0), per sharp obstacle its block [u_c, lambda, G].
struct RodContactVariables {
  RodContactOptions options;
  std::vector<int> distributed;             ///< indices in options.obstacles of the distributed obstacles
  std::vector<int> sharp;                   ///< ... and of the sharp ones (edges, points)
  std::vector<double> midpoints;            ///< u_j
  std::vector<VariableId> multipliers;      ///< per midpoint (K > 0 only), size K = distributed.size()
  std::vector<int> multiplier_offsets;      ///< their indices in x
  std::vector<ResidualId> blocks;           ///< per midpoint: "rod.contact" (3 + K rows)
  std::vector<VariableId> sharp_variables;  ///< per sharp obstacle: [u_c, lambda, G (3)]
  std::vector<int> sharp_offsets;           ///< their indices in x
  std::vector<ResidualId> sharp_blocks;     ///< per sharp obstacle: "rod.sharp_contact" (5 rows), or for
                                            ///< an adhesive roller "rod.adhesive_contact" (6 rows)
  /// Per sharp obstacle: the index in x of its tangential force mu (adhesive rollers), else -1.
  std::vector<int> tangential_offsets;
  /// Ipopt treatment only (relax_rod_contact, contact_ipopt.hpp): the fixed relaxation parameter mu of
  /// the rod's product rows (-1 without), and the blocks that replace `blocks` and `sharp_blocks` (which
  /// are switched off).
  VariableId relaxation = -1;
  std::vector<ResidualId> relaxed_blocks;
};

/// Adds the multipliers and the contact rows of a rod added with RodDiscretization::contact_forces.
/// Throws InputError for an unsupported formulation, no obstacle, a bad radius or obstacle, or an initial
/// configuration (the problem's initial values) whose centerline penetrates an obstacle at a midpoint
/// (gap < -1e-9 L0), naming the rod, the obstacle, the arc length and the gap.
/// wrap_block, when given, is applied to every contact block before it is added to the problem (the
/// robots' assembly wraps them to move the obstacles with a link whose pose depends on unknowns;
/// options.obstacles are then their placement in the problem's initial configuration).
using ContactBlockWrapper = std::function<std::shared_ptr<ResidualBlock>(std::shared_ptr<ResidualBlock>)>;
RodContactVariables add_rod_contact(Problem& problem, const CollocationRod& rod, const RodVariables& vars,
                                    const RodContactOptions& options,
                                    const ContactBlockWrapper& wrap_block = {});

/// One run of collocation cells [tau_j, tau_{j+1}] (arc lengths) in contact with an obstacle: from the first
/// to the last cell carrying force, across cells between them that touch without carrying force.
/// A sharp obstacle's contact is one point: s_begin = s_end = centroid = the contact section.
struct ContactInterval {
  double s_begin = 0.0, s_end = 0.0;  ///< [m]
  Vec3 force = Vec3::Zero();          ///< resultant on the rod: sum_j lambda_j nu_j L (tau_{j+1} - tau_j) [N]
  /// Arc length of the force's centroid: sum_j s_j |F_j| / sum_j |F_j| over the cells' resultants [m].
  double centroid = 0.0;
};

/// The contact of one rod with one obstacle in a solution.
struct ObstacleContact {
  std::string rod, obstacle;
  std::vector<ContactInterval> intervals;
  Vec3 force = Vec3::Zero();  ///< resultant of all intervals [N]
  /// Smallest gap along the centerline (sampled at 8 points per cell) and where; negative values are
  /// penetration between the collocation points.
  double min_gap = 0.0, min_gap_arc_length = 0.0;
  /// Penetration that the results accept without a warning: kPenetrationTolerance times the contact radius.
  double penetration_tolerance = 0.0;
  /// Per midpoint: arc length s_j, density lambda_j [N/m] and gap g_j [m]. Sharp obstacles: the contact
  /// section s_c, the force magnitude |F| [N] and the gap there (one value each).
  std::vector<double> arc_lengths, densities, gaps;
  /// Per midpoint: the cell's resultant lambda_j nu_j L (tau_{j+1} - tau_j) on the rod [N, world frame].
  /// Sharp obstacles: the concentrated force (one value; zero when the contact is not active).
  std::vector<Vec3> forces;
  bool concentrated = false;  ///< a sharp obstacle: a point force (one interval of zero length)
  /// An adhesive roller (Obstacle::law): the force's tangential part, signed along the rod's unit tangent
  /// at the contact section [N] (0 while the contact is open; included in `force`).
  bool adhesive = false;
  double tangential_force = 0.0;
};

/// The penetration the results tolerate, as a fraction of the rod's contact radius r. The gap rows hold at
/// the collocation midpoints only; between them the centerline may dip into an obstacle. A dip below
/// 0.1 r is smaller than the tube model's own error for a rod that shears (O(r eps), with eps up to a few
/// percent near concentrated contact forces) would make it, and invisible at the rod's scale; a dip of
/// the order of r means the rod's surface, or for a sharp edge its centerline, passes through the
/// obstacle between two midpoints, i.e. the contact is not resolved by the mesh (docs/contact.md).
inline constexpr double kPenetrationTolerance = 0.1;

/// The smallest sampled gap of one rod over all its obstacles.
struct RodContactGap {
  std::string rod, obstacle;               ///< the rod and the obstacle of its smallest gap
  double min_gap = 0.0, arc_length = 0.0;  ///< [m]
  double tolerance = 0.0;                  ///< kPenetrationTolerance r [m]
  bool penetrates() const { return min_gap < -tolerance; }
};

/// Per rod (in the order of `contacts`, whose entries of one rod follow each other) its smallest gap.
std::vector<RodContactGap> rod_contact_gaps(const std::vector<ObstacleContact>& contacts);

/// A warning for the solve summary naming every rod that penetrates by more than its tolerance, with the
/// depth, the arc length and the obstacle, and asking for more elements; "" when none does.
std::string contact_penetration_warning(const std::vector<RodContactGap>& gaps);

/// The contact set of a rod: one entry per obstacle it may touch. A cell carries force when its density
/// exceeds 1e-8 F0 / L0 (the solver's residual tolerance scale); it touches when its gap is below 1e-6 L0.
/// The densities of a contact interval may alternate between large and vanishing values from cell to cell
/// (a checkerboard mode of the collocated densities, seen on a beam lying on a plane): their sums over
/// the cells, the resultants, are what converges.
std::vector<ObstacleContact> read_rod_contact(const CollocationRod& rod, const RodVariables& vars,
                                              const RodContactVariables& contact, const VecX& x);

}  // namespace pcr
