// Robots with joint rod ends and passive joints, built in code (see joint_robots.hpp).
#include "joint_robots.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "pcr/math/quaternion.hpp"

namespace pcr {
namespace test_robots {
namespace {

// The parts of a model being built.
struct Parts {
  std::vector<Link> links;
  std::vector<Joint> joints;
  std::vector<Platform> platforms;
  std::vector<RodElement> rods;

  int link(const std::string& name, double mass = 0.0, const Vec3& com = Vec3::Zero()) {
    Link l;
    l.name = name;
    l.mass = mass;
    l.center_of_mass = com;
    links.push_back(l);
    return static_cast<int>(links.size()) - 1;
  }
  Joint& joint(const std::string& name, JointType type, int parent, int child, const Pose& origin) {
    Joint j;
    j.name = name;
    j.type = type;
    j.parent_link = parent;
    j.child_link = child;
    j.origin = origin;
    joints.push_back(j);
    return joints.back();
  }
  Joint& passive(const std::string& name, JointType type, int parent, int child, const Pose& origin,
                 const Vec3& axis) {
    Joint& j = joint(name, type, parent, child, origin);
    j.axis = axis;
    j.passive = true;
    if (type == JointType::Revolute) {
      j.lower = -M_PI;
      j.upper = M_PI;
    }
    return j;
  }
  void platform(int link, double mass, const Vec3& com = Vec3::Zero()) {
    Platform p;
    p.link = link;
    p.mass = mass;
    p.center_of_mass = com;
    platforms.push_back(p);
  }
  std::shared_ptr<const RobotModel> build(const std::string& name, const Vec3& gravity) {
    return std::make_shared<const RobotModel>(name, links, joints, platforms, rods,
                                              std::vector<ExternalLoad>{}, gravity);
  }
};

RodAttachment attachment(int link, const Pose& frame, RodEndKind coupling, const Vec3& axis = Vec3::UnitX()) {
  RodAttachment a;
  a.link = link;
  a.frame = frame;
  a.coupling = coupling;
  a.axis = axis;
  return a;
}

RodElement rod(const std::string& name, const Material& material, double radius, double length) {
  RodElement e;
  e.name = name;
  e.rod.set_material_and_section(material, CrossSection::circle(radius));
  e.length_default = length;
  return e;
}

Pose at(double x, double y, double z, double roll = 0.0, double pitch = 0.0, double yaw = 0.0) {
  return Pose::from_xyz_rpy(Vec3(x, y, z), Vec3(roll, pitch, yaw));
}

}  // namespace

std::shared_ptr<const RobotModel> six_rus_like(bool passive_universals) {
  const double yaw = 2.094395102393;
  const Pose motors[6] = {at(0.0675, 0.126099072294, 0),
                          at(-0.0675, 0.126099072294, 0),
                          at(-0.142955, -0.004592821391, 0, 0, 0, yaw),
                          at(-0.075455, -0.121506250902, 0, 0, 0, yaw),
                          at(0.075455, -0.121506250902, 0, 0, 0, -yaw),
                          at(0.142955, -0.004592821391, 0, 0, 0, -yaw)};
  const Vec3 platform_joints[6] = {{0.121685, 0.132308474439, 0}, {-0.121685, 0.132308474439, 0},
                                   {-0.175425, 0.03922806404, 0}, {-0.05374, -0.171536538479, 0},
                                   {0.05374, -0.171536538479, 0}, {0.175425, 0.03922806404, 0}};
  const Pose crank_tip = at(0, 0.23164, 0);
  Parts parts;
  const int base = parts.link("base");
  const int platform = parts.link("platform");
  parts.platform(platform, 0.5);
  parts.joint("platform_pose", JointType::Floating, base, platform, at(0, 0, 0.5));
  const Material titanium = Material::from_poisson_ratio(110.3e9, 0.31, 4428.8);
  for (int i = 0; i < 6; ++i) {
    const std::string n = std::to_string(i + 1);
    const int crank = parts.link("crank" + n);
    Joint& motor = parts.joint("motor" + n, JointType::Revolute, base, crank, motors[i]);
    motor.axis = Vec3::UnitX();
    motor.lower = -0.349065850399;
    motor.upper = 1.570796326795;
    motor.default_value = 0.39497946;
    RodElement e = rod("rod" + n, titanium, 0.002, 0.53);
    e.rod.intrinsic.curvature = Vec3(1.0 / 0.3, 0, 0);
    if (passive_universals) {
      // The universal joint's two axes as joints: a = crank y, then b = e3 x a = -x, rod clamped after.
      const int first = parts.link("u_first" + n), second = parts.link("u_second" + n);
      parts.passive("u_a" + n, JointType::Continuous, crank, first, crank_tip, Vec3::UnitY());
      parts.passive("u_b" + n, JointType::Revolute, first, second, Pose(), -Vec3::UnitX());
      e.start = attachment(second, Pose(), RodEndKind::Clamped);
    } else {
      e.start = attachment(crank, crank_tip, RodEndKind::Universal, Vec3::UnitY());
    }
    e.end = attachment(platform, Pose{platform_joints[i], Quat(1, 0, 0, 0)}, RodEndKind::Spherical);
    parts.rods.push_back(e);
  }
  return parts.build(passive_universals ? "six_rus_like_passive" : "six_rus_like", Vec3(0, 0, -9.81));
}

std::shared_ptr<const RobotModel> planar_pinned(bool massless_rods) {
  // planar_three_rod.urdf: start x, pitch of both frames, end point in the platform frame, length.
  struct Leg {
    const char* name;
    double x, pitch;
    Vec3 end;
    double length;
  };
  const Leg legs[3] = {{"left", -0.15, 0.351444794004, {-0.04, 0, 0}, 0.319530906173},
                       {"middle", -0.08, 0.278299659005, {0, 0, -0.02}, 0.291204395571},
                       {"right", 0.15, -0.351444794004, {0.04, 0, 0}, 0.319530906173}};
  Parts parts;
  const int base = parts.link("base");
  const int platform = parts.link("platform");
  parts.platform(platform, 0.05, Vec3(0, 0, -0.005));
  parts.joint("platform_pose", JointType::Floating, base, platform, at(0, 0, 0.3));
  const Material steel{200e9, 80e9, massless_rods ? 0.0 : 8000.0};
  for (const Leg& leg : legs) {
    RodElement e = rod(leg.name, steel, 0.001, leg.length);
    e.length_actuated = true;
    e.length_lower = 0.15;
    e.length_upper = 0.5;
    const int pin = parts.link(std::string("pin_") + leg.name);
    parts.passive(std::string("pin_") + leg.name, JointType::Revolute, base, pin,
                  at(leg.x, 0, 0, 0, leg.pitch), Vec3::UnitY());
    e.start = attachment(pin, Pose(), RodEndKind::Clamped);
    e.end = attachment(platform, Pose{leg.end, at(0, 0, 0, 0, leg.pitch).orientation}, RodEndKind::Revolute,
                       Vec3::UnitY());
    parts.rods.push_back(e);
  }
  return parts.build("planar_pinned", Vec3(0, 0, -9.81));
}

std::shared_ptr<const RobotModel> tripod_pinned(bool passive_starts) {
  Parts parts;
  const int base = parts.link("base");
  const int platform = parts.link("platform");
  parts.platform(platform, 0.3, Vec3(0.02, 0, 0));
  const double height = 0.3;
  parts.joint("platform_pose", JointType::Floating, base, platform, at(0, 0, height));
  const Material steel{200e9, 80e9, 8000.0};
  for (int i = 0; i < 3; ++i) {
    const std::string n = std::to_string(i + 1);
    const double angle = M_PI / 2 + 2 * M_PI * i / 3;
    const Vec3 radial(std::cos(angle), std::sin(angle), 0.0),
        tangential(-std::sin(angle), std::cos(angle), 0.0);
    const Vec3 start = 0.12 * radial, end = 0.06 * radial + Vec3(0, 0, height);
    // Frame: x tangential (the pin axis), z along the rod, y = z x x.
    const Vec3 z = (end - start).normalized();
    Mat3 R;
    R << tangential, z.cross(tangential), z;
    const Quat q = quat_from_rotation(R);
    RodElement e = rod("rod" + n, steel, 0.0015, (end - start).norm());
    if (passive_starts) {
      const int pin = parts.link("pin" + n);
      parts.passive("pin" + n, JointType::Revolute, base, pin, Pose{start, q}, Vec3::UnitX());
      e.start = attachment(pin, Pose(), RodEndKind::Clamped);
    } else {
      e.start = attachment(base, Pose{start, q}, RodEndKind::Revolute, Vec3::UnitX());
    }
    e.end = attachment(platform, Pose{end - Vec3(0, 0, height), q}, RodEndKind::Clamped);
    parts.rods.push_back(e);
  }
  return parts.build(passive_starts ? "tripod_passive_pins" : "tripod_pinned", Vec3(0, 0, -9.81));
}

std::shared_ptr<const RobotModel> spring_hinge(JointType type) {
  const bool prismatic = type == JointType::Prismatic;
  Parts parts;
  const int base = parts.link("base");
  const int arm = parts.link("arm", 0.2, Vec3(0, 0.05, 0));
  const int platform = parts.link("platform");
  parts.platform(platform, 0.5, Vec3(0, 0.03, 0));
  parts.joint("platform_pose", JointType::Floating, base, platform, at(0, 0.2, 0));
  Joint& spring = parts.passive("spring", type, base, arm, Pose(), prismatic ? Vec3::UnitZ() : Vec3::UnitX());
  spring.stiffness = prismatic ? 2000.0 : 10.0;
  spring.rest = prismatic ? 0.01 : 0.6;
  if (prismatic) {
    spring.lower = -0.1;
    spring.upper = 0.1;
  }
  RodElement e = rod("rod", Material{200e9, 80e9, 8000.0}, prismatic ? 0.003 : 0.01, 0.2);
  // Along +y: the frame's z axis turned by -90 deg about x.
  e.start = attachment(arm, at(0, 0, 0, -M_PI / 2), RodEndKind::Clamped);
  e.end = attachment(platform, at(0, 0, 0, -M_PI / 2), RodEndKind::Clamped);
  parts.rods.push_back(e);
  return parts.build(prismatic ? "spring_slider" : "spring_hinge", Vec3(0, 0, -9.81));
}

}  // namespace test_robots
}  // namespace pcr
