#pragma once
// Private to pcr_robots: reads the <pcr_obstacle> elements of a model and the <contact> child of each
// <pcr_rod> (docs/model_format.md, docs/contact.md), with messages naming the file, line, element,
// attribute and value.
#include <string>
#include <vector>

#include "pcr/robots/robot_model.hpp"
#include "urdf_part_reader.hpp"

class TiXmlElement;

namespace pcr {

/// The obstacles of <robot> in file order; fills each rod's obstacles and contact radius from its
/// <contact obstacles="names" radius="r"> child (rods: the pcr_rod elements read so far, by name).
std::vector<ObstacleElement> read_obstacles(const TiXmlElement& robot, const std::string& source,
                                            const UrdfTree& tree, std::vector<RodElement>& rods);

}  // namespace pcr
