#include "pcr/robots/urdf_loader.hpp"

#include <tinyxml.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "pcr/core/error.hpp"
#include "xml_element_reader.hpp"

namespace pcr {
namespace {

std::string quoted(const std::string& kind, const std::string& name) {
  return kind + " '" + name + "'";
}

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

JointType parse_joint_type(XmlElementReader& reader) {
  const std::string type = reader.text("type");
  if (type == "fixed") return JointType::Fixed;
  if (type == "prismatic") return JointType::Prismatic;
  if (type == "revolute") return JointType::Revolute;
  if (type == "continuous") return JointType::Continuous;
  if (type == "floating") return JointType::Floating;
  reader.fail("type", type, "is not supported (fixed, prismatic, revolute, continuous or floating)");
}

const TiXmlElement* single_child(const XmlElementReader& reader, const TiXmlElement& element,
                                 const char* name, bool required) {
  const TiXmlElement* child = element.FirstChildElement(name);
  if (child == nullptr && required) reader.fail(std::string("missing element <") + name + ">");
  if (child != nullptr && child->NextSiblingElement(name) != nullptr) {
    reader.fail(std::string("element <") + name + "> given more than once");
  }
  return child;
}

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

RodEndKind parse_coupling(XmlElementReader& reader) {
  const std::string coupling = reader.text("coupling");
  if (coupling == "clamped") return RodEndKind::Clamped;
  if (coupling == "collar") return RodEndKind::Collar;
  if (coupling == "spherical") return RodEndKind::Spherical;
  if (coupling == "free") return RodEndKind::Free;
  reader.fail("coupling", coupling, "is not a coupling (clamped, collar, spherical or free)");
}

void read_rod_end(const TiXmlElement& e, const std::string& source, const std::string& label,
                  const UrdfTree& tree, RodAttachment& attachment, RodEnd& rod_end) {
  XmlElementReader reader(e, source, label);
  attachment.coupling = parse_coupling(reader);
  if (attachment.coupling == RodEndKind::Free) {
    for (const char* a : {"link", "xyz", "rpy"}) {
      if (reader.has(a)) reader.fail(a, reader.text(a), "is not allowed on a free end (it is not attached)");
    }
    rod_end.force = reader.vec3_or("force", Vec3::Zero());
    rod_end.moment = reader.vec3_or("moment", Vec3::Zero());
  } else {
    for (const char* a : {"force", "moment"}) {
      if (reader.has(a))
        reader.fail(a, reader.text(a), "is only allowed on a free end (use pcr_load on links)");
    }
    const std::string link = reader.text("link");
    const auto it = tree.link_index.find(link);
    if (it == tree.link_index.end()) reader.fail("link", link, "is not a link of the robot");
    attachment.link = it->second;
    attachment.frame =
        Pose::from_xyz_rpy(reader.vec3_or("xyz", Vec3::Zero()), reader.vec3_or("rpy", Vec3::Zero()));
  }
  reader.finish();
}

Material read_material(XmlElementReader& reader) {
  const double E = reader.positive("youngs_modulus");
  const double density = reader.non_negative("density");
  const bool has_G = reader.has("shear_modulus"), has_nu = reader.has("poisson_ratio");
  if (has_G == has_nu) reader.fail("give exactly one of the attributes 'shear_modulus' and 'poisson_ratio'");
  Material material;
  if (has_G) {
    material = Material{E, reader.positive("shear_modulus"), density};
  } else {
    const double nu = reader.number("poisson_ratio");
    if (!(nu > -1.0 && nu < 0.5))
      reader.fail("poisson_ratio", reader.text("poisson_ratio"), "must lie in (-1, 0.5)");
    material = Material::from_poisson_ratio(E, nu, density);
  }
  reader.finish();
  return material;
}

CrossSection read_section(XmlElementReader& reader) {
  const std::string type = reader.text("type");
  CrossSection section;
  if (type == "circle") {
    section = CrossSection::circle(reader.positive("radius"));
  } else if (type == "rectangle") {
    const double width = reader.positive("width");
    section = CrossSection::rectangle(width, reader.positive("height"));
  } else {
    reader.fail("type", type, "is not a section type (circle or rectangle)");
  }
  reader.finish();
  return section;
}

void read_length(XmlElementReader& reader, RodElement& rod) {
  rod.length_default = reader.positive("value");
  rod.length_actuated = reader.boolean_or("actuated", false);
  if (!rod.length_actuated) {
    for (const char* a : {"lower", "upper"}) {
      if (reader.has(a)) reader.fail(a, reader.text(a), "is only allowed with actuated=\"true\"");
    }
    rod.length_lower = rod.length_upper = rod.length_default;
  } else {
    rod.length_lower = reader.positive("lower");
    rod.length_upper = reader.positive("upper");
    if (rod.length_lower > rod.length_upper) {
      reader.fail("lower", reader.text("lower"), "is greater than upper = " + reader.text("upper"));
    }
    if (rod.length_default < rod.length_lower || rod.length_default > rod.length_upper) {
      reader.fail("value", reader.text("value"),
                  "(the default length) is outside [lower, upper] = [" + reader.text("lower") + ", " +
                      reader.text("upper") + "]");
    }
  }
  reader.finish();
}

void read_discretization(XmlElementReader& reader, RodElement& rod) {
  const std::string formulation = reader.text_or("formulation", "auto");
  if (formulation == "auto") {
    rod.formulation = RodFormulation::Auto;
  } else if (formulation == "primal") {
    rod.formulation = RodFormulation::Primal;
  } else if (formulation == "mixed") {
    rod.formulation = RodFormulation::Mixed;
  } else {
    reader.fail("formulation", formulation, "is not a formulation (auto, primal or mixed)");
  }
  rod.degree = reader.integer_or("degree", 0);
  if (reader.has("degree") && rod.degree < 2) reader.fail("degree", reader.text("degree"), "must be >= 2");
  rod.elements = reader.integer_or("elements", 0);
  if (reader.has("elements") && rod.elements < 1)
    reader.fail("elements", reader.text("elements"), "must be >= 1");
  reader.finish();
}

RodElement read_rod(const TiXmlElement& e, const std::string& source, const UrdfTree& tree) {
  RodElement rod;
  {
    XmlElementReader reader(e, source, "pcr_rod");
    rod.name = reader.text("name");
    if (rod.name.empty()) reader.fail("name", rod.name, "is empty");
    reader.finish();
  }
  const std::string label = quoted("pcr_rod", rod.name);
  XmlElementReader element(e, source, label);
  static const char* const known[] = {
      "start",           "end", "material", "section", "length", "intrinsic_curvature", "discretization",
      "distributed_load"};
  for (const TiXmlElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) {
    bool ok = false;
    for (const char* k : known) ok = ok || c->ValueStr() == k;
    if (!ok) element.fail("unknown element <" + c->ValueStr() + ">");
  }
  auto child = [&](const char* name, bool required) { return single_child(element, e, name, required); };
  read_rod_end(*child("start", true), source, label + " <start>", tree, rod.start, rod.rod.base);
  read_rod_end(*child("end", true), source, label + " <end>", tree, rod.end, rod.rod.tip);
  if (rod.start.coupling != RodEndKind::Clamped && rod.end.coupling != RodEndKind::Clamped) {
    element.fail(std::string("couplings start = ") + to_string(rod.start.coupling) +
                 ", end = " + to_string(rod.end.coupling) +
                 " leave the rod free to move or twist; clamp at least one end");
  }
  if (rod.start.link >= 0 && rod.start.link == rod.end.link) {
    element.fail("both ends are on link '" + tree.link_names[rod.start.link] +
                 "'; a rod must join two different links");
  }
  XmlElementReader material(*child("material", true), source, label + " <material>");
  XmlElementReader section(*child("section", true), source, label + " <section>");
  rod.rod.name = rod.name;
  rod.rod.set_material_and_section(read_material(material), read_section(section));
  XmlElementReader length(*child("length", true), source, label + " <length>");
  read_length(length, rod);
  if (const TiXmlElement* c = child("intrinsic_curvature", false)) {
    XmlElementReader reader(*c, source, label + " <intrinsic_curvature>");
    rod.rod.intrinsic.curvature = reader.vec3("xyz");
    reader.finish();
  }
  if (const TiXmlElement* c = child("discretization", false)) {
    XmlElementReader reader(*c, source, label + " <discretization>");
    read_discretization(reader, rod);
  }
  if (const TiXmlElement* c = child("distributed_load", false)) {
    XmlElementReader reader(*c, source, label + " <distributed_load>");
    rod.rod.loads.force_per_length = reader.vec3_or("force", Vec3::Zero());
    rod.rod.loads.moment_per_length = reader.vec3_or("moment", Vec3::Zero());
    reader.finish();
  }
  return rod;
}

RobotModel parse_document(const std::string& xml, const std::string& source) {
  TiXmlDocument document;
  document.Parse(xml.c_str());
  if (document.Error()) {
    throw_input_error(source, ":", document.ErrorRow(), ": XML error: ", document.ErrorDesc());
  }
  const TiXmlElement* robot = document.RootElement();
  if (robot == nullptr || robot->ValueStr() != "robot")
    throw_input_error(source, ": the root element is not <robot>");
  XmlElementReader robot_reader(*robot, source, "robot");
  const std::string robot_name = robot_reader.text("name");

  const UrdfTree tree = read_tree(*robot, source);
  const std::shared_ptr<urdf::ModelInterface> urdf = parse_with_urdfdom(xml, source);
  std::vector<Link> links(tree.links.size());
  for (std::size_t i = 0; i < links.size(); ++i) links[i].name = tree.link_names[i];
  std::vector<Joint> joints = read_joints(tree, *urdf, source);

  // Platforms (children of floating joints, file order) and their mass; mass elsewhere on a platform's
  // subtree would be ignored silently, so it is rejected.
  std::vector<Platform> platforms;
  for (std::size_t i = 0; i < links.size(); ++i) {
    const urdf::LinkConstSharedPtr u = urdf->getLink(links[i].name);
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

  // Extension elements.
  Vec3 gravity = Vec3::Zero();
  std::vector<RodElement> rods;
  std::vector<ExternalLoad> loads;
  std::map<std::string, int> rod_lines;
  bool has_gravity = false;
  for (const TiXmlElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->ValueStr();
    if (tag == "pcr_gravity") {
      XmlElementReader reader(*e, source, "pcr_gravity");
      if (has_gravity) reader.fail("given more than once");
      has_gravity = true;
      gravity = reader.vec3("xyz");
      reader.finish();
    } else if (tag == "pcr_rod") {
      rods.push_back(read_rod(*e, source, tree));
      if (!rod_lines.emplace(rods.back().name, e->Row()).second) {
        XmlElementReader reader(*e, source, quoted("pcr_rod", rods.back().name));
        reader.fail("name", rods.back().name,
                    "is already used by the pcr_rod on line " + std::to_string(rod_lines[rods.back().name]));
      }
    } else if (tag == "pcr_load") {
      XmlElementReader reader(*e, source, "pcr_load");
      ExternalLoad load;
      const std::string link = reader.text("link");
      const auto it = tree.link_index.find(link);
      if (it == tree.link_index.end()) reader.fail("link", link, "is not a link of the robot");
      if (carrying_floating_link(tree, it->second) < 0) {
        reader.fail("link", link, "is not carried by a platform (a load there acts on the fixed world)");
      }
      load.link = it->second;
      load.point = reader.vec3_or("xyz", Vec3::Zero());
      load.force = reader.vec3_or("force", Vec3::Zero());
      load.torque = reader.vec3_or("torque", Vec3::Zero());
      reader.finish();
      loads.push_back(load);
    } else if (tag == "pcr_joint") {
      XmlElementReader reader(*e, source, "pcr_joint");
      const std::string name = reader.text("name");
      int j = 0;
      while (j < static_cast<int>(joints.size()) && joints[j].name != name) ++j;
      if (j == static_cast<int>(joints.size())) reader.fail("name", name, "is not a joint of the robot");
      Joint& joint = joints[j];
      if (joint.type == JointType::Fixed || joint.type == JointType::Floating) {
        reader.fail("name", name,
                    std::string("is a ") + to_string(joint.type) + " joint, which has no value");
      }
      const double value = reader.number("default");
      if (joint.type != JointType::Continuous && (value < joint.lower || value > joint.upper)) {
        std::ostringstream bounds;
        bounds << "is outside the joint limits [" << joint.lower << ", " << joint.upper << "]";
        reader.fail("default", reader.text("default"), bounds.str());
      }
      joint.default_value = value;
      reader.finish();
    } else if (tag.compare(0, 4, "pcr_") == 0) {
      XmlElementReader reader(*e, source, "<" + tag + ">");
      reader.fail("unknown pcr element (pcr_rod, pcr_gravity, pcr_load or pcr_joint)");
    }
  }
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

  // Cross-element checks (well-posedness, platform hold) live in RobotModel; prefix the file name.
  try {
    return RobotModel(robot_name, std::move(links), std::move(joints), std::move(platforms), std::move(rods),
                      std::move(loads), gravity);
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
