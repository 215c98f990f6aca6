// Obstacles in the model format (<pcr_obstacle>, a rod's <contact>): parsing, the errors of bad input,
// and a robot with contact solved by forward and inverse kinematics.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;

namespace {

// A cantilever (as models/cantilever.urdf, 0.3 m) with `obstacles` after the rod and `contact` inside it.
std::string cantilever_xml(const std::string& obstacles, const std::string& contact,
                           const std::string& length = "0.3", const std::string& tip_force = "0 0 -0.1") {
  return R"(<?xml version="1.0"?>
<robot name="beam_on_floor">
  <link name="base"/>
  <pcr_gravity xyz="0 0 -9.81"/>
  <pcr_rod name="beam">
    <start link="base" xyz="0 0 0" rpy="0 1.570796326795 0" coupling="clamped"/>
    <end coupling="free" force=")" +
         tip_force + R"(" moment="0 0 0"/>
    <material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
    <section type="circle" radius="0.001"/>
    <length value=")" +
         length + R"("/>
    )" + contact +
         R"(
  </pcr_rod>
  )" + obstacles +
         R"(
</robot>)";
}

const std::string kFloor = R"(<pcr_obstacle name="floor" type="half_space" xyz="0 0 -0.02" normal="0 0 1"/>)";

// The InputError message of parsing xml, or "" when it parses.
std::string parse_error(const std::string& xml) {
  try {
    parse_robot_model(xml, "bad.urdf");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

BOOST_AUTO_TEST_CASE(obstacles_are_read_from_the_model) {
  const RobotModel m = parse_robot_model(cantilever_xml(kFloor + R"(
  <pcr_obstacle name="ball" type="sphere" link="base" xyz="0.1 0 -0.05" radius="0.02"/>
  <pcr_obstacle name="post" type="capsule" xyz="0.2 -0.01 -0.05" end="0.2 0.01 -0.05" radius="0.01"/>
  <pcr_obstacle name="drum" type="cylinder" xyz="0 0 -1" axis="0 1 0" radius="0.5"/>)",
                                                        R"(<contact obstacles="floor post"/>)"),
                                         "test.urdf");
  BOOST_TEST_REQUIRE(m.obstacles().size() == 4u);
  BOOST_TEST((m.obstacles()[0].obstacle.shape == ObstacleShape::HalfSpace));
  BOOST_TEST(m.obstacles()[0].link == -1);
  BOOST_TEST(m.obstacles()[1].link == m.link_index("base"));
  BOOST_TEST(m.obstacles()[2].obstacle.end.y() == 0.01);
  BOOST_TEST(m.obstacles()[3].obstacle.radius == 0.5);
  const RodElement& rod = m.rods()[0];
  BOOST_TEST(rod.obstacles == std::vector<int>({0, 2}), boost::test_tools::per_element());
  BOOST_TEST(rod.contact_radius == 0.001);  // the section's outer radius by default
  const RobotModel r =
      parse_robot_model(cantilever_xml(kFloor, R"(<contact obstacles="floor" radius="0.002"/>)"));
  BOOST_TEST(r.rods()[0].contact_radius == 0.002);
}

BOOST_AUTO_TEST_CASE(bad_obstacle_input_names_file_line_element_and_value) {
  struct Case {
    std::string obstacles, contact, expected;
  };
  const Case cases[] = {
      {kFloor, R"(<contact obstacles="floor wall"/>)",
       "attribute 'obstacles' = \"wall\" is not the name of a pcr_obstacle"},
      {kFloor, R"(<contact obstacles="floor" radius="-0.001"/>)", "attribute 'radius' = \"-0.001\""},
      {kFloor, R"(<contact obstacles="floor" radius="0"/>)", "attribute 'radius' = \"0\""},
      {kFloor, R"(<contact obstacles=""/>)", "names no obstacle"},
      {kFloor, R"(<contact obstacles="floor floor"/>)", "is named twice"},
      {R"(<pcr_obstacle name="floor" type="half_space" xyz="0 0 -0.02" normal="0 1 1"/>)", "",
       "pcr_obstacle 'floor': attribute 'normal' = \"0 1 1\" is not a unit vector"},
      {R"(<pcr_obstacle name="floor" type="half_space" xyz="0 0 -0.02" normal="0 0 0"/>)", "",
       "is not a unit vector"},
      {R"(<pcr_obstacle name="floor" type="half_space" xyz="0 nan -0.02" normal="0 0 1"/>)", "",
       "attribute 'xyz'"},
      {R"(<pcr_obstacle name="b" type="sphere" xyz="0 0 -1" radius="-2"/>)", "",
       "pcr_obstacle 'b': attribute 'radius' = \"-2\""},
      {R"(<pcr_obstacle name="b" type="sphere" xyz="0 0 -1" radius="nan"/>)", "",
       "attribute 'radius' = \"nan\""},
      {R"(<pcr_obstacle name="b" type="cone" xyz="0 0 -1" radius="1"/>)", "",
       "attribute 'type' = \"cone\" is not an obstacle type"},
      {R"(<pcr_obstacle name="b" type="sphere" link="arm" xyz="0 0 -1" radius="1"/>)", "",
       "attribute 'link' = \"arm\" is not a link"},
      {R"(<pcr_obstacle name="b" type="sphere" xyz="0 0 -1" radius="1" normal="0 0 1"/>)", "", "'normal'"},
      {R"(<pcr_obstacle name="c" type="capsule" xyz="0 0 -1" end="0 0 -1" radius="1"/>)", "",
       "is the same point as xyz"},
      {kFloor + kFloor, "", "is already used by the pcr_obstacle on line"},
  };
  for (const Case& c : cases) {
    const std::string message = parse_error(cantilever_xml(c.obstacles, c.contact));
    BOOST_TEST(message.find("bad.urdf:") == 0, message);
    BOOST_TEST(message.find(c.expected) != std::string::npos,
               "expected '" << c.expected << "' in: " << message);
  }
}

BOOST_AUTO_TEST_CASE(unsupported_contact_set_ups_are_rejected_by_the_assembly) {
  // A penetrating initial guess: the straight rod lies 0.5 mm above a floor (radius 1 mm).
  auto penetrating = std::make_shared<const RobotModel>(parse_robot_model(
      cantilever_xml(R"(<pcr_obstacle name="floor" type="half_space" xyz="0 0 -0.0005" normal="0 0 1"/>)",
                     R"(<contact obstacles="floor"/>)")));
  try {
    RobotAssembly assembly(penetrating);
    BOOST_FAIL("a penetrating initial guess was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("penetrates obstacle 'floor'") != std::string::npos, e.what());
  }
  // The primal form asked for by name.
  const std::string primal = cantilever_xml(kFloor, R"(<contact obstacles="floor"/>
    <discretization formulation="primal"/>)");
  BOOST_CHECK_THROW(RobotAssembly(std::make_shared<const RobotModel>(parse_robot_model(primal))), InputError);
}

BOOST_AUTO_TEST_CASE(heavy_cantilever_model_lies_on_its_floor) {
  // A 1 m rod under its weight with the floor's surface 2 mm below the clamp (1 mm below the lowest
  // fibre): the free tip sag q L^4 / (8 EI) = 0.2 m is stopped by the floor, the rod touches down near
  // (72 EI H / q)^(1/4) = 0.47 m (test_contact_references.cpp) and lies flat beyond: one interval to the
  // free end, the contact force up, the flat part at the floor (gap 0 to the solver tolerance 1e-10 L).
  // 32 elements: cells of 3 cm, so that the cells of the flat part that carry no force (rod_contact.hpp)
  // touch to within the 1e-6 L of the contact set.
  const std::string floor =
      R"(<pcr_obstacle name="floor" type="half_space" xyz="0 0 -0.002" normal="0 0 1"/>)";
  auto model = std::make_shared<const RobotModel>(
      parse_robot_model(cantilever_xml(floor, R"(<contact obstacles="floor"/>
    <discretization degree="4" elements="32"/>)",
                                       "1.0", "0 0 0")));
  ForwardKinematics fk(model);
  const RobotSolution s = fk.solve(VecX());
  BOOST_TEST_REQUIRE(s.summary.converged(), s.summary.message);
  BOOST_TEST_REQUIRE(s.contacts.size() == 1u);
  BOOST_TEST(s.contacts[0].rod == "beam");
  BOOST_TEST(s.contacts[0].obstacle == "floor");
  BOOST_TEST_REQUIRE(s.contacts[0].intervals.size() == 1u);
  BOOST_TEST(s.contacts[0].intervals[0].s_end == 1.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.contacts[0].intervals[0].s_begin > 0.4);
  BOOST_TEST(s.contacts[0].intervals[0].s_begin < 0.55);
  BOOST_TEST(s.contacts[0].force.z() > 0.0);
  BOOST_TEST(std::abs(s.rods[0].centerline.back().z() - (-0.001)) < 1e-9);
}

BOOST_AUTO_TEST_CASE(planar_post_model_fk_and_ik_with_contact) {
  // models/planar_post.urdf: the pre-curved middle rod bows onto the post. FK at moved
  // inputs, then IK back to the reached platform pose (x, z, ry: the planar robot's 3 inputs): the inputs
  // come back to within 1e-7 m (both solves end at residuals <= 1e-10 of well-conditioned systems; the
  // IK test of the other models (test_kinematics) uses the same bound), and the contact set is the same.
  auto model =
      std::make_shared<const RobotModel>(load_robot_model(std::string(PCR_MODEL_DIR) + "/planar_post.urdf"));
  ForwardKinematics fk(model);
  const RobotSolution at_default = fk.solve(model->default_input_values());
  BOOST_TEST_REQUIRE(at_default.summary.converged(), at_default.summary.message);
  BOOST_TEST_REQUIRE(at_default.contacts.size() == 1u);
  const ObstacleContact& c = at_default.contacts[0];
  BOOST_TEST(c.rod == "middle");
  BOOST_TEST(c.obstacle == "post");
  BOOST_TEST_REQUIRE(!c.intervals.empty());
  BOOST_TEST(c.force.x() < 0.0);  // the post, right of the rod, pushes it to the left
  // The centerline dips into the post between the midpoints (the gap is enforced at them only): by
  // 3e-5 m in this solve; bound 1e-4 m, 0.5 % of the post radius.
  BOOST_TEST(c.min_gap > -1e-4);

  // The results name the contact: a "contacts" member in the JSON, a line in the table.
  std::ostringstream json, table;
  BOOST_TEST(write_solution_json(json, *model, at_default) == 0);
  write_solution_table(table, *model, at_default);
  BOOST_TEST(json.str().find("\"contacts\": [") != std::string::npos, json.str());
  BOOST_TEST(json.str().find("\"obstacle\": \"post\"") != std::string::npos);
  BOOST_TEST(json.str().find("\"s_begin\"") != std::string::npos);
  BOOST_TEST(table.str().find("contact middle / post: [") != std::string::npos, table.str());

  VecX u = model->default_input_values();
  u += Vec3(0.001, 0.002, 0.001);  // a longer middle rod bows further onto the post
  const RobotSolution moved = fk.solve(u);
  BOOST_TEST_REQUIRE(moved.summary.converged(), moved.summary.message);
  BOOST_TEST_REQUIRE(!moved.contacts[0].intervals.empty());
  LinkTarget target;
  target.link = "platform";
  target.components = {{true, false, true, false, true, false}};
  InverseKinematics ik(model, {target});
  const RobotSolution back = ik.solve({moved.platforms[0]});
  BOOST_TEST_REQUIRE(back.summary.converged(), back.summary.message);
  for (int i = 0; i < 3; ++i) BOOST_TEST(std::abs(back.inputs[i] - u[i]) < 1e-7, "input " << i);
  BOOST_TEST_REQUIRE(back.contacts.size() == 1u);
  BOOST_TEST((back.contacts[0].force - moved.contacts[0].force).norm() <
             1e-6 * (1.0 + moved.contacts[0].force.norm()));
}

BOOST_AUTO_TEST_CASE(obstacles_on_links_fixed_to_the_world) {
  // A floor given in the frame of a link mounted upside down 0.5 m below the base by a fixed joint is the
  // world floor at z = -0.002: the same problem, so the same solution (to round-off, 1e-12 m).
  const std::string contact = R"(<contact obstacles="floor"/>
    <discretization degree="4" elements="32"/>)";
  const std::string world =
      R"(<pcr_obstacle name="floor" type="half_space" xyz="0 0 -0.002" normal="0 0 1"/>)";
  const std::string on_link = R"(<link name="table"/>
  <joint name="table_mount" type="fixed"><parent link="base"/><child link="table"/>
    <origin xyz="0 0 -0.5" rpy="3.141592653589793 0 0"/></joint>
  <pcr_obstacle name="floor" type="half_space" link="table" xyz="0.1 0 -0.498" normal="0 0 -1"/>)";
  ForwardKinematics a(
      std::make_shared<const RobotModel>(parse_robot_model(cantilever_xml(world, contact, "1.0", "0 0 0"))));
  ForwardKinematics b(std::make_shared<const RobotModel>(
      parse_robot_model(cantilever_xml(on_link, contact, "1.0", "0 0 0"))));
  const RobotSolution sa = a.solve(VecX()), sb = b.solve(VecX());
  BOOST_TEST_REQUIRE(sa.summary.converged());
  BOOST_TEST_REQUIRE(sb.summary.converged());
  for (size_t i = 0; i < sa.rods[0].centerline.size(); ++i)
    BOOST_TEST((sa.rods[0].centerline[i] - sb.rods[0].centerline[i]).norm() < 1e-12);

  // A concentrated contact with an obstacle on a moving link (the platform) is rejected: its reaction on
  // the platform is not modelled (distributed contact is: tests/robots/test_moving_obstacles.cpp).
  std::string xml = test::model_text("planar_post");
  const std::string post = R"(<pcr_obstacle name="post" type="capsule")";
  BOOST_TEST_REQUIRE(xml.find(post) != std::string::npos);
  xml.replace(xml.find(post), post.size(),
              R"(<pcr_obstacle name="post" type="capsule" contact="point" link="platform")");
  try {
    RobotAssembly assembly(std::make_shared<const RobotModel>(parse_robot_model(xml)));
    BOOST_FAIL("an obstacle on a moving link was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(
        std::string(e.what()).find("obstacle 'post' on link 'platform': the link moves") != std::string::npos,
        e.what());
  }
}
