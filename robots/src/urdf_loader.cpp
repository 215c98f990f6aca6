#include "pcr/robots/urdf_loader.hpp"

#include <tinyxml.h>

#include <fstream>
#include <map>
#include <sstream>

#include "model_text_check.hpp"
#include "obstacle_reader.hpp"
#include "pcr/core/error.hpp"
#include "rod_element_reader.hpp"
#include "urdf_part_reader.hpp"
#include "xml_element_reader.hpp"

namespace pcr {
namespace {

// Whether a passive joint lies on the link's path from the world (no floating joint between them).
bool moved_by_passive_joint(const UrdfTree& tree, const std::vector<Joint>& joints, int link) {
  for (; tree.parent_joint[link] >= 0; link = tree.joint_parent[tree.parent_joint[link]]) {
    const Joint& joint = joints[tree.parent_joint[link]];
    if (joint.type == JointType::Floating) return false;
    if (joint.passive) return true;
  }
  return false;
}

// Whether the value of joint j moves the link (j on its path from the world, no floating joint between).
bool joint_moves_link(const UrdfTree& tree, const std::vector<Joint>& joints, int j, int link) {
  for (; tree.parent_joint[link] >= 0; link = tree.joint_parent[tree.parent_joint[link]]) {
    if (tree.parent_joint[link] == j) return true;
    if (joints[tree.parent_joint[link]].type == JointType::Floating) return false;
  }
  return false;
}

// A passive joint needs something beyond it that determines its value: a rod end, a pcr_load, or a
// link mass under gravity on a link it moves. Fails at the joint's <pcr_joint> element.
void check_passive_joint_loaded(const TiXmlElement& e, const std::string& source, const UrdfTree& tree,
                                const std::vector<Joint>& joints, const std::vector<Link>& links,
                                const std::vector<RodElement>& rods, const std::vector<ExternalLoad>& loads,
                                const Vec3& gravity, int j) {
  bool loaded = false;
  for (const RodElement& rod : rods)
    for (int link : {rod.start.link, rod.end.link})
      loaded = loaded || (link >= 0 && joint_moves_link(tree, joints, j, link));
  for (const ExternalLoad& load : loads) loaded = loaded || joint_moves_link(tree, joints, j, load.link);
  for (int l = 0; l < static_cast<int>(links.size()); ++l)
    loaded = loaded || (links[l].mass > 0.0 && !gravity.isZero(0.0) && joint_moves_link(tree, joints, j, l));
  if (loaded) return;
  XmlElementReader reader(e, source, "pcr_joint");
  reader.fail("name", joints[j].name,
              "is a passive joint with nothing attached beyond it (no rod end, pcr_load, or link mass under "
              "gravity on link '" +
                  tree.link_names[joints[j].child_link] +
                  "' or the links it carries), so nothing determines its value");
}

// <pcr_joint name default passive stiffness rest>: the default (initial) value of a moving joint, and
// whether it is passive (an unknown of the assembly balanced by its spring, docs/model_format.md).
void read_pcr_joint(const TiXmlElement& e, const std::string& source, const UrdfTree& tree,
                    std::vector<Joint>& joints) {
  XmlElementReader reader(e, source, "pcr_joint");
  const std::string name = reader.text("name");
  int j = 0;
  while (j < static_cast<int>(joints.size()) && joints[j].name != name) ++j;
  if (j == static_cast<int>(joints.size())) reader.fail("name", name, "is not a joint of the robot");
  Joint& joint = joints[j];
  if (joint.type == JointType::Fixed || joint.type == JointType::Floating) {
    reader.fail("name", name, std::string("is a ") + to_string(joint.type) + " joint, which has no value");
  }
  joint.passive = reader.boolean_or("passive", false);
  if (joint.passive) {
    if (carrying_floating_link(tree, joint.child_link) >= 0) {
      reader.fail("passive", reader.text("passive"),
                  "is not supported below a platform: joint '" + name + "' is carried by platform '" +
                      tree.link_names[carrying_floating_link(tree, joint.child_link)] +
                      "' (passive joints go between the world and rod attachments)");
    }
    joint.stiffness = reader.has("stiffness") ? reader.non_negative("stiffness") : 0.0;
    joint.rest = reader.number_or("rest", 0.0);
  } else {
    for (const char* a : {"stiffness", "rest"})
      if (reader.has(a)) reader.fail(a, reader.text(a), "is only allowed with passive=\"true\"");
  }
  if (!joint.passive || reader.has("default")) {
    const double value = reader.number("default");
    if (joint.type != JointType::Continuous && (value < joint.lower || value > joint.upper)) {
      std::ostringstream bounds;
      bounds << "is outside the joint limits [" << joint.lower << ", " << joint.upper << "]";
      reader.fail("default", reader.text("default"), bounds.str());
    }
    joint.default_value = value;
  }
  reader.finish();
}

// <pcr_load link xyz force torque>: a constant wrench on a link (where the link must be movable is
// checked once the joints are known, check_loads_act_on_movable_links).
ExternalLoad read_pcr_load(const TiXmlElement& e, const std::string& source, const UrdfTree& tree) {
  XmlElementReader reader(e, source, "pcr_load");
  ExternalLoad load;
  const std::string link = reader.text("link");
  const auto it = tree.link_index.find(link);
  if (it == tree.link_index.end()) reader.fail("link", link, "is not a link of the robot");
  load.link = it->second;
  load.point = reader.vec3_or("xyz", Vec3::Zero());
  load.force = reader.vec3_or("force", Vec3::Zero());
  load.torque = reader.vec3_or("torque", Vec3::Zero());
  reader.finish();
  return load;
}

// The pcr extension elements of a model file, with the elements the later checks name in messages.
struct PcrElements {
  Vec3 gravity = Vec3::Zero();
  bool has_gravity = false;
  std::vector<RodElement> rods;
  std::map<std::string, int> rod_lines;  // line of each rod's element, by rod name
  std::vector<ExternalLoad> loads;
  std::vector<const TiXmlElement*> load_elements;   // per load
  std::vector<const TiXmlElement*> joint_elements;  // per pcr_joint
};

// Adds one <pcr_rod>; fails when its name is already taken by an earlier rod.
void add_pcr_rod(const TiXmlElement& e, const std::string& source, const UrdfTree& tree, PcrElements& pcr) {
  pcr.rods.push_back(read_rod(e, source, tree));
  const std::string& name = pcr.rods.back().name;
  if (!pcr.rod_lines.emplace(name, e.Row()).second) {
    XmlElementReader reader(e, source, quoted("pcr_rod", name));
    reader.fail("name", name,
                "is already used by the pcr_rod on line " + std::to_string(pcr.rod_lines[name]));
  }
}

// Reads the pcr_ children of <robot> in file order (pcr_joint values go into `joints`); an unknown
// pcr_ element is an error, other elements are the URDF part's.
PcrElements read_pcr_elements(const TiXmlElement& robot, const std::string& source, const UrdfTree& tree,
                              std::vector<Joint>& joints) {
  PcrElements pcr;
  for (const TiXmlElement* e = robot.FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->ValueStr();
    if (tag == "pcr_gravity") {
      XmlElementReader reader(*e, source, "pcr_gravity");
      if (pcr.has_gravity) reader.fail("given more than once");
      pcr.has_gravity = true;
      pcr.gravity = reader.vec3("xyz");
      reader.finish();
    } else if (tag == "pcr_rod") {
      add_pcr_rod(*e, source, tree, pcr);
    } else if (tag == "pcr_load") {
      pcr.loads.push_back(read_pcr_load(*e, source, tree));
      pcr.load_elements.push_back(e);
    } else if (tag == "pcr_joint") {
      read_pcr_joint(*e, source, tree, joints);
      pcr.joint_elements.push_back(e);
    } else if (tag.compare(0, 4, "pcr_") == 0 && tag != "pcr_obstacle") {
      XmlElementReader reader(*e, source, "<" + tag + ">");
      reader.fail("unknown pcr element (pcr_rod, pcr_gravity, pcr_load, pcr_joint or pcr_obstacle)");
    }
  }
  return pcr;
}

// A load acts on a link a platform carries or a passive joint moves (else on the fixed world).
void check_loads_act_on_movable_links(const PcrElements& pcr, const std::string& source, const UrdfTree& tree,
                                      const std::vector<Joint>& joints) {
  for (std::size_t i = 0; i < pcr.loads.size(); ++i) {
    const int link = pcr.loads[i].link;
    if (carrying_floating_link(tree, link) >= 0 || moved_by_passive_joint(tree, joints, link)) continue;
    XmlElementReader reader(*pcr.load_elements[i], source, "pcr_load");
    reader.fail("link", tree.link_names[link],
                "is not carried by a platform or moved by a passive joint (a load there acts on the fixed "
                "world)");
  }
}

// Every passive joint named by a <pcr_joint> has something beyond it that determines its value.
void check_passive_joints_loaded(const PcrElements& pcr, const std::string& source, const UrdfTree& tree,
                                 const std::vector<Joint>& joints, const std::vector<Link>& links) {
  for (const TiXmlElement* e : pcr.joint_elements) {
    const std::string name = e->Attribute("name") ? e->Attribute("name") : "";
    for (int j = 0; j < static_cast<int>(joints.size()); ++j)
      if (joints[j].name == name && joints[j].passive)
        check_passive_joint_loaded(*e, source, tree, joints, links, pcr.rods, pcr.loads, pcr.gravity, j);
  }
}

// Every platform carries the end of at least one rod (else nothing determines its pose).
void check_platforms_hold_rods(const std::vector<Platform>& platforms, const std::vector<RodElement>& rods,
                               const std::string& source, const UrdfTree& tree) {
  for (const Platform& platform : platforms) {
    bool has_rod = false;
    for (const RodElement& rod : rods) {
      for (int link : {rod.start.link, rod.end.link}) {
        has_rod = has_rod || (link >= 0 && carrying_floating_link(tree, link) == platform.link);
      }
    }
    if (!has_rod) {
      throw_input_error(source, ":", tree.links[platform.link]->Row(), ": ",
                        quoted("link", tree.link_names[platform.link]), " (platform of floating joint '",
                        tree.joint_names[tree.parent_joint[platform.link]],
                        "'): no pcr_rod is attached to it, so its pose is undetermined");
    }
  }
}

// The <robot> root of a model file's text (UTF-8 XML characters only, checked before any parser sees it).
const TiXmlElement& robot_element(TiXmlDocument& document, const std::string& xml,
                                  const std::string& source) {
  check_model_text(xml, source);
  document.Parse(xml.c_str());
  if (document.Error()) {
    throw_input_error(source, ":", document.ErrorRow(), ": XML error: ", document.ErrorDesc());
  }
  const TiXmlElement* robot = document.RootElement();
  if (robot == nullptr || robot->ValueStr() != "robot")
    throw_input_error(source, ": the root element is not <robot>");
  return *robot;
}

RobotModel parse_document(const std::string& xml, const std::string& source) {
  TiXmlDocument document;
  const TiXmlElement& robot = robot_element(document, xml, source);
  XmlElementReader robot_reader(robot, source, "robot");
  const std::string robot_name = robot_reader.text("name");

  const UrdfTree tree = read_tree(robot, source);
  UrdfPart urdf = read_urdf_part(xml, tree, source);
  PcrElements pcr = read_pcr_elements(robot, source, tree, urdf.joints);
  std::vector<ObstacleElement> obstacles = read_obstacles(robot, source, tree, pcr.rods);
  check_loads_act_on_movable_links(pcr, source, tree, urdf.joints);
  check_passive_joints_loaded(pcr, source, tree, urdf.joints, urdf.links);
  check_platforms_hold_rods(urdf.platforms, pcr.rods, source, tree);

  // Cross-element checks (well-posedness, platform hold) live in RobotModel; prefix the file name.
  try {
    return RobotModel(robot_name, std::move(urdf.links), std::move(urdf.joints), std::move(urdf.platforms),
                      std::move(pcr.rods), std::move(pcr.loads), pcr.gravity, std::move(obstacles));
  } catch (const InputError& e) {
    throw InputError(source + ": " + e.what());
  }
}

}  // namespace

RobotModel parse_robot_model(const std::string& xml, const std::string& source_name) {
  return parse_document(xml, source_name);
}

RobotModel load_robot_model(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw_input_error(path, ": cannot open the robot model file");
  std::ostringstream text;
  text << file.rdbuf();
  return parse_document(text.str(), path);
}

}  // namespace pcr
