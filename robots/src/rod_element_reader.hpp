#pragma once
// Private to pcr_robots: reads one <pcr_rod> element (docs/model_format.md) into a RodElement, with
// messages naming the file, line, rod, child element and attribute.
#include <string>

#include "pcr/robots/robot_model.hpp"
#include "urdf_part_reader.hpp"

class TiXmlElement;

namespace pcr {

RodElement read_rod(const TiXmlElement& element, const std::string& source, const UrdfTree& tree);

}  // namespace pcr
