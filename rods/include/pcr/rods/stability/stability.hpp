#pragma once
// Stability verdict of an equilibrium (docs/design.md §4 "Stability"): the number of unstable modes is
// the Morse index of the second variation of the total potential energy on the admissible variations
// (its number of negative eigenvalues), valid for conservative loads; a positive definite second
// variation is a strict local minimum of the energy, i.e. a stable equilibrium.
#include <string>
#include <vector>

namespace pcr {

enum class StabilityVerdict {
  NotChecked,  ///< not asked for, or the solve did not converge
  Stable,      ///< second variation positive definite: no unstable mode, no neutral one
  Unstable,    ///< unstable_modes > 0 (whatever the neutral modes)
  Critical,    ///< no unstable mode but a neutral one: a fold or bifurcation point, or a symmetry
  Unknown,     ///< an assumption of the criterion fails (reason says which)
};
const char* to_string(StabilityVerdict verdict);

struct Stability {
  StabilityVerdict verdict = StabilityVerdict::NotChecked;
  /// Negative eigenvalues of the second variation on the admissible variations (Morse index); 0 unless
  /// Stable, Unstable or Critical.
  int unstable_modes = 0;
  /// Eigenvalues of the probe (or reduced) stiffness within the neutral tolerance of zero.
  int neutral_modes = 0;
  /// Smallest eigenvalue of the dimensionless probe stiffness (one rod: at its free end, or at its
  /// middle section when both ends are clamped; robot: the reduced stiffness of the platforms and passive
  /// joints); goes to zero at a fold or bifurcation. Scaling: displacements by a length L0, rotations in rad,
  /// energy by a moment M0 (docs/design.md §4). 0 when not computed.
  double margin = 0.0;
  /// The scales of the margin: displacements divided by length_scale [m], the second variation of the
  /// energy by energy_scale [J]; e.g. a rotational stiffness of margin x energy_scale N m / rad.
  double length_scale = 0.0, energy_scale = 0.0;
  /// Largest relative asymmetry of a stiffness that theory says is symmetric (a check of the
  /// computation: integration and discretisation errors).
  double asymmetry = 0.0;
  /// Unknown: which assumption fails; Critical: what the neutral mode may be; a robot's count taken on a
  /// refined mesh (its reduced stiffness too asymmetric on the requested one) says so.
  std::string reason;
  /// Robots: each rod's unstable modes with its couplings held in fixed link frames (rod order), and
  /// the negative eigenvalues of the reduced stiffness of the platforms and passive joint coordinates
  /// (the border); their sum is unstable_modes.
  std::vector<int> rod_unstable_modes;
  int border_unstable_modes = 0;
};

/// Stable / Unstable / Critical from the counts (unstable first, then neutral).
StabilityVerdict verdict_of(int unstable_modes, int neutral_modes);
/// Whether s is a count (Stable, Unstable or Critical): unstable_modes and margin hold values.
bool is_counted(const Stability& s);
/// A Stability with verdict Unknown and the reason.
Stability unknown_stability(std::string reason);
/// "1 unstable mode", "n unstable modes" (for messages).
std::string unstable_modes_text(int n);

}  // namespace pcr
