#include "urdf_part_reader.hpp"

#include <tinyxml.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <memory>

#include "pcr/core/error.hpp"
#include "xml_element_reader.hpp"

namespace pcr {
namespace {

JointType parse_joint_type(XmlElementReader& reader) {
  const std::string type = reader.text("type");
  if (type == "fixed") return JointType::Fixed;
  if (type == "prismatic") return JointType::Prismatic;
  if (type == "revolute") return JointType::Revolute;
  if (type == "continuous") return JointType::Continuous;
  if (type == "floating") return JointType::Floating;
  reader.fail("type", type, "is not supported (fixed, prismatic, revolute, continuous or floating)");
}

// The <origin xyz rpy> child of a joint or an <inertial> (URDF: optional, identity when omitted).
Pose read_origin(const XmlElementReader& parent, const TiXmlElement& element, const std::string& source) {
  const TiXmlElement* origin = single_child(parent, element, "origin", false);
  if (origin == nullptr) return Pose::identity();
  XmlElementReader reader(*origin, source, parent.label() + " <origin>");
  return Pose::from_xyz_rpy(reader.vec3_or("xyz", Vec3::Zero()), reader.vec3_or("rpy", Vec3::Zero()));
}

// urdfdom rejects what it cannot parse only through its log; its verdict comes after pcr's own checks,
// so that a file ROS tools reject is not accepted here either.
void require_urdfdom_accepts(const std::string& xml, const std::string& source) {
  std::shared_ptr<urdf::ModelInterface> urdf;
  try {
    urdf = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    throw_input_error(source, ": urdfdom rejected the URDF: ", e.what());
  }
  if (!urdf) throw_input_error(source, ": urdfdom rejected the URDF (its log above gives the reason)");
}

// Joints in file order, every value read by pcr: urdfdom defaults missing limits to 0 silently and
// reports malformed numbers only in its log.
std::vector<Joint> read_joints(const UrdfTree& tree, const std::string& source) {
  std::vector<Joint> joints;
  for (std::size_t j = 0; j < tree.joints.size(); ++j) {
    const std::string label = quoted("joint", tree.joint_names[j]);
    XmlElementReader named(*tree.joints[j], source, label);
    Joint joint;
    joint.name = tree.joint_names[j];
    joint.type = tree.joint_type[j];
    joint.parent_link = tree.joint_parent[j];
    joint.child_link = tree.joint_child[j];
    joint.origin = read_origin(named, *tree.joints[j], source);
    const bool moves = joint.type == JointType::Prismatic || joint.type == JointType::Revolute ||
                       joint.type == JointType::Continuous;
    if (moves) {
      // URDF: the axis defaults to x; urdfdom keeps it as written (pcr normalises it where it is used).
      joint.axis = Vec3::UnitX();
      if (const TiXmlElement* axis = single_child(named, *tree.joints[j], "axis", false)) {
        XmlElementReader reader(*axis, source, label + " <axis>");
        joint.axis = reader.vec3("xyz");
        if (!(joint.axis.norm() > 1e-12)) reader.fail("xyz", reader.text("xyz"), "is zero");
      }
    }
    if (joint.type == JointType::Prismatic || joint.type == JointType::Revolute) {
      const TiXmlElement* limit = single_child(named, *tree.joints[j], "limit", true);
      XmlElementReader reader(*limit, source, label + " <limit>");
      joint.lower = reader.number("lower");
      joint.upper = reader.number("upper");
      if (joint.lower > joint.upper) {
        reader.fail("lower", reader.text("lower"), "is greater than upper = " + reader.text("upper"));
      }
      // 0 if allowed, else the nearest limit; pcr_joint overrides it.
      joint.default_value = std::min(std::max(0.0, joint.lower), joint.upper);
    }
    joints.push_back(joint);
  }
  return joints;
}

// A link's <inertial> (URDF: <origin> optional, <mass value> and the six <inertia> entries required),
// read by pcr: urdfdom logs a malformed one and drops it, which would lose the mass silently. pcr uses
// the mass (>= 0) and the centre of mass; the inertia tensor (statics) only has to be finite.
struct LinkInertial {
  double mass = 0.0;
  Vec3 center_of_mass = Vec3::Zero();  ///< link frame
};
LinkInertial read_inertial(const TiXmlElement& link, const std::string& source, const std::string& label) {
  XmlElementReader named(link, source, label);
  const TiXmlElement* inertial = single_child(named, link, "inertial", false);
  if (inertial == nullptr) return LinkInertial{};
  XmlElementReader in(*inertial, source, label + " <inertial>");
  LinkInertial result;
  result.center_of_mass = read_origin(in, *inertial, source).position;
  XmlElementReader mass(*single_child(in, *inertial, "mass", true), source, in.label() + " <mass>");
  result.mass = mass.non_negative("value");
  XmlElementReader inertia(*single_child(in, *inertial, "inertia", true), source, in.label() + " <inertia>");
  for (const char* entry : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) inertia.number(entry);
  return result;
}

// The <link> elements: unique, non-empty names, at least one.
void read_links(const TiXmlElement& robot, const std::string& source, UrdfTree& tree) {
  for (const TiXmlElement* e = robot.FirstChildElement("link"); e; e = e->NextSiblingElement("link")) {
    XmlElementReader reader(*e, source, "link");
    const std::string name = reader.text("name");
    if (name.empty()) reader.fail("name", name, "is empty");
    if (!tree.link_index.emplace(name, static_cast<int>(tree.links.size())).second) {
      reader.fail("name", name, "is used by two links");
    }
    tree.links.push_back(e);
    tree.link_names.push_back(name);
  }
  if (tree.links.empty()) throw_input_error(source, ": <robot> has no <link>");
}

// The <joint> elements: unique names, a type, a parent and a child link that differ, at most one parent
// joint per link.
void read_joints(const TiXmlElement& robot, const std::string& source, UrdfTree& tree) {
  tree.parent_joint.assign(tree.links.size(), -1);
  std::map<std::string, int> joint_index;
  for (const TiXmlElement* e = robot.FirstChildElement("joint"); e; e = e->NextSiblingElement("joint")) {
    XmlElementReader reader(*e, source, "joint");
    const std::string name = reader.text("name");
    XmlElementReader named(*e, source, quoted("joint", name));
    if (!joint_index.emplace(name, static_cast<int>(tree.joints.size())).second) {
      named.fail("name", name, "is used by two joints");
    }
    const JointType type = parse_joint_type(named);
    if (e->FirstChildElement("mimic")) named.fail("<mimic> joints are not supported");
    int ends[2] = {-1, -1};
    const char* tags[2] = {"parent", "child"};
    for (int k = 0; k < 2; ++k) {
      const TiXmlElement* t = single_child(named, *e, tags[k], true);
      XmlElementReader tag(*t, source, quoted("joint", name) + " <" + tags[k] + ">");
      const std::string link = tag.text("link");
      const auto it = tree.link_index.find(link);
      if (it == tree.link_index.end()) tag.fail("link", link, "is not a link of the robot");
      ends[k] = it->second;
    }
    if (ends[0] == ends[1])
      named.fail("parent and child are the same link '" + tree.link_names[ends[0]] + "'");
    const int j = static_cast<int>(tree.joints.size());
    if (tree.parent_joint[ends[1]] >= 0) {
      named.fail("link '" + tree.link_names[ends[1]] + "' is already the child of joint '" +
                 tree.joint_names[tree.parent_joint[ends[1]]] + "' (a URDF is a tree)");
    }
    tree.parent_joint[ends[1]] = j;
    tree.joints.push_back(e);
    tree.joint_names.push_back(name);
    tree.joint_parent.push_back(ends[0]);
    tree.joint_child.push_back(ends[1]);
    tree.joint_type.push_back(type);
  }
}

// One root link, which every link reaches through its parent joints (no cycle).
void check_single_root(const std::string& source, const UrdfTree& tree) {
  int root = -1;
  for (std::size_t i = 0; i < tree.links.size(); ++i) {
    if (tree.parent_joint[i] >= 0) continue;
    if (root >= 0) {
      throw_input_error(source, ": the URDF has several root links, '", tree.link_names[root], "' and '",
                        tree.link_names[i], "' (connect them with a joint)");
    }
    root = static_cast<int>(i);
  }
  if (root < 0) throw_input_error(source, ": the URDF has no root link: its joints form a cycle");
  for (std::size_t i = 0; i < tree.links.size(); ++i) {
    int link = static_cast<int>(i);
    for (std::size_t steps = 0; tree.parent_joint[link] >= 0; ++steps) {
      if (steps > tree.links.size()) {
        throw_input_error(source, ": link '", tree.link_names[i], "' is on a cycle of joints (",
                          quoted("joint", tree.joint_names[tree.parent_joint[link]]),
                          ") not connected to the root '", tree.link_names[root], "'");
      }
      link = tree.joint_parent[tree.parent_joint[link]];
    }
  }
}

}  // namespace

UrdfTree read_tree(const TiXmlElement& robot, const std::string& source) {
  UrdfTree tree;
  read_links(robot, source, tree);
  read_joints(robot, source, tree);
  check_single_root(source, tree);
  return tree;
}

// Platform carrying a link (nearest ancestor whose parent joint is floating, itself included), or -1.
int carrying_floating_link(const UrdfTree& tree, int link) {
  for (; tree.parent_joint[link] >= 0; link = tree.joint_parent[tree.parent_joint[link]]) {
    if (tree.joint_type[tree.parent_joint[link]] == JointType::Floating) return link;
  }
  return -1;
}

UrdfPart read_urdf_part(const std::string& xml, const UrdfTree& tree, const std::string& source) {
  UrdfPart part;
  std::vector<Link>& links = part.links;
  links.resize(tree.links.size());
  for (std::size_t i = 0; i < links.size(); ++i) links[i].name = tree.link_names[i];
  part.joints = read_joints(tree, source);

  // Platforms (children of floating joints, file order) and their mass; mass elsewhere on a platform's
  // subtree would be ignored silently, so it is rejected. The other links keep theirs: it loads the
  // passive joints that move them (RobotModel), and is unused on links fixed to the world or moved
  // only by actuated joints (the base or the actuators carry it). Every <inertial> is checked.
  for (std::size_t i = 0; i < links.size(); ++i) {
    const std::string label = quoted("link", links[i].name);
    const LinkInertial inertial = read_inertial(*tree.links[i], source, label);
    const int carrier = carrying_floating_link(tree, static_cast<int>(i));
    if (carrier == static_cast<int>(i)) {
      Platform platform;
      platform.link = static_cast<int>(i);
      platform.mass = inertial.mass;
      platform.center_of_mass = inertial.center_of_mass;
      part.platforms.push_back(platform);
    } else if (carrier >= 0 && inertial.mass != 0.0) {
      throw_input_error(source, ":", tree.links[i]->Row(), ": ", label,
                        " <inertial> <mass>: attribute 'value' = ", inertial.mass,
                        ": only the platform link '", tree.link_names[carrier],
                        "' may carry mass (move it into the platform's <inertial>)");
    } else if (carrier < 0) {
      links[i].mass = inertial.mass;
      links[i].center_of_mass = inertial.center_of_mass;
    }
  }
  require_urdfdom_accepts(xml, source);
  return part;
}

}  // namespace pcr
