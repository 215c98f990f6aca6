#include "urdf_part_reader.hpp"

#include <tinyxml.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>

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

Pose to_pose(const urdf::Pose& p) {
  const urdf::Rotation& r = p.rotation;
  return Pose{Vec3(p.position.x, p.position.y, p.position.z), Quat(r.w, r.x, r.y, r.z)};
}

std::shared_ptr<urdf::ModelInterface> parse_with_urdfdom(const std::string& xml, const std::string& source) {
  std::shared_ptr<urdf::ModelInterface> urdf;
  try {
    urdf = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    throw_input_error(source, ": urdfdom rejected the URDF: ", e.what());
  }
  if (!urdf) throw_input_error(source, ": urdfdom rejected the URDF (its log above gives the reason)");
  return urdf;
}

// Joints in file order, with limits read by pcr (urdfdom defaults missing limits to 0 silently).
std::vector<Joint> read_joints(const UrdfTree& tree, const urdf::ModelInterface& urdf,
                               const std::string& source) {
  std::vector<Joint> joints;
  for (std::size_t j = 0; j < tree.joints.size(); ++j) {
    const std::string label = quoted("joint", tree.joint_names[j]);
    const urdf::JointConstSharedPtr u = urdf.getJoint(tree.joint_names[j]);
    if (!u) throw_input_error(source, ": ", label, ": not found by urdfdom");
    Joint joint;
    joint.name = tree.joint_names[j];
    joint.type = tree.joint_type[j];
    joint.parent_link = tree.joint_parent[j];
    joint.child_link = tree.joint_child[j];
    joint.origin = to_pose(u->parent_to_joint_origin_transform);
    joint.axis = Vec3(u->axis.x, u->axis.y, u->axis.z);
    if (joint.type == JointType::Prismatic || joint.type == JointType::Revolute) {
      XmlElementReader named(*tree.joints[j], source, label);
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
    if ((joint.type == JointType::Prismatic || joint.type == JointType::Revolute ||
         joint.type == JointType::Continuous) &&
        !(joint.axis.allFinite() && joint.axis.norm() > 1e-12)) {
      XmlElementReader named(*tree.joints[j], source, label);
      named.fail("<axis> is zero");
    }
    joints.push_back(joint);
  }
  return joints;
}

}  // namespace

UrdfTree read_tree(const TiXmlElement& robot, const std::string& source) {
  UrdfTree tree;
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
  // One root; every link reaches it.
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
  const std::shared_ptr<urdf::ModelInterface> parsed = parse_with_urdfdom(xml, source);
  const urdf::ModelInterface& urdf = *parsed;
  UrdfPart part;
  std::vector<Link>& links = part.links;
  links.resize(tree.links.size());
  for (std::size_t i = 0; i < links.size(); ++i) links[i].name = tree.link_names[i];
  part.joints = read_joints(tree, urdf, source);

  // Platforms (children of floating joints, file order) and their mass; mass elsewhere on a platform's
  // subtree would be ignored silently, so it is rejected.
  std::vector<Platform>& platforms = part.platforms;
  for (std::size_t i = 0; i < links.size(); ++i) {
    const urdf::LinkConstSharedPtr u = urdf.getLink(links[i].name);
    const double mass = u && u->inertial ? u->inertial->mass : 0.0;
    const int carrier = carrying_floating_link(tree, static_cast<int>(i));
    if (carrier == static_cast<int>(i)) {
      Platform platform;
      platform.link = static_cast<int>(i);
      platform.mass = mass;
      if (u && u->inertial) {
        const urdf::Vector3& c = u->inertial->origin.position;
        platform.center_of_mass = Vec3(c.x, c.y, c.z);
      }
      if (!(std::isfinite(mass) && mass >= 0.0)) {
        throw_input_error(source, ":", tree.links[i]->Row(), ": ", quoted("link", links[i].name),
                          " <inertial> <mass>: attribute 'value' = ", mass, " must be non-negative");
      }
      platforms.push_back(platform);
    } else if (carrier >= 0 && mass != 0.0) {
      throw_input_error(source, ":", tree.links[i]->Row(), ": ", quoted("link", links[i].name),
                        " <inertial> <mass>: attribute 'value' = ", mass, ": only the platform link '",
                        tree.link_names[carrier],
                        "' may carry mass (move it into the platform's <inertial>)");
    }
  }

  return part;
}

}  // namespace pcr
