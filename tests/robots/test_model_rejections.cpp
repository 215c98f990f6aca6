// One malformed-model case per validation rule of the URDF loader: each changes one piece of a valid
// one-rod model (model_xml.hpp) and must throw an InputError naming the file, the element and the value.
#include <boost/test/unit_test.hpp>

#include <string>

#include "model_xml.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;
using test::check_rejected;
using test::kPlatformTree;
using test::robot;
using test::RodXml;

BOOST_AUTO_TEST_CASE(valid_template_loads) {
  // The malformed cases below each change one piece of this model.
  const RobotModel m = parse_robot_model(robot(RodXml().str()), "good.urdf");
  BOOST_TEST(m.rods().size() == 1u);
  BOOST_TEST(m.platforms().size() == 1u);
}

BOOST_AUTO_TEST_CASE(rejects_unknown_link) {
  RodXml rod;
  rod.start = R"(<start link="nowhere" coupling="clamped"/>)";
  check_rejected(robot(rod.str()), {"bad.urdf", "pcr_rod 'r0' <start>", "'link'", "\"nowhere\""});
  check_rejected(robot(RodXml().str() + R"(<pcr_load link="moon" force="0 0 -1"/>)"),
                 {"bad.urdf", "pcr_load", "'link'", "\"moon\""});
}

BOOST_AUTO_TEST_CASE(rejects_missing_attribute_and_element) {
  RodXml rod;
  rod.section = R"(<section type="circle"/>)";
  check_rejected(robot(rod.str()), {"bad.urdf", "pcr_rod 'r0' <section>", "missing attribute 'radius'"});
  rod = RodXml();
  rod.material = "";
  check_rejected(robot(rod.str()), {"bad.urdf", "pcr_rod 'r0'", "missing element <material>"});
  rod = RodXml();
  rod.end = R"(<end link="platform"/>)";
  check_rejected(robot(rod.str()), {"bad.urdf", "pcr_rod 'r0' <end>", "missing attribute 'coupling'"});
}

BOOST_AUTO_TEST_CASE(rejects_non_numeric_values) {
  RodXml rod;
  rod.section = R"(<section type="circle" radius="1mm"/>)";
  check_rejected(robot(rod.str()),
                 {"bad.urdf", "pcr_rod 'r0' <section>", "'radius'", "\"1mm\"", "not a finite"});
  rod = RodXml();
  rod.start = R"(<start link="base" xyz="0 0" coupling="clamped"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <start>", "'xyz'", "\"0 0\""});
  rod = RodXml();
  rod.material = R"(<material youngs_modulus="nan" shear_modulus="80e9" density="8000"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <material>", "'youngs_modulus'", "\"nan\""});
  check_rejected(robot(RodXml().str() + R"(<pcr_gravity xyz="0 0 -9.81 1"/>)"), {"pcr_gravity", "'xyz'"});
}

BOOST_AUTO_TEST_CASE(rejects_non_physical_values) {
  RodXml rod;
  rod.section = R"(<section type="circle" radius="-0.001"/>)";
  check_rejected(robot(rod.str()),
                 {"bad.urdf", "pcr_rod 'r0' <section>", "'radius'", "\"-0.001\"", "positive"});
  rod.section = R"(<section type="rectangle" width="0.002" height="0"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <section>", "'height'", "\"0\""});
  rod = RodXml();
  rod.material = R"(<material youngs_modulus="0" shear_modulus="80e9" density="8000"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <material>", "'youngs_modulus'", "\"0\"", "positive"});
  rod.material = R"(<material youngs_modulus="200e9" shear_modulus="-80e9" density="8000"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <material>", "'shear_modulus'", "\"-80e9\""});
  rod.material = R"(<material youngs_modulus="200e9" poisson_ratio="0.7" density="8000"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <material>", "'poisson_ratio'", "\"0.7\""});
  rod.material = R"(<material youngs_modulus="200e9" shear_modulus="80e9" poisson_ratio="0.3" density="1"/>)";
  check_rejected(robot(rod.str()),
                 {"pcr_rod 'r0' <material>", "exactly one", "'shear_modulus'", "'poisson_ratio'"});
  rod.material = R"(<material youngs_modulus="200e9" shear_modulus="80e9" density="-1"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <material>", "'density'", "\"-1\""});
  rod = RodXml();
  rod.length = R"(<length value="-0.3"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <length>", "'value'", "\"-0.3\"", "positive"});
  rod.length = R"(<length value="0"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <length>", "'value'", "\"0\""});
  rod.length = R"(<length value="0.3" actuated="true" lower="0.5" upper="0.4"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <length>", "'lower'", "\"0.5\"", "upper = 0.4"});
  rod.length = R"(<length value="0.9" actuated="true" lower="0.2" upper="0.8"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <length>", "'value'", "\"0.9\"", "[0.2, 0.8]"});
  rod.length = R"(<length value="0.3" lower="0.2" upper="0.8"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <length>", "'lower'", "actuated"});
  rod = RodXml();
  rod.extra = R"(<discretization degree="1"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <discretization>", "'degree'", "\"1\""});
}

BOOST_AUTO_TEST_CASE(rejects_unknown_kinds_and_attributes) {
  RodXml rod;
  rod.end = R"(<end link="platform" coupling="welded"/>)";
  check_rejected(robot(rod.str()), {"bad.urdf", "pcr_rod 'r0' <end>", "'coupling'", "\"welded\""});
  rod = RodXml();
  rod.section = R"(<section type="hexagon" radius="0.001"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <section>", "'type'", "\"hexagon\""});
  rod.section = R"(<section type="circle" radus="0.001"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <section>", "'radius'"});
  rod.section = R"(<section type="circle" radius="0.001" width="0.002"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <section>", "'width'", "\"0.002\"", "not allowed"});
  rod = RodXml();
  rod.extra = R"(<intrinsic_curvatur xyz="0 0 0"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0'", "unknown element <intrinsic_curvatur>"});
  rod.extra = R"(<discretization formulation="weak"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0' <discretization>", "'formulation'", "\"weak\""});
  check_rejected(robot(RodXml().str() + R"(<pcr_spring name="s"/>)"),
                 {"bad.urdf", "<pcr_spring>", "unknown"});
}

BOOST_AUTO_TEST_CASE(rejects_duplicate_rod_names) {
  RodXml a, b;
  b.start = R"(<start link="base" xyz="0.1 0 0" coupling="clamped"/>)";
  check_rejected(robot(a.str() + b.str()), {"bad.urdf", "pcr_rod 'r0'", "'name'", "\"r0\"", "already used"});
}

BOOST_AUTO_TEST_CASE(rejects_platform_without_rods) {
  const std::string cantilever = R"(<pcr_rod name="beam"><start link="base" coupling="clamped"/>
<end coupling="free"/><material youngs_modulus="1e9" shear_modulus="4e8" density="0"/>
<section type="circle" radius="0.001"/><length value="0.2"/></pcr_rod>)";
  check_rejected(robot(cantilever), {"bad.urdf", "link 'platform'", "floating joint 'float'", "no pcr_rod"});
}

BOOST_AUTO_TEST_CASE(rejects_bad_urdf_trees) {
  const std::string cycle = R"(<link name="base"/><link name="a"/><link name="b"/>
<joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
<joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint>
)";
  check_rejected(robot("", cycle), {"bad.urdf", "cycle", "joint '"});
  const std::string two_roots = R"(<link name="base"/><link name="ground"/>)";
  check_rejected(robot("", two_roots), {"bad.urdf", "several root links", "'base'", "'ground'"});
  const std::string unknown_child = R"(<link name="base"/>
<joint name="j" type="fixed"><parent link="base"/><child link="ghost"/></joint>
)";
  check_rejected(robot("", unknown_child), {"bad.urdf", "joint 'j' <child>", "'link'", "\"ghost\""});
  const std::string planar = R"(<link name="base"/><link name="a"/>
<joint name="j" type="planar"><parent link="base"/><child link="a"/></joint>
)";
  check_rejected(robot("", planar), {"bad.urdf", "joint 'j'", "'type'", "\"planar\""});
  const std::string bad_limits = R"(<link name="base"/><link name="a"/>
<joint name="j" type="prismatic"><parent link="base"/><child link="a"/>
<limit lower="0.3" upper="0.1" effort="1" velocity="1"/></joint>
)";
  check_rejected(robot("", bad_limits),
                 {"bad.urdf", "joint 'j' <limit>", "'lower'", "\"0.3\"", "upper = 0.1"});
  // Values pcr uses are read by pcr, with the line, element and value.
  const std::string bad_origin = R"(<link name="base"/><link name="a"/>
<joint name="j" type="fixed"><parent link="base"/><child link="a"/><origin xyz="1 two 3"/></joint>
)";
  check_rejected(robot("", bad_origin), {"bad.urdf:4:", "joint 'j' <origin>", "'xyz'", "\"1 two 3\""});
  // Errors found by urdfdom itself (here in a part pcr does not use) are wrapped with the file name.
  const std::string bad_dynamics = R"(<link name="base"/><link name="a"/>
<joint name="j" type="fixed"><parent link="base"/><child link="a"/><dynamics damping="two"/></joint>
)";
  check_rejected(robot("", bad_dynamics), {"bad.urdf", "urdfdom"});
  check_rejected("<robot name=\"x\"><link name=\"base\"/>", {"bad.urdf", "XML error"});
  check_rejected("<model name=\"x\"/>", {"bad.urdf", "<robot>"});
}

BOOST_AUTO_TEST_CASE(rejects_ill_posed_rods) {
  RodXml rod;
  rod.start = R"(<start link="base" coupling="free"/>)";
  check_rejected(robot(rod.str()), {"bad.urdf", "pcr_rod 'r0' <start>", "'link'", "\"base\"", "free end"});
  rod.start = R"(<start coupling="free"/>)";
  rod.end = R"(<end coupling="free"/>)";
  check_rejected(robot(rod.str()),
                 {"bad.urdf", "pcr_rod 'r0'", "start = free, end = free", "clamp at least one"});
  rod.start = R"(<start link="base" coupling="collar"/>)";
  rod.end = R"(<end link="platform" coupling="collar"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0'", "start = collar, end = collar", "clamp at least one"});
  rod.start = R"(<start link="platform" coupling="clamped"/>)";
  rod.end = R"(<end link="platform" xyz="0.1 0 0" coupling="collar"/>)";
  check_rejected(robot(rod.str()), {"pcr_rod 'r0'", "both ends are on link 'platform'"});
}

BOOST_AUTO_TEST_CASE(rejects_platforms_not_held) {
  // Count: one rod with a spherical end puts 3 constraints on the platform.
  RodXml rod;
  rod.end = R"(<end link="platform" coupling="spherical"/>)";
  check_rejected(robot(rod.str()), {"bad.urdf", "platform 'platform'", "under-constrained",
                                    "pcr_rod 'r0' (end spherical)", "3"});
  // Only a free rod hangs from the platform: 0 constraints.
  RodXml hanging;
  hanging.start = R"(<start link="platform" coupling="clamped"/>)";
  hanging.end = R"(<end coupling="free"/>)";
  check_rejected(robot(hanging.str()),
                 {"platform 'platform'", "under-constrained", "pcr_rod 'r0' (start clamped)"});
  // Rank: two spherical ends give 6 constraints, but the platform still turns about the line through
  // the two points (the x axis through the platform origin): w = [+-1 0 0], v = 0.
  RodXml a, b;
  a.start = R"(<start link="base" xyz="-0.1 0 0" coupling="clamped"/>)";
  a.end = R"(<end link="platform" xyz="-0.1 0 0" coupling="spherical"/>)";
  b.name = "r1";
  b.start = R"(<start link="base" xyz="0.1 0 0" coupling="clamped"/>)";
  b.end = R"(<end link="platform" xyz="0.1 0 0" coupling="spherical"/>)";
  check_rejected(robot(a.str() + b.str()), {"bad.urdf", "platform 'platform'", "not held", "pcr_rod 'r0'",
                                            "pcr_rod 'r1'", "v = [0 0 0], w = [1 0 0]"});
  // Adding a third, non-collinear spherical end holds it.
  RodXml c = b;
  c.name = "r2";
  c.start = R"(<start link="base" xyz="0 0.1 0" coupling="clamped"/>)";
  c.end = R"(<end link="platform" xyz="0 0.1 0" coupling="spherical"/>)";
  BOOST_CHECK_NO_THROW(parse_robot_model(robot(a.str() + b.str() + c.str())));
}

BOOST_AUTO_TEST_CASE(rejects_misplaced_mass_and_loads) {
  check_rejected(robot(RodXml().str() + R"(<pcr_load link="base" force="0 0 -1"/>)"),
                 {"bad.urdf", "pcr_load", "'link'", "\"base\"", "not carried by a platform"});
  const std::string tree = kPlatformTree + R"(<link name="tool"><inertial><mass value="0.2"/>
<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
<joint name="mount" type="fixed"><parent link="platform"/><child link="tool"/></joint>
)";
  check_rejected(robot(RodXml().str(), tree), {"bad.urdf", "link 'tool'", "mass", "0.2", "platform"});
  check_rejected(robot(RodXml().str() + R"(<pcr_joint name="float" default="1"/>)"),
                 {"bad.urdf", "pcr_joint", "'name'", "\"float\"", "floating"});
}

BOOST_AUTO_TEST_CASE(nothing_half_loaded) {
  RobotModel m = load_robot_model(test::model_path("stewart_gough"));
  RodXml bad;
  bad.section = R"(<section type="circle" radius="-1"/>)";
  // The failed load throws before anything is assigned: the previous model is untouched.
  BOOST_CHECK_THROW(m = parse_robot_model(robot(bad.str())), InputError);
  BOOST_TEST(m.rods().size() == 6u);
  BOOST_TEST(m.rods()[5].name == "leg5");
  BOOST_CHECK_THROW(m = load_robot_model(test::model_path("no_such_model")), InputError);
  BOOST_TEST(m.platforms().size() == 1u);
  try {
    load_robot_model("/nonexistent/robot.urdf");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("/nonexistent/robot.urdf") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(rejects_bad_joint_defaults_and_input_names) {
  const std::string slider = kPlatformTree + R"(<link name="carriage"/>
<joint name="slide" type="prismatic"><parent link="base"/><child link="carriage"/>
  <axis xyz="0 0 1"/><limit lower="0.1" upper="0.2" effort="1" velocity="1"/></joint>
)";
  RodXml rod;
  rod.start = R"(<start link="carriage" coupling="clamped"/>)";
  // Without pcr_joint the default is the limit nearest to 0.
  const RobotModel m = parse_robot_model(robot(rod.str(), slider));
  BOOST_TEST(m.inputs()[m.input_index("slide")].default_value == 0.1);
  const RobotModel m2 =
      parse_robot_model(robot(rod.str() + R"(<pcr_joint name="slide" default="0.15"/>)", slider));
  BOOST_TEST(m2.inputs()[m2.input_index("slide")].default_value == 0.15);
  check_rejected(robot(rod.str() + R"(<pcr_joint name="slide" default="0.3"/>)", slider),
                 {"bad.urdf", "pcr_joint", "'default'", "\"0.3\"", "[0.1, 0.2]"});
  check_rejected(robot(rod.str() + R"(<pcr_joint name="slid" default="0.15"/>)", slider),
                 {"bad.urdf", "pcr_joint", "'name'", "\"slid\""});
  // An actuated rod named like an actuated joint: two inputs with one name.
  rod.name = "slide";
  rod.length = R"(<length value="0.3" actuated="true" lower="0.2" upper="0.4"/>)";
  check_rejected(robot(rod.str(), slider), {"bad.urdf", "actuation input name 'slide'"});
}
