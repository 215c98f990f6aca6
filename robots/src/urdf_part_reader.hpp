#pragma once
// Private to pcr_robots: the URDF part of a model file (links, joints, platforms). pcr reads every
// value it uses itself (tree, joint origins, axes and limits, inertials), with messages that name the
// file, line, element and value: urdfdom only logs its reasons, and drops a malformed <inertial>
// silently. urdfdom then parses the file too, so that what ROS tools reject is rejected here as well.
#include <map>
#include <string>
#include <vector>

#include "pcr/robots/robot_model.hpp"

class TiXmlElement;

namespace pcr {

// The link/joint tree as written in the file (file order), checked with element-level messages
// before urdfdom sees it (urdfdom only logs its reasons).
struct UrdfTree {
  std::map<std::string, int> link_index;
  std::vector<const TiXmlElement*> links, joints;
  std::vector<std::string> link_names, joint_names;
  std::vector<int> parent_joint;               // per link
  std::vector<int> joint_parent, joint_child;  // per joint
  std::vector<JointType> joint_type;
};

/// Links and joints of the <robot> element, in file order; checks names, parent/child links, one root,
/// no cycles and the supported joint types.
UrdfTree read_tree(const TiXmlElement& robot, const std::string& source);

// Platform carrying a link (nearest ancestor whose parent joint is floating, itself included), or -1.
int carrying_floating_link(const UrdfTree& tree, int link);

struct UrdfPart {
  std::vector<Link> links;
  std::vector<Joint> joints;        ///< limits and defaults filled
  std::vector<Platform> platforms;  ///< link, mass, center_of_mass
};
/// Reads joints and inertials of the tree, rejects mass on links carried by a platform, then requires
/// urdfdom to accept the file.
UrdfPart read_urdf_part(const std::string& xml, const UrdfTree& tree, const std::string& source);

}  // namespace pcr
