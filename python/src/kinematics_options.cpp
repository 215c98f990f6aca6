// KinematicsOptions from Python keyword arguments (the names of the pcr tool's options, docs/cli.md).
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <string>

#include "bindings.hpp"
#include "pcr/core/error.hpp"

namespace py = pybind11;

namespace pcr::python {
namespace {

std::string text_option(const std::string& key, const py::handle& value,
                        const std::vector<std::string>& allowed) {
  const std::string text = py::cast<std::string>(value);
  for (const std::string& a : allowed)
    if (text == a) return text;
  std::string list;
  for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
  throw InputError("option " + key + "='" + text + "': expected one of " + list);
}

double positive_number(const std::string& key, const py::handle& value) {
  const double x = py::cast<double>(value);
  if (!(x > 0.0) || !std::isfinite(x))
    throw InputError("option " + key + "=" + std::to_string(x) + ": must be positive");
  return x;
}

int positive_count(const std::string& key, const py::handle& value) {
  const int n = py::cast<int>(value);
  if (n < 1) throw InputError("option " + key + "=" + std::to_string(n) + ": must be at least 1");
  return n;
}

// formulation: "auto" keeps the choice by slenderness (mixed rods solved condensed); the others are
// exactly that formulation for every rod without a model hint (as the tool's --formulation).
void set_formulation(KinematicsOptions& o, const std::string& f) {
  if (f == "auto") return;
  o.assembly.discretization.formulation = f == "primal"  ? RodFormulation::Primal
                                          : f == "mixed" ? RodFormulation::Mixed
                                                         : RodFormulation::Condensed;
  o.assembly.formulation_by_slenderness = false;
  o.assembly.condense_mixed_rods = false;
}

void set_objective(KinematicsOptions& o, const std::string& objective) {
  o.ik.objective = objective == "effort"   ? IkObjective::ActuationEffort
                   : objective == "energy" ? IkObjective::ElasticEnergy
                                           : IkObjective::InputDistance;
}

}  // namespace

KinematicsOptions kinematics_options(const py::kwargs& kwargs) {
  KinematicsOptions o;
  for (const auto& item : kwargs) {
    const std::string key = py::cast<std::string>(item.first);
    const py::handle v = item.second;
    if (key == "tolerance")
      o.tolerance = positive_number(key, v);
    else if (key == "max_iterations")
      o.max_iterations = positive_count(key, v);
    else if (key == "centerline_points")
      o.centerline_points = positive_count(key, v);
    else if (key == "degree")
      o.assembly.discretization.degree = positive_count(key, v);
    else if (key == "elements")
      o.assembly.discretization.elements = positive_count(key, v);
    else if (key == "formulation")
      set_formulation(o, text_option(key, v, {"auto", "mixed", "condensed", "primal"}));
    else if (key == "mixed_points")
      o.assembly.discretization.mixed_points = text_option(key, v, {"midpoints", "greville"}) == "greville"
                                                   ? MixedPoints::Greville
                                                   : MixedPoints::Midpoints;
    else if (key == "solver")
      o.solver = text_option(key, v, {"newton", "ipopt"}) == "ipopt" ? SolverKind::Ipopt : SolverKind::Newton;
    else if (key == "objective")
      set_objective(o, text_option(key, v, {"distance", "effort", "energy"}));
    else if (key == "max_rod_stress")
      o.ik.max_rod_stress = positive_number(key, v);
    else if (key == "check_stability")
      o.check_stability = py::cast<bool>(v);
    else if (key == "stability_verdict")
      o.stability_verdict = py::cast<bool>(v);
    else
      throw InputError(
          "unknown option '" + key +
          "': expected tolerance, max_iterations, centerline_points, degree, elements, formulation, "
          "mixed_points, solver, objective, max_rod_stress, check_stability or stability_verdict");
  }
  return o;
}

}  // namespace pcr::python
