// KinematicsOptions from Python keyword arguments (the names of the pcr tool's options, docs/cli.md).
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <string>

#include "bindings.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/kinematics_option_names.hpp"

namespace py = pybind11;

namespace pcr::python {
namespace {

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
    else if (!kinematics_option_words(key).empty())  // solver, formulation, mixed_points, objective
      set_kinematics_option(o, key, py::cast<std::string>(v));
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
