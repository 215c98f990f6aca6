#pragma once
// Reads a robot from one URDF file: the text must be UTF-8 XML; the link tree and the pcr extension
// elements (pcr_rod, pcr_gravity, pcr_load, pcr_joint) are read through TinyXML, and urdfdom must
// accept the URDF as well. The format is documented in
// docs/model_format.md. Everything is validated before the model is returned; any problem throws
// pcr::InputError naming the file, the line, the element, the attribute and its value.
#include <string>

#include "pcr/robots/robot_model.hpp"

namespace pcr {

/// Loads a model file.
RobotModel load_robot_model(const std::string& path);
/// Parses a model from its XML text; source_name stands for the file name in error messages.
RobotModel parse_robot_model(const std::string& xml, const std::string& source_name = "<string>");

}  // namespace pcr
