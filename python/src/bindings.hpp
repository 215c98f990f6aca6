#pragma once
// The Python module pcr._pcr (pybind11): one function per part of the API, called by module.cpp.
// Conventions as in C++ (docs/api.md): SI units, world frame, quaternions [w, x, y, z]; vectors and
// matrices are numpy arrays (copies), bad input raises pcr.InputError (a ValueError) with the C++
// message.
#include <pybind11/pybind11.h>

#include "pcr/robots/kinematics.hpp"

namespace pcr::python {

/// RobotModel, load_model / parse_model, Pose, LinkTarget.
void bind_model(pybind11::module_& m);
/// SolveSummary, RodResult, Stability, RobotSolution.
void bind_results(pybind11::module_& m);
/// ForwardKinematics, InverseKinematics, their path helpers and the workspace sampler.
void bind_kinematics(pybind11::module_& m);

/// KinematicsOptions from the keyword arguments of a constructor (tolerance, max_iterations,
/// centerline_points, degree, elements, formulation, mixed_points, solver, objective, max_rod_stress,
/// check_stability, stability_verdict); an unknown keyword or value raises InputError naming it.
KinematicsOptions kinematics_options(const pybind11::kwargs& kwargs);

}  // namespace pcr::python
