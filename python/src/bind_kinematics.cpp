// Python bindings of ForwardKinematics, InverseKinematics (with warm-started paths) and the workspace
// sampler. Solves release the GIL: kinematics objects of one model may solve in Python threads at once
// (Newton only; Ipopt 3.11 is not thread-safe, kinematics.hpp).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>

#include "bindings.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/workspace.hpp"

namespace py = pybind11;

namespace pcr::python {
namespace {

// pybind11 holders cannot be shared_ptr<const T>: the Python object holds a shared_ptr<RobotModel>, and
// only read-only members are bound (the model stays immutable); C++ takes it as shared_ptr<const ...>.
using ModelPtr = std::shared_ptr<RobotModel>;
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Inputs by name, the others at the model's defaults.
VecX named_inputs(const RobotModel& model, const std::map<std::string, double>& values) {
  VecX u = model.default_input_values();
  for (const auto& [name, value] : values) u[model.input_index(name)] = value;
  return u;
}

int platform_argument(const RobotModel& model, const py::object& platform) {
  if (py::isinstance<py::str>(platform)) return model.platform_index(py::cast<std::string>(platform));
  const int p = py::cast<int>(platform);
  if (p < 0 || p >= static_cast<int>(model.platforms().size()))
    throw InputError("platform index " + std::to_string(p) + " out of range [0, " +
                     std::to_string(model.platforms().size()) + ")");
  return p;
}

// FK along the rows of `inputs` (one row per point, model input order), warm-started.
std::vector<RobotSolution> fk_path(ForwardKinematics& fk, const RowMatrix& inputs) {
  std::vector<RobotSolution> out;
  for (int i = 0; i < inputs.rows(); ++i) out.push_back(fk.solve(inputs.row(i).transpose()));
  return out;
}

std::vector<RobotSolution> ik_path(InverseKinematics& ik, const std::vector<std::vector<Pose>>& targets) {
  std::vector<RobotSolution> out;
  for (const std::vector<Pose>& point : targets) out.push_back(ik.solve(point));
  return out;
}

void bind_forward(py::module_& m) {
  py::class_<ForwardKinematics>(m, "ForwardKinematics",
                                "Inputs -> platform poses, rods, wrenches. Keyword options: tolerance, "
                                "max_iterations, centerline_points, degree, elements, formulation, "
                                "mixed_points, solver, check_stability.")
      .def(py::init([](ModelPtr model, const py::kwargs& kwargs) {
             return ForwardKinematics(std::move(model), kinematics_options(kwargs));
           }),
           py::arg("model"))
      .def("solve", &ForwardKinematics::solve, py::arg("inputs"), py::call_guard<py::gil_scoped_release>(),
           "Solves for the inputs (array, model order), warm-started from the previous solve.")
      .def(
          "solve",
          [](ForwardKinematics& fk, const std::map<std::string, double>& values) {
            const VecX u = named_inputs(fk.assembly().model(), values);
            py::gil_scoped_release release;
            return fk.solve(u);
          },
          py::arg("inputs"), "The same with {name: value}; inputs not named keep the model's defaults.")
      .def("solve_path", &fk_path, py::arg("inputs"), py::call_guard<py::gil_scoped_release>(),
           "FK along the rows of an n x m array (one row per point), each warm-started from the last.")
      .def("input_jacobian", &ForwardKinematics::input_jacobian,
           "d(platform poses)/d(inputs) at the last solution: 6 rows per platform [dx, dtheta].")
      .def(
          "compliance",
          [](const ForwardKinematics& fk, const py::object& platform) {
            return fk.compliance(platform_argument(fk.assembly().model(), platform));
          },
          py::arg("platform") = 0, "d(pose)/d(wrench on the platform), 6 x 6, at the last solution.")
      .def_property_readonly("has_solution", &ForwardKinematics::has_solution);
}

void bind_inverse(py::module_& m) {
  py::class_<InverseKinematics>(m, "InverseKinematics",
                                "Targets -> inputs. Keyword options as ForwardKinematics, plus objective "
                                "('distance', 'effort', 'energy') and max_rod_stress [Pa].")
      .def(py::init([](ModelPtr model, const std::vector<LinkTarget>& targets, const py::kwargs& kwargs) {
             return InverseKinematics(std::move(model), targets, kinematics_options(kwargs));
           }),
           py::arg("model"), py::arg("targets"))
      .def(
          "solve",
          [](InverseKinematics& ik, const std::vector<Pose>& poses, const std::optional<VecX>& reference) {
            py::gil_scoped_release release;
            return ik.solve(poses, reference ? &*reference : nullptr);
          },
          py::arg("poses"), py::arg("reference") = py::none(),
          "Solves for one Pose per target; reference: inputs to stay close to (default: the last "
          "solution's).")
      .def("solve_path", &ik_path, py::arg("targets"), py::call_guard<py::gil_scoped_release>(),
           "IK along a list of points, each a list of one Pose per target, warm-started.")
      .def_property_readonly("square", &InverseKinematics::square);
}

void bind_workspace(py::module_& m) {
  py::class_<WorkspaceSample>(m, "WorkspaceSample")
      .def_readonly("index", &WorkspaceSample::index)
      .def_readonly("inputs", &WorkspaceSample::inputs)
      .def_readonly("platforms", &WorkspaceSample::platforms)
      .def_property_readonly("status", [](const WorkspaceSample& s) { return to_string(s.status); })
      .def_property_readonly("converged", &WorkspaceSample::converged)
      .def_readonly("iterations", &WorkspaceSample::iterations)
      .def_readonly("residual_max_abs", &WorkspaceSample::residual_max_abs)
      .def_readonly("wall_time_seconds", &WorkspaceSample::wall_time_seconds)
      .def_readonly("message", &WorkspaceSample::message)
      .def_readonly("stability", &WorkspaceSample::stability);
  py::class_<WorkspaceResult>(m, "WorkspaceResult")
      .def_readonly("samples", &WorkspaceResult::samples)
      .def_readonly("failures", &WorkspaceResult::failures)
      .def_readonly("seed", &WorkspaceResult::seed)
      .def_readonly("first_sample", &WorkspaceResult::first_sample)
      .def_readonly("threads", &WorkspaceResult::threads)
      .def_readonly("wall_time_seconds", &WorkspaceResult::wall_time_seconds);
  m.def(
      "sample_workspace",
      [](ModelPtr model, std::int64_t samples, std::uint64_t seed, std::int64_t first_sample, int threads,
         const py::kwargs& kwargs) {
        WorkspaceOptions o;
        o.samples = samples;
        o.seed = seed;
        o.first_sample = first_sample;
        o.threads = threads;
        o.kinematics = kinematics_options(kwargs);
        auto assembly = std::make_shared<const RobotAssembly>(model, o.kinematics.assembly);
        py::gil_scoped_release release;
        return sample_workspace(std::move(assembly), o);
      },
      py::arg("model"), py::arg("samples"), py::arg("seed") = 1, py::arg("first_sample") = 0,
      py::arg("threads") = 1,
      "FK of random inputs within the bounds (samples first_sample .. first_sample + samples - 1 of seed), "
      "each from a fresh state, in `threads` threads; a sample depends on (seed, index) only.");
}

}  // namespace

void bind_kinematics(py::module_& m) {
  bind_forward(m);
  bind_inverse(m);
  bind_workspace(m);
}

}  // namespace pcr::python
