#include "rod_element_reader.hpp"

#include <tinyxml.h>

#include "pcr/core/error.hpp"
#include "pcr/robots/robot_assembly.hpp"
#include "pcr/rods/end_axes.hpp"
#include "xml_element_reader.hpp"

namespace pcr {
namespace {

RodEndKind parse_coupling(XmlElementReader& reader) {
  const std::string coupling = reader.text("coupling");
  if (coupling == "clamped") return RodEndKind::Clamped;
  if (coupling == "collar") return RodEndKind::Collar;
  if (coupling == "spherical") return RodEndKind::Spherical;
  if (coupling == "universal") return RodEndKind::Universal;
  if (coupling == "revolute") return RodEndKind::Revolute;
  if (coupling == "free") return RodEndKind::Free;
  reader.fail("coupling", coupling,
              "is not a coupling (clamped, collar, spherical, universal, revolute or free)");
}

// The joint axis of a universal or revolute end (attachment frame, default x), normalised; rejected on
// the other couplings.
Vec3 read_joint_axis(XmlElementReader& reader, RodEndKind coupling) {
  if (coupling != RodEndKind::Universal && coupling != RodEndKind::Revolute) {
    if (reader.has("axis"))
      reader.fail("axis", reader.text("axis"), "is only allowed on universal and revolute couplings");
    return Vec3::UnitX();
  }
  const Vec3 axis = reader.vec3_or("axis", Vec3::UnitX());
  if (!(axis.norm() > 1e-12)) reader.fail("axis", reader.text("axis"), "is zero");
  if (coupling == RodEndKind::Universal && sine_to_tangent(axis) < kMinJointAxisSine) {
    reader.fail("axis", reader.text("axis"),
                "lies along the attachment z axis (the rod tangent); a universal joint's first axis must be "
                "normal to it");
  }
  return axis.normalized();
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
  attachment.axis = read_joint_axis(reader, attachment.coupling);
  rod_end.axis = attachment.axis;
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
    rod.formulation = RodFormulationHint::Auto;
  } else if (formulation == "primal") {
    rod.formulation = RodFormulationHint::Primal;
  } else if (formulation == "mixed") {
    rod.formulation = RodFormulationHint::Mixed;
  } else {
    reader.fail("formulation", formulation, "is not a formulation (auto, primal or mixed)");
  }
  rod.degree = reader.integer_or("degree", 0);
  if (reader.has("degree") && rod.degree < 2) reader.fail("degree", reader.text("degree"), "must be >= 2");
  rod.elements = reader.integer_or("elements", 0);
  if (reader.has("elements") && rod.elements < 1)
    reader.fail("elements", reader.text("elements"), "must be >= 1");
  if (reader.has("elements")) {
    // Rejected here, before any allocation, with the file and line; without a degree hint at the
    // assembly's default degree (the tool's --degree is checked again when the rod is built).
    const int degree = rod.degree > 0 ? rod.degree : AssemblyOptions{}.discretization.degree;
    const std::string excess = rod_memory_excess(degree, rod.elements);
    if (!excess.empty()) reader.fail("elements", reader.text("elements"), "is too many: " + excess);
  }
  reader.finish();
}

// The drawing speed c of a rod in steady axial motion (docs/model_format.md), checked against the rod's
// material, section and intrinsic strains (RodModel::drawing_speed_problem: the admissibility limits).
void check_drawing_speed(XmlElementReader& element, const RodModel& rod) {
  const std::string problem = rod.drawing_speed_problem();
  if (!problem.empty()) element.fail("drawing_speed", element.text("drawing_speed"), problem);
}

// Every child element of <pcr_rod> is one that pcr reads.
void check_known_children(XmlElementReader& element, const TiXmlElement& e) {
  static const char* const known[] = {"start",          "end",
                                      "material",       "section",
                                      "length",         "intrinsic_curvature",
                                      "discretization", "distributed_load",
                                      "contact"};
  for (const TiXmlElement* c = e.FirstChildElement(); c; c = c->NextSiblingElement()) {
    bool ok = false;
    for (const char* k : known) ok = ok || c->ValueStr() == k;
    if (!ok) element.fail("unknown element <" + c->ValueStr() + ">");
  }
}

// The two ends together: the twist rule, no rod that swings about a joint because its other end is free,
// and two different links.
void check_end_pair(XmlElementReader& element, const RodElement& rod, const UrdfTree& tree) {
  const std::string twist = twist_rule_violation(rod);
  if (!twist.empty()) element.fail(twist);
  // A universal or revolute end with the other end free leaves the rod a pendulum about the joint.
  for (const auto& [held, other] : {std::pair(&rod.start, &rod.end), std::pair(&rod.end, &rod.start)}) {
    if (other->coupling == RodEndKind::Free &&
        (held->coupling == RodEndKind::Universal || held->coupling == RodEndKind::Revolute)) {
      element.fail(std::string("couplings start = ") + to_string(rod.start.coupling) +
                   ", end = " + to_string(rod.end.coupling) + ": a " + to_string(held->coupling) +
                   " coupling with the other end free lets the rod swing about the joint as a rigid body; "
                   "clamp that end, or attach the free one");
    }
  }
  if (rod.start.link >= 0 && rod.start.link == rod.end.link) {
    element.fail("both ends are on link '" + tree.link_names[rod.start.link] +
                 "'; a rod must join two different links");
  }
}

}  // namespace

RodElement read_rod(const TiXmlElement& e, const std::string& source, const UrdfTree& tree) {
  RodElement rod;
  {
    XmlElementReader reader(e, source, "pcr_rod");
    rod.name = reader.text("name");
    if (rod.name.empty()) reader.fail("name", rod.name, "is empty");
    rod.rod.drawing_speed = reader.number_or("drawing_speed", 0.0);
    reader.finish();
  }
  const std::string label = quoted("pcr_rod", rod.name);
  XmlElementReader element(e, source, label);
  check_known_children(element, e);
  auto child = [&](const char* name, bool required) { return single_child(element, e, name, required); };
  read_rod_end(*child("start", true), source, label + " <start>", tree, rod.start, rod.rod.base);
  read_rod_end(*child("end", true), source, label + " <end>", tree, rod.end, rod.rod.tip);
  check_end_pair(element, rod, tree);
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
  check_drawing_speed(element, rod.rod);
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

}  // namespace pcr
