// Energy minimisation, then Newton, then the stability verdict (energy_fallback.hpp).
#include "energy_fallback.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <utility>

#include "../stability/robot_stability_parts.hpp"
#include "energy_model.hpp"
#include "pcr/robots/robot_stability.hpp"
#include "pseudo_transient_snap.hpp"
#include "refined_verdict.hpp"
#include "solve_support.hpp"

namespace pcr::kinematics {

namespace {

/// Ipopt 3.11's MUMPS keeps global state (ipopt_solver.hpp): FK objects in several threads that reach
/// this fallback at once take turns.
std::mutex& ipopt_mutex() {
  static std::mutex m;
  return m;
}

/// Ipopt on the energy: exact gradient, Hessian by differences of it (energy_hessian.hpp). tol 1e-8 on the
/// scaled problem: the minimiser need only be inside Newton's basin of the equilibrium (Newton then reaches
/// the full tolerance); constraint rows to 1e-10 (L0 units, as the collocation tolerance). 3,000 iterations:
/// the passive_hinge input of docs/design.md "Energy minimisation (the last FK strategy)" takes a few
/// hundred.
IpoptOptions energy_ipopt_options() {
  IpoptOptions o;
  o.tol = 1e-8;
  o.constraint_tolerance = 1e-10;
  o.max_iterations = 3000;
  o.warm_start = false;
  return o;
}

std::string format(const char* fmt, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, fmt, value);
  return buffer;
}

/// "; the equilibrium is unstable (N unstable modes)" and the like, for a verdict that is not stable.
std::string not_stable(const Stability& v) {
  return std::string("; the equilibrium is ") + to_string(v.verdict) +
         (v.verdict == StabilityVerdict::Unstable ? " (" + unstable_modes_text(v.unstable_modes) + ")"
          : v.reason.empty()                      ? ""
                                                  : " (" + v.reason + ")");
}

/// The energy's minimum that Ipopt reached from one start.
struct Minimum {
  const EnergyModel& energy;
  double value;  ///< V at the minimiser [J]
};

/// Two discretisations of one equilibrium differ in energy by far less than this fraction of it (the Ritz
/// minimiser and the collocation's equilibrium next to it: 5.4e-7 on planar_post at 0.177198 0.184144
/// 0.182836 m); Newton landing on another equilibrium changes it by more.
constexpr double kSameMinimum = 1e-5;

/// The verdicts the fallback accepts: stable, or `unknown` only because a rod touches an obstacle (the
/// contact constraints are not in the second variation) at a state with the minimum's energy (to
/// kSameMinimum of it, or of the energy scale M0 L0 where it is near 0): the collocation's equilibrium
/// next to a minimiser of the energy with its gap constraints.
bool accepted(const RobotAssembly& assembly, const Minimum& m, const VecX& x, const Stability& v,
              std::string& note) {
  if (v.verdict == StabilityVerdict::Stable) return true;
  if (v.verdict != StabilityVerdict::Unknown || stability::touching_contact(assembly, x).empty())
    return false;
  const double V = m.energy.energy(m.energy.from_state(x));
  if (std::abs(V - m.value) <= kSameMinimum * std::max(std::abs(m.value), m.energy.energy_scale()))
    return true;
  note += "; in contact at energy " + format("%.9g", V) + " J, not the minimum's";
  return false;
}

/// The verdict of the equilibrium x, taken on twice the elements where the requested mesh cannot count
/// (refined_verdict.hpp), as FK reports it.
Stability judged_verdict(const FkData& data, const VecX& x) {
  Stability v = robot_stability(*data.model->assembly, x);
  refine_unknown_verdict(*data.model->assembly, x, data.model->options.tolerance, v);
  return v;
}

/// Newton from the minimiser (xs, in and out): true at an accepted equilibrium (its verdict in v, the
/// solve's summary in summary).
bool newton_to_stable(FkData& data, const Minimum& minimum, const VecX& inputs, VecX& xs, EnergyFallback& out,
                      std::string& note, SolveSummary& summary, Stability& v) {
  summary = data.solve_at(inputs, xs);
  out.iterations += summary.iterations;
  out.jacobians += summary.jacobian_evaluations;
  if (!summary.converged() || !xs.allFinite()) {
    note += "; Newton from the minimiser: " + summary.message;
    return false;
  }
  note += "; Newton " + std::to_string(summary.iterations) + " iterations";
  v = judged_verdict(data, xs);
  if (accepted(*data.model->assembly, minimum, xs, v, note)) return true;
  note += not_stable(v);
  return false;
}

/// The damped motion of the platforms and passive joints from `start` (pseudo_transient_snap.hpp; `label`
/// names it in the note), judged as Newton's result is: true at an accepted equilibrium (xs, v, summary:
/// the FK Newton solver's at it).
bool damped_motion(FkData& data, const Minimum& minimum, const VecX& inputs, const VecX& start, double shift,
                   const std::string& label, VecX& xs, EnergyFallback& out, std::string& note,
                   SolveSummary& summary, Stability& v) {
  const RobotAssembly& assembly = *data.model->assembly;
  const PseudoTransientResult r =
      pseudo_transient_equilibrium(assembly, start, data.model->options.tolerance, shift);
  out.iterations += r.iterations;
  out.jacobians += r.jacobian_evaluations;
  note += "; " + label + ": ";
  if (!r.converged) {
    note += r.stopped;
    return false;
  }
  v = judged_verdict(data, r.x);
  note += std::to_string(r.steps) + " steps";
  if (!accepted(assembly, minimum, r.x, v, note)) {
    note += not_stable(v);
    return false;
  }
  xs = r.x;
  summary = data.solve_at(inputs, xs);  // at the equilibrium: its residual, in the solver's summary
  return summary.converged();
}

/// Where Newton from the minimiser lands on an unstable equilibrium or none (the energy model's minimiser
/// lies off the collocation's equilibria by the difference of the two discretisations, and Newton's
/// first steps can cross a ridge), the damped motion from the minimiser (with the shift on the rods'
/// unknowns where the platforms alone stall, as the snap does) follows the robot's descent instead.
bool damped_to_stable(FkData& data, const Minimum& minimum, const VecX& inputs, const VecX& minimiser,
                      VecX& xs, EnergyFallback& out, std::string& note, SolveSummary& summary, Stability& v) {
  for (double shift : {0.0, 1e-3})
    if (damped_motion(
            data, minimum, inputs, minimiser, shift,
            shift > 0.0 ? "damped motion from the minimiser (shifted)" : "damped motion from the minimiser",
            xs, out, note, summary, v))
      return true;
  return false;
}

/// Pushes along the unstable mode (pushed_along_border_mode: the largest border coordinate moved by 1 % and
/// 5 % of L0 or 0.01 and 0.05 rad, both ways): small enough to stay in the valley the mode descends into,
/// as the fold snap's (fold_snap.cpp kDampedPushes).
constexpr double kModePushes[] = {0.01, -0.01, 0.05, -0.05};

/// Where Newton from the minimiser lands on an unstable equilibrium (`landed`) and the damped motion from
/// the minimiser stays on it: the damped motion from `landed` pushed along its border's unstable mode. A
/// planar robot's minimiser lies in its plane where the Ritz form's in-plane equilibrium is still stable
/// and the collocation's, just past a pitchfork, is not: the stable equilibria lie off the plane, which
/// no motion from an in-plane start reaches by symmetry (planar_post at 0.455351 0.171345 0.180950 m).
bool descended_along_unstable_mode(FkData& data, const Minimum& minimum, const VecX& inputs,
                                   const VecX& landed, VecX& xs, EnergyFallback& out, std::string& note,
                                   SolveSummary& summary, Stability& v) {
  const RobotAssembly& assembly = *data.model->assembly;
  const VecX mode = border_unstable_mode(assembly, landed);
  if (mode.size() == 0) return false;
  for (double amplitude : kModePushes) {
    const VecX start = pushed_along_border_mode(assembly, landed, mode, amplitude);
    if (damped_motion(data, minimum, inputs, start, 0.0,
                      "damped motion along the unstable mode (" + format("%+.2f", amplitude) + ")", xs, out,
                      note, summary, v))
      return true;
  }
  return false;
}

/// One start: Ipopt from it, then Newton, then the damped motion; true when either reached a stable
/// equilibrium (in xs). Else `refused` is the equilibrium Newton reached from the minimiser (empty if none).
bool from_start(FkData& data, const VecX& inputs, const EnergyStart& start, VecX& xs, EnergyFallback& out,
                std::string& note, VecX& refused) {
  refused.resize(0);
  const RobotAssembly& assembly = *data.model->assembly;
  const Clock::time_point t0 = Clock::now();
  xs = *start.x;
  assembly.set_inputs(xs, inputs);
  const EnergyModel energy(assembly, xs);
  // Started off symmetry planes by 1e-3 (L0 for positions): an in-plane state of a planar robot is often
  // a saddle of the full energy (passive_hinge's default equilibrium has 1 unstable mode).
  VecX e = energy.perturbed(energy.from_state(xs), 1e-3);
  SolveSummary minimised;
  VecX row_multipliers;  // the contact forces of the minimiser (EnergyModel::to_state)
  {
    const std::lock_guard<std::mutex> lock(ipopt_mutex());
    IpoptSolver ipopt(energy.problem(), energy_ipopt_options());
    minimised = ipopt.solve(e);
    row_multipliers = ipopt.constraint_multipliers();
  }
  out.iterations += minimised.iterations;
  out.jacobians += minimised.jacobian_evaluations;
  note = std::string("from ") + start.name + ": Ipopt " + to_string(minimised.status) + " in " +
         std::to_string(minimised.iterations) + " iterations, energy " + format("%.6g", energy.energy(e)) +
         " J";
  if (!e.allFinite()) return false;
  energy.to_state(e, xs, row_multipliers);
  const VecX minimiser = xs;
  SolveSummary summary;
  Stability verdict;
  const Minimum minimum{energy, energy.energy(e)};
  if (!newton_to_stable(data, minimum, inputs, xs, out, note, summary, verdict)) {
    const bool landed = summary.converged() && xs.allFinite();
    const VecX newton_x = xs;
    if (landed) refused = newton_x;
    if (!damped_to_stable(data, minimum, inputs, minimiser, xs, out, note, summary, verdict) &&
        !(landed &&
          descended_along_unstable_mode(data, minimum, inputs, newton_x, xs, out, note, summary, verdict)))
      return false;
  }
  note += (verdict.verdict == StabilityVerdict::Stable ? "; stable, margin " + format("%.3g", verdict.margin)
                                                       : "; verdict unknown (" + verdict.reason + ")") +
          ", " + format("%.2f", seconds_since(t0)) + " s";
  out.summary = summary;
  out.verdict = verdict;
  return true;
}

}  // namespace

EnergyFallback minimise_energy_then_newton(FkData& data, const VecX& inputs,
                                           const std::vector<EnergyStart>& starts) {
  EnergyFallback out;
  const std::string refusal = energy_model_refusal(data.model->assembly->model());
  if (!refusal.empty()) {
    out.message = "skipped: " + refusal;
    return out;
  }
  const int n = data.model->assembly->problem().num_variables();
  std::vector<VecX> refused;  // the equilibria Newton reached from the starts' minimisers, refused
  const auto from = [&](const EnergyStart& start) {
    VecX xs, landed;
    std::string note;
    const bool stable = from_start(data, inputs, start, xs, out, note, landed);
    out.message += (out.message.empty() ? "" : "; ") + note;
    if (landed.size() == n) refused.push_back(landed);
    if (!stable) return false;
    out.converged = true;
    out.x = xs;
    return true;
  };
  for (const EnergyStart& start : starts)
    if (start.x && start.x->size() == n && start.x->allFinite() && from(start)) return out;
  // A minimum with a small basin (a rod jammed on a roller, stretched by kilonewtons: planar_rollers at
  // 0.272806 0.186439 0.173524 m) polished into an equilibrium that is refused: minimised again from that
  // equilibrium moved off it by from_start's 1e-3, which leaves such a basin.
  const std::vector<VecX> first_round = std::move(refused);
  for (const VecX& x : first_round)
    if (from({&x, "an equilibrium refused above"})) return out;
  if (out.message.empty()) out.message = "no finite start state";
  return out;
}

}  // namespace pcr::kinematics
