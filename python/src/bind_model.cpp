// Python bindings of the model side: RobotModel (read-only), Pose, LinkTarget.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>

#include "bindings.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace py = pybind11;

namespace pcr::python {
namespace {

// pybind11 holders cannot be shared_ptr<const T>: the Python object holds a shared_ptr<RobotModel>, and
// only read-only members are bound (the model stays immutable); C++ takes it as shared_ptr<const ...>.
using ModelPtr = std::shared_ptr<RobotModel>;

std::vector<std::string> input_names(const RobotModel& model) {
  std::vector<std::string> names;
  for (const ActuationInput& input : model.inputs()) names.push_back(input.name);
  return names;
}

VecX input_bound(const RobotModel& model, bool upper) {
  VecX b(static_cast<int>(model.inputs().size()));
  for (int i = 0; i < b.size(); ++i) b[i] = upper ? model.inputs()[i].upper : model.inputs()[i].lower;
  return b;
}

std::vector<std::string> passive_joint_names(const RobotModel& model) {
  std::vector<std::string> names;
  for (int j : model.passive_joints()) names.push_back(model.joints()[j].name);
  return names;
}

template <class Items>
std::vector<std::string> names_of(const Items& items) {
  std::vector<std::string> names;
  for (const auto& item : items) names.push_back(item.name);
  return names;
}

// "pose" / "position" / "orientation" -> LinkTarget::Mode.
LinkTarget::Mode target_mode(const std::string& mode) {
  if (mode == "pose") return LinkTarget::Mode::Pose;
  if (mode == "position") return LinkTarget::Mode::Position;
  if (mode == "orientation") return LinkTarget::Mode::Orientation;
  throw InputError("LinkTarget mode '" + mode + "': expected 'pose', 'position' or 'orientation'");
}

const char* mode_name(LinkTarget::Mode mode) {
  switch (mode) {
    case LinkTarget::Mode::Position: return "position";
    case LinkTarget::Mode::Orientation: return "orientation";
    default: return "pose";
  }
}

// Component names x, y, z (position, world frame), rx, ry, rz (rotation about the target frame's axes).
std::array<bool, 6> target_components(const std::vector<std::string>& names) {
  static const char* all[6] = {"x", "y", "z", "rx", "ry", "rz"};
  std::array<bool, 6> on{{false, false, false, false, false, false}};
  for (const std::string& name : names) {
    int k = 0;
    while (k < 6 && name != all[k]) ++k;
    if (k == 6) throw InputError("LinkTarget component '" + name + "': expected x, y, z, rx, ry or rz");
    on[static_cast<size_t>(k)] = true;
  }
  return on;
}

void bind_pose(py::module_& m) {
  py::class_<Pose>(m, "Pose", "A frame's position [m] and unit quaternion [w, x, y, z] in another frame.")
      .def(py::init([](const Vec3& position, const Quat& orientation) {
             if (!position.allFinite() || !orientation.allFinite() || orientation.norm() == 0.0)
               throw InputError("Pose: position and orientation must be finite, the quaternion nonzero");
             return Pose{position, orientation.normalized()};
           }),
           py::arg("position") = Vec3::Zero(), py::arg("orientation") = Quat(1, 0, 0, 0))
      .def_static("from_xyz_rpy", &Pose::from_xyz_rpy, py::arg("xyz"), py::arg("rpy"),
                  "URDF origin: R = Rz(yaw) Ry(pitch) Rx(roll), rpy = (roll, pitch, yaw) [rad].")
      .def_readwrite("position", &Pose::position)
      .def_readwrite("orientation", &Pose::orientation, "unit quaternion [w, x, y, z]")
      .def("rotation", &Pose::rotation, "3x3 rotation matrix")
      .def("rpy", &Pose::rpy, "URDF roll, pitch, yaw [rad]")
      .def("__mul__", &Pose::operator*)
      .def("inverse", &Pose::inverse)
      .def("__repr__", [](const Pose& p) {
        return "Pose(position=[" + std::to_string(p.position.x()) + ", " + std::to_string(p.position.y()) +
               ", " + std::to_string(p.position.z()) + "], orientation=[" + std::to_string(p.orientation[0]) +
               ", " + std::to_string(p.orientation[1]) + ", " + std::to_string(p.orientation[2]) + ", " +
               std::to_string(p.orientation[3]) + "])";
      });
}

void bind_link_target(py::module_& m) {
  py::class_<LinkTarget>(
      m, "LinkTarget",
      "What IK aims at on a link carried by a platform: mode 'pose', 'position' or "
      "'orientation'; components a subset of x, y, z, rx, ry, rz (default: all of the mode).")
      .def(py::init([](const std::string& link, const std::string& mode, py::object components) {
             LinkTarget t{link, target_mode(mode), Pose{}, {{true, true, true, true, true, true}}};
             if (!components.is_none())
               t.components = target_components(components.cast<std::vector<std::string>>());
             return t;
           }),
           py::arg("link"), py::arg("mode") = "pose", py::arg("components") = py::none())
      .def_readonly("link", &LinkTarget::link)
      .def_property_readonly("mode", [](const LinkTarget& t) { return mode_name(t.mode); })
      .def_property_readonly("components", [](const LinkTarget& t) {
        static const char* all[6] = {"x", "y", "z", "rx", "ry", "rz"};
        std::vector<std::string> on;
        for (size_t k = 0; k < 6; ++k)
          if (t.components[k]) on.push_back(all[k]);
        return on;
      });
}

void bind_robot_model(py::module_& m) {
  py::class_<RobotModel, ModelPtr>(m, "RobotModel",
                                   "An immutable, validated robot (load_model / parse_model).")
      .def_property_readonly("name", &RobotModel::name)
      .def_property_readonly("input_names", &input_names, "actuated rod lengths, then moving joints")
      .def_property_readonly("default_inputs", &RobotModel::default_input_values, "[m or rad]")
      .def_property_readonly("input_lower", [](const RobotModel& r) { return input_bound(r, false); })
      .def_property_readonly("input_upper", [](const RobotModel& r) { return input_bound(r, true); })
      .def_property_readonly("platform_names", [](const RobotModel& r) { return names_of(r.platforms()); })
      .def_property_readonly("rod_names", [](const RobotModel& r) { return names_of(r.rods()); })
      .def_property_readonly("link_names", [](const RobotModel& r) { return names_of(r.links()); })
      .def_property_readonly("passive_joint_names", &passive_joint_names)
      .def_property_readonly("gravity", &RobotModel::gravity, "[m/s^2], world frame")
      .def("input_index", &RobotModel::input_index, py::arg("name"))
      .def("platform_index", &RobotModel::platform_index, py::arg("name"))
      .def("__repr__", [](const RobotModel& r) {
        return "<pcr.RobotModel '" + r.name() + "': " + std::to_string(r.inputs().size()) + " inputs, " +
               std::to_string(r.platforms().size()) + " platforms, " + std::to_string(r.rods().size()) +
               " rods>";
      });
  m.def(
      "load_model",
      [](const std::string& path) { return std::make_shared<RobotModel>(load_robot_model(path)); },
      py::arg("path"),
      "Loads and validates a robot file (URDF with pcr_ elements); InputError names file and line.");
  m.def(
      "parse_model",
      [](const std::string& xml, const std::string& source) {
        return std::make_shared<RobotModel>(parse_robot_model(xml, source));
      },
      py::arg("xml"), py::arg("source") = "<string>", "The same from text; `source` names it in messages.");
}

}  // namespace

void bind_model(py::module_& m) {
  bind_pose(m);
  bind_link_target(m);
  bind_robot_model(m);
}

}  // namespace pcr::python
