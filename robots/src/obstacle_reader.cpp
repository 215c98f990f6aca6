#include "obstacle_reader.hpp"

#include <tinyxml.h>

#include <cmath>
#include <map>
#include <sstream>

#include "pcr/core/error.hpp"
#include "xml_element_reader.hpp"

namespace pcr {
namespace {

// A unit vector attribute (|1 - |a|| <= 1e-9: a direction, not a scaled one).
Vec3 unit_vector(XmlElementReader& reader, const char* attribute) {
  const Vec3 a = reader.vec3(attribute);
  if (std::abs(a.norm() - 1.0) > 1e-9) reader.fail(attribute, reader.text(attribute), "is not a unit vector");
  return a;
}

// A sharp edge: the line through xyz along a unit `axis`, or the segment from xyz to `end` (one of them).
void read_edge(XmlElementReader& element, Obstacle& o) {
  if (element.has("axis") == element.has("end"))
    element.fail("an edge needs either axis (an infinite line) or end (a segment), not both");
  if (element.has("axis")) {
    o.direction = unit_vector(element, "axis");
    return;
  }
  o.finite = true;
  o.end = element.vec3("end");
  if (o.end == o.position) element.fail("end", element.text("end"), "is the same point as xyz (use a point)");
}

// contact="distributed" (default) | "point" on a sphere, capsule or cylinder.
void read_contact_kind(XmlElementReader& element, Obstacle& o) {
  if (!element.has("contact")) return;
  const std::string kind = element.text("contact");
  const bool round = o.shape == ObstacleShape::Sphere || o.shape == ObstacleShape::Capsule ||
                     o.shape == ObstacleShape::Cylinder;
  if (kind == "point" && round) {
    o.point_contact = true;
  } else if (kind != "distributed" || !round) {
    element.fail("contact", kind,
                 round ? "is not a contact kind (distributed, point)"
                       : "is given on an obstacle that is not a sphere, capsule or cylinder");
  }
}

// law="slip" (default) | "adhesion" on a roller; adhesion needs stuck_at (the arc length of the rod's
// section at the contact at angle 0, >= 0) and takes angle (rad, default 0) (docs/contact.md, "Rollers").
void read_roller_law(XmlElementReader& element, Obstacle& o) {
  if (!element.has("law")) {
    if (element.has("stuck_at") || element.has("angle"))
      element.fail(element.has("stuck_at") ? "stuck_at" : "angle",
                   element.text(element.has("stuck_at") ? "stuck_at" : "angle"),
                   "is given without law=\"adhesion\"");
    return;
  }
  const std::string law = element.text("law");
  if (o.shape != ObstacleShape::Roller)
    element.fail("law", law, "is given on an obstacle that is not a roller");
  if (law != "slip" && law != "adhesion") element.fail("law", law, "is not a roller law (slip, adhesion)");
  if (law == "slip") {
    if (element.has("stuck_at") || element.has("angle"))
      element.fail("law", law, "takes no stuck_at or angle (they belong to law=\"adhesion\")");
    return;
  }
  o.law = RollerLaw::Adhesion;
  if (!element.has("stuck_at"))
    element.fail("law", law, "needs stuck_at (the arc length of the rod's section at the contact)");
  o.stuck_section = element.non_negative("stuck_at");
  o.angle = element.number_or("angle", 0.0);
}

// <pcr_obstacle name type link xyz normal | radius | end radius | axis radius>.
ObstacleElement read_obstacle(const TiXmlElement& e, const std::string& source, const UrdfTree& tree) {
  XmlElementReader reader(e, source, "pcr_obstacle");
  ObstacleElement out;
  Obstacle& o = out.obstacle;
  o.name = reader.text("name");
  if (o.name.empty()) reader.fail("name", o.name, "is empty");
  XmlElementReader element(e, source, quoted("pcr_obstacle", o.name));
  element.text("name");
  const std::string type = element.text("type");
  static const std::map<std::string, ObstacleShape> shapes{{"half_space", ObstacleShape::HalfSpace},
                                                           {"sphere", ObstacleShape::Sphere},
                                                           {"capsule", ObstacleShape::Capsule},
                                                           {"cylinder", ObstacleShape::Cylinder},
                                                           {"edge", ObstacleShape::Edge},
                                                           {"point", ObstacleShape::Point},
                                                           {"roller", ObstacleShape::Roller}};
  const auto shape = shapes.find(type);
  if (shape == shapes.end())
    element.fail("type", type,
                 "is not an obstacle type (half_space, sphere, capsule, cylinder, edge, point, roller)");
  o.shape = shape->second;
  if (element.has("link")) {
    const std::string link = element.text("link");
    const auto it = tree.link_index.find(link);
    if (it == tree.link_index.end()) element.fail("link", link, "is not a link of the robot");
    out.link = it->second;
  }
  o.position = element.vec3("xyz");
  switch (o.shape) {
    case ObstacleShape::HalfSpace: o.direction = unit_vector(element, "normal"); break;
    case ObstacleShape::Sphere: o.radius = element.positive("radius"); break;
    case ObstacleShape::Capsule:
      o.end = element.vec3("end");
      if (o.end == o.position)
        element.fail("end", element.text("end"), "is the same point as xyz (use a sphere)");
      o.radius = element.positive("radius");
      break;
    case ObstacleShape::Cylinder:
      o.direction = unit_vector(element, "axis");
      o.radius = element.positive("radius");
      break;
    case ObstacleShape::Edge: read_edge(element, o); break;
    case ObstacleShape::Point: break;
    case ObstacleShape::Roller:
      o.direction = unit_vector(element, "axis");
      o.radius = element.positive("radius");
      o.length = element.positive("length");
      break;
  }
  read_contact_kind(element, o);
  read_roller_law(element, o);
  element.finish();
  return out;
}

// The adhesive rollers among the rod's obstacles: their stuck section (minus radius x angle) lies on the
// rod, and no other rod names them (the stuck section belongs to one rod).
void check_adhesive_rollers(XmlElementReader& reader, const std::vector<ObstacleElement>& obstacles,
                            const RodElement& rod) {
  for (int k : rod.obstacles) {
    const Obstacle& o = obstacles[k].obstacle;
    if (!adhesive(o)) continue;
    const double sigma = o.adhesive_section(), L = rod.length_default;
    if (o.stuck_section > L)
      reader.fail("obstacles", o.name,
                  "is an adhesive roller whose stuck section (stuck_at = " + std::to_string(o.stuck_section) +
                      " m) is not on the rod [0, " + std::to_string(L) + "] m");
    if (sigma > L)
      reader.fail("obstacles", o.name,
                  "is an adhesive roller whose section at the contact (stuck_at - radius x angle = " +
                      std::to_string(sigma) + " m) is not on the rod [0, " + std::to_string(L) + "] m");
    if (sigma < 0.0)
      reader.fail("obstacles", o.name,
                  "is an adhesive roller whose section at the contact (stuck_at - radius x angle = " +
                      std::to_string(sigma) + " m) is before the rod's start");
  }
}

// <contact obstacles="a b" radius="r"> of one pcr_rod.
void read_rod_contact(const TiXmlElement& c, const std::string& source, const std::string& rod_name,
                      const std::map<std::string, int>& obstacle_index,
                      const std::vector<ObstacleElement>& obstacles, RodElement& rod) {
  XmlElementReader reader(c, source, quoted("pcr_rod", rod_name) + " <contact>");
  std::istringstream names(reader.text("obstacles"));
  for (std::string name; names >> name;) {
    const auto it = obstacle_index.find(name);
    if (it == obstacle_index.end()) reader.fail("obstacles", name, "is not the name of a pcr_obstacle");
    for (int k : rod.obstacles)
      if (k == it->second) reader.fail("obstacles", name, "is named twice");
    rod.obstacles.push_back(it->second);
  }
  check_adhesive_rollers(reader, obstacles, rod);
  if (rod.obstacles.empty()) reader.fail("obstacles", "", "names no obstacle");
  if (reader.has("radius")) {
    rod.contact_radius = reader.positive("radius");
  } else {
    rod.contact_radius = rod.rod.outer_radius;
    if (!(rod.contact_radius > 0.0)) reader.fail("the section has no outer radius; give radius");
  }
  reader.finish();
}

// An adhesive roller holds one material section of one rod: a second rod naming it is an error.
void check_one_rod_per_adhesive_roller(const TiXmlElement& robot, const std::string& source,
                                       const std::vector<ObstacleElement>& obstacles,
                                       const std::vector<RodElement>& rods) {
  std::map<int, std::string> holder;
  for (const TiXmlElement* e = robot.FirstChildElement("pcr_rod"); e; e = e->NextSiblingElement("pcr_rod")) {
    const char* name = e->Attribute("name");
    const TiXmlElement* c = e->FirstChildElement("contact");
    if (name == nullptr || c == nullptr) continue;
    for (const RodElement& rod : rods) {
      if (rod.name != name) continue;
      for (int k : rod.obstacles) {
        if (!adhesive(obstacles[k].obstacle)) continue;
        const auto [it, first] = holder.emplace(k, rod.name);
        if (first) continue;
        XmlElementReader reader(*c, source, quoted("pcr_rod", name) + " <contact>");
        reader.fail("obstacles", obstacles[k].obstacle.name,
                    "is an adhesive roller already named by pcr_rod '" + it->second +
                        "' (its stuck section belongs to one rod)");
      }
    }
  }
}

}  // namespace

std::vector<ObstacleElement> read_obstacles(const TiXmlElement& robot, const std::string& source,
                                            const UrdfTree& tree, std::vector<RodElement>& rods) {
  std::vector<ObstacleElement> obstacles;
  std::map<std::string, int> index, lines;
  for (const TiXmlElement* e = robot.FirstChildElement("pcr_obstacle"); e;
       e = e->NextSiblingElement("pcr_obstacle")) {
    obstacles.push_back(read_obstacle(*e, source, tree));
    const std::string& name = obstacles.back().obstacle.name;
    if (!index.emplace(name, static_cast<int>(obstacles.size()) - 1).second) {
      XmlElementReader reader(*e, source, quoted("pcr_obstacle", name));
      reader.fail("name", name, "is already used by the pcr_obstacle on line " + std::to_string(lines[name]));
    }
    lines[name] = e->Row();
  }
  for (const TiXmlElement* e = robot.FirstChildElement("pcr_rod"); e; e = e->NextSiblingElement("pcr_rod")) {
    const char* name = e->Attribute("name");
    const TiXmlElement* c = e->FirstChildElement("contact");
    if (name == nullptr || c == nullptr) continue;
    if (c->NextSiblingElement("contact") != nullptr) {
      XmlElementReader reader(*c->NextSiblingElement("contact"), source,
                              quoted("pcr_rod", name) + " <contact>");
      reader.fail("is given more than once");
    }
    for (RodElement& rod : rods)
      if (rod.name == name) read_rod_contact(*c, source, name, index, obstacles, rod);
  }
  check_one_rod_per_adhesive_roller(robot, source, obstacles, rods);
  return obstacles;
}

}  // namespace pcr
