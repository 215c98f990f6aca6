#pragma once
// Private to pcr_robots: the URDF part of a model file (links, joints, platforms). The tree is checked
// with element-level messages before urdfdom parses the file (urdfdom only logs its reasons); urdfdom
// then supplies origins, axes and inertials.
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
/// Parses the file with urdfdom and converts the tree; rejects mass on links carried by a platform.
UrdfPart read_urdf_part(const std::string& xml, const UrdfTree& tree, const std::string& source);

}  // namespace pcr
