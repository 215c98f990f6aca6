// Joint models the loader checks: the rank check's constraint counts (universal 4, revolute 5), a
// spring-less hinge that nothing holds rejected, and malformed joint input rejected with file, line,
// element and value.
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/math/dense_decompositions.hpp"
#include "pcr/robots/platform_hold_check.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;
using test::kSteel;
using test::load_model;
using test::model_text;

namespace {

/// Parses xml (as `source`) expecting an InputError whose message holds "source:line" (the line of the
/// first occurrence of `at` in xml) and every one of `parts`.
void check_rejected(const std::string& xml, const std::string& source, const std::string& at,
                    const std::vector<std::string>& parts) {
  const size_t pos = xml.find(at);
  BOOST_REQUIRE_MESSAGE(pos != std::string::npos, "'" << at << "' not in the model");
  const int line = 1 + static_cast<int>(std::count(xml.begin(), xml.begin() + static_cast<long>(pos), '\n'));
  try {
    parse_robot_model(xml, source);
    BOOST_ERROR(source << ": accepted");
  } catch (const InputError& e) {
    const std::string what = e.what();
    BOOST_TEST(what.find(source + ":" + std::to_string(line) + ":") != std::string::npos,
               line << " not in: " << what);
    for (const std::string& part : parts)
      BOOST_TEST(what.find(part) != std::string::npos, "'" << part << "' not in: " << what);
  }
}

/// xml with the first occurrence of `from` replaced by `to` (which must occur).
std::string edited(std::string xml, const std::string& from, const std::string& to) {
  const size_t pos = xml.find(from);
  BOOST_REQUIRE_MESSAGE(pos != std::string::npos, "'" << from << "' not in the model");
  return xml.replace(pos, from.size(), to);
}

std::string one_rod(const std::string& start, const std::string& end) {
  return std::string(R"(<?xml version="1.0"?>
<robot name="one_rod">
  <link name="base"/>
  <link name="top"/>
  <joint name="top_fixed" type="fixed"><parent link="base"/><child link="top"/><origin xyz="0 0 0.3" rpy="0 0 0"/></joint>
  <pcr_rod name="hanging">
    )") + start +
         "\n    " + end + "\n    " + kSteel +
         R"(
    <section type="circle" radius="0.001"/>
    <length value="0.3"/>
  </pcr_rod>
</robot>
)";
}

}  // namespace

BOOST_AUTO_TEST_CASE(rank_check_counts_universal_4_and_revolute_5_constraints) {
  BOOST_TEST(kinematic_constraint_count(RodEndKind::Universal) == 4);
  BOOST_TEST(kinematic_constraint_count(RodEndKind::Revolute) == 5);
  // Rows: both couplings of a rod without a clamped end, the other coupling of a clamped rod. Columns:
  // the platform (6), each spring-less passive joint (1), each rod without a clamped end (6). Each model
  // is held: full column rank.
  struct Case {
    const char* model;
    int rows, columns;
  };
  for (const Case& c :
       {Case{"planar_pinned", 3 * (5 + 5), 6 + 3 * 6}, Case{"universal_pair", 6 * (4 + 3), 6 + 6 * 6},
        Case{"universal_passive", 6 * 3, 6 + 6 * 2}, Case{"passive_hinge", 3 * 3, 6}}) {
    const auto model = load_model(c.model);
    const MatX C =
        coupling_constraint_matrix(*model, model->default_joint_values(), model->initial_platform_poses());
    BOOST_TEST(C.rows() == c.rows, c.model);
    BOOST_TEST(C.cols() == c.columns, c.model);
    const VecX sigma = singular_values(C);
    // Held: the smallest singular value is a lever-arm ratio, far above round-off (1e-16 of the largest).
    BOOST_TEST(sigma.minCoeff() > 1e-3 * sigma.maxCoeff(), c.model);
  }
  // One rod pinned at both ends holds a platform by 10 constraints: 12 motions, so it is rejected.
  std::string one = model_text("planar_pinned");
  for (const char* rod : {"middle", "right"}) {
    const size_t from = one.find(std::string("<pcr_rod name=\"") + rod + "\"");
    one.erase(from, one.find("</pcr_rod>", from) + 10 - from);
  }
  try {
    parse_robot_model(one, "one_pinned_rod.urdf");
    BOOST_ERROR("accepted");
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find("platform 'platform'") != std::string::npos, e.what());
  }
}

BOOST_AUTO_TEST_CASE(a_spring_less_hinge_carrying_only_a_rod_pinned_on_its_axis_is_rejected) {
  // planar_pinned with the middle rod's base pin on a link that turns about the pin's own line (a passive
  // hinge without spring): the hinge is a free motion of the rigid-rod rank check.
  std::string xml = model_text("planar_pinned");
  const std::string base_pin = R"(<start link="base" xyz="-0.08 0 0" rpy="0 0.278299659005 0")";
  xml.replace(xml.find(base_pin), base_pin.size(), R"(<start link="hinge" rpy="0 0.278299659005 0")");
  xml.replace(xml.find("<pcr_gravity"), 12, R"(<link name="hinge"/>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="hinge"/><origin xyz="-0.08 0 0" rpy="0 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="0" velocity="1"/></joint>
  <pcr_joint name="hinge" passive="true"/>
  <pcr_gravity)");
  try {
    parse_robot_model(xml, "pinned_hinge.urdf");
    BOOST_ERROR("accepted");
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const char* part :
         {"pinned_hinge.urdf", "passive joint 'hinge'", "pcr_rod 'middle'", "free to move"})
      BOOST_TEST(what.find(part) != std::string::npos, "'" << part << "' not in: " << what);
  }
  // With a spring it is held.
  const std::string spring = R"(<pcr_joint name="hinge" passive="true"/>)";
  xml.replace(xml.find(spring), spring.size(), R"(<pcr_joint name="hinge" passive="true" stiffness="0.1"/>)");
  BOOST_CHECK_NO_THROW(parse_robot_model(xml, "pinned_hinge.urdf"));
}

BOOST_AUTO_TEST_CASE(malformed_joint_input_is_rejected_with_file_line_element_and_value) {
  const std::string pinned = model_text("planar_pinned"), pair = model_text("universal_pair"),
                    hinge = model_text("passive_hinge");
  const std::string leg0 = R"(coupling="universal" axis="1 0 0")";
  check_rejected(edited(pair, leg0, R"(coupling="universal" axis="1 x 0")"), "u.urdf", "axis=\"1 x 0\"",
                 {"pcr_rod 'leg0' <start>", "'axis' = \"1 x 0\""});
  check_rejected(edited(pair, leg0, R"(coupling="universal" axis="0 0 2")"), "u.urdf", "axis=\"0 0 2\"",
                 {"pcr_rod 'leg0' <start>", "'axis' = \"0 0 2\"", "along the attachment z axis"});
  const std::string pin = R"(coupling="revolute" axis="0 1 0")";
  check_rejected(edited(pinned, pin, R"(coupling="revolute" axis="0 0 0")"), "p.urdf", "axis=\"0 0 0\"",
                 {"pcr_rod 'left' <start>", "'axis' = \"0 0 0\"", "zero"});
  check_rejected(edited(pinned, pin, R"(coupling="revolute" axis="0 1 0" axes="1 0 0")"), "p.urdf",
                 "axes=", {"pcr_rod 'left' <start>", "'axes' = \"1 0 0\""});
  check_rejected(edited(hinge, R"(coupling="spherical"/>)", R"(coupling="spherical" axis="1 0 0"/>)"),
                 "h.urdf", R"(coupling="spherical" axis)",
                 {"pcr_rod 'left' <end>", "'axis' = \"1 0 0\"", "only allowed"});
  // Collars or spherical joints at both ends, or a pin along the rod, leave its twist free.
  std::string collars = pinned;
  for (int i = 0; i < 2; ++i) collars = edited(collars, pin, R"(coupling="collar")");
  check_rejected(collars, "c.urdf", "<pcr_rod name=\"left\"",
                 {"pcr_rod 'left'", "start = collar, end = collar", "twist"});
  check_rejected(one_rod(R"(<start link="base" coupling="spherical"/>)",
                         R"(<end link="top" coupling="revolute" axis="0 0 1"/>)"),
                 "s.urdf", "<pcr_rod", {"pcr_rod 'hanging'", "start = spherical, end = revolute", "twist"});
  // A universal end with no link (a free end), or with the other end free (a pendulum).
  check_rejected(one_rod(R"(<start link="base" coupling="clamped"/>)", R"(<end coupling="universal"/>)"),
                 "f.urdf", "<end", {"pcr_rod 'hanging' <end>", "'link'"});
  check_rejected(
      one_rod(R"(<start link="base" coupling="universal" axis="0 1 0"/>)", R"(<end coupling="free"/>)"),
      "f.urdf", "<pcr_rod", {"pcr_rod 'hanging'", "start = universal, end = free", "rigid body"});
  // A passive joint with nothing beyond it, a negative spring, a spring on an input joint.
  const std::string lonely = R"(<link name="idle"/>
  <joint name="idle_joint" type="revolute"><parent link="base"/><child link="idle"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="0" velocity="1"/></joint>
  <pcr_joint name="idle_joint" passive="true" stiffness="0.1"/>
  <pcr_gravity)";
  check_rejected(edited(hinge, "<pcr_gravity", lonely), "h.urdf", "<pcr_joint name=\"idle_joint\"",
                 {"pcr_joint", "'name' = \"idle_joint\"", "nothing attached beyond it", "'idle'"});
  check_rejected(edited(hinge, R"(stiffness="0.5")", R"(stiffness="-0.5")"), "h.urdf", "stiffness=\"-0.5\"",
                 {"pcr_joint", "'stiffness' = \"-0.5\""});
  check_rejected(
      edited(hinge, R"(passive="true" stiffness="0.5" rest="0")", R"(default="0.1" stiffness="0.5")"),
      "h.urdf", "default=\"0.1\"", {"pcr_joint", "'stiffness' = \"0.5\"", "passive"});
}
