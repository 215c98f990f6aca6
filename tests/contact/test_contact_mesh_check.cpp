// Contact that the mesh does not resolve is reported, never silently accepted: the gap sampled densely
// along each contact rod (RobotSolution::contact_gaps) and the penetration warning in the summary, the
// JSON and the table (docs/contact.md, "Penetration check").
#define BOOST_TEST_MODULE contact_edges
#include <boost/test/unit_test.hpp>

#include <memory>
#include <sstream>
#include <string>

#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"
#include "robot_fixtures.hpp"

using namespace pcr;

namespace {

// models/planar_post.urdf with its middle rod meshed by `elements` elements, solved by FK at the default
// inputs.
RobotSolution planar_post_with(int elements, std::shared_ptr<const RobotModel>& model, bool point = false) {
  std::string xml = test::model_text("planar_post");
  const std::string mesh = R"(elements="24")";
  BOOST_TEST_REQUIRE(xml.find(mesh) != std::string::npos);
  xml.replace(xml.find(mesh), mesh.size(), "elements=\"" + std::to_string(elements) + "\"");
  const std::string post = R"(radius="0.02"/>)";
  BOOST_TEST_REQUIRE(xml.find(post) != std::string::npos);
  if (point) xml.replace(xml.find(post), post.size(), R"(radius="0.02" contact="point"/>)");
  model = std::make_shared<const RobotModel>(parse_robot_model(xml, "planar_post.urdf"));
  ForwardKinematics fk(model);
  return fk.solve(model->default_input_values());
}

}  // namespace

BOOST_AUTO_TEST_CASE(penetration_between_midpoints_is_reported_on_a_coarse_mesh) {
  // The post has radius 20 mm, the rod's contact radius is 0.5 mm (the section's): tolerance
  // 0.1 x 0.5 mm (kPenetrationTolerance). With 8 elements the midpoints are ~3 cm apart, more than the
  // post's contact arc: the discrete solve converges while the centerline passes 3 mm into the post between
  // two midpoints. With the model's 24 elements the dip is 0.03 mm, within the tolerance.
  std::shared_ptr<const RobotModel> model;
  const RobotSolution coarse = planar_post_with(8, model);
  BOOST_TEST_REQUIRE(coarse.summary.converged(), coarse.summary.message);
  BOOST_TEST_REQUIRE(coarse.contact_gaps.size() == 1u);
  const RodContactGap& g = coarse.contact_gaps[0];
  BOOST_TEST(g.rod == "middle");
  BOOST_TEST(g.obstacle == "post");
  BOOST_TEST(g.tolerance == 0.1 * 0.0005, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(g.min_gap < -1e-3);  // a visible dip, 2 x the rod's radius and more
  BOOST_TEST(g.penetrates());
  BOOST_TEST(g.arc_length > 0.12);  // where the rod lies on the post (s = 0.15 m on the fine mesh)
  BOOST_TEST(g.arc_length < 0.18);
  BOOST_TEST(
      coarse.summary.message.find("warning: rod 'middle' penetrates obstacle 'post'") != std::string::npos,
      coarse.summary.message);
  BOOST_TEST(coarse.summary.message.find("more elements") != std::string::npos);
  std::ostringstream json, table;
  BOOST_TEST(write_solution_json(json, *model, coarse) == 0);
  write_solution_table(table, *model, coarse);
  BOOST_TEST(json.str().find("\"contact_gaps\": [") != std::string::npos, json.str());
  BOOST_TEST(json.str().find("\"penetrates\": true") != std::string::npos);
  BOOST_TEST(table.str().find("warning: rod 'middle' penetrates obstacle 'post'") != std::string::npos,
             table.str());

  const RobotSolution fine = planar_post_with(24, model);
  BOOST_TEST_REQUIRE(fine.summary.converged(), fine.summary.message);
  BOOST_TEST_REQUIRE(fine.contact_gaps.size() == 1u);
  BOOST_TEST(!fine.contact_gaps[0].penetrates(), fine.contact_gaps[0].min_gap);
  BOOST_TEST(fine.contact_gaps[0].min_gap > -0.1 * 0.0005);
  BOOST_TEST(fine.summary.message.find("penetrates") == std::string::npos, fine.summary.message);
  std::ostringstream fine_table;
  write_solution_table(fine_table, *model, fine);
  BOOST_TEST(fine_table.str().find("contact gap middle: min ") != std::string::npos, fine_table.str());
  BOOST_TEST(fine_table.str().find("warning:") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(point_contact_on_the_post_needs_no_fine_mesh) {
  // The pre-curved middle rod (radius of curvature 0.5 m) touches the post (radius 20 mm) at one point:
  // with contact="point" that section is an unknown, so even 8 elements hold the gap there, and the
  // rest of the rod stays clear (no penetration at all, to the solver tolerance 1e-10 L). The contact
  // section agrees with that of 24 elements to within one 24-element cell (the resolution of a
  // concentrated force, docs/contact.md), and the force is normal to the post: along the arm from its
  // axis (the line y through x = -0.0147, z = 0.1436) to the contact point.
  std::shared_ptr<const RobotModel> model;
  const RobotSolution coarse = planar_post_with(8, model, true), fine = planar_post_with(24, model, true);
  for (const RobotSolution* s : {&coarse, &fine}) {
    BOOST_TEST_REQUIRE(s->summary.converged(), s->summary.message);
    BOOST_TEST_REQUIRE(s->contacts.size() == 1u);
    const ObstacleContact& c = s->contacts[0];
    BOOST_TEST(c.concentrated);
    BOOST_TEST_REQUIRE(c.intervals.size() == 1u);
    BOOST_TEST(!s->contact_gaps[0].penetrates());
    BOOST_TEST(c.min_gap >= -1e-10 * 0.291);
    BOOST_TEST(s->summary.message.find("penetrates") == std::string::npos);
  }
  const double h = 0.291204395571 / 24;
  BOOST_TEST(std::abs(coarse.contacts[0].intervals[0].centroid - fine.contacts[0].intervals[0].centroid) <=
             h);
  // The contact point from the 21 result points by linear interpolation: the chord departs from the rod
  // by at most kappa h^2 / 8 = 5e-5 m (kappa = 2 1/m, h = 14.6 mm), 2.5e-3 of the arm R + r = 20.5 mm;
  // bound on the sine of the angle between arm and force: 0.02.
  const ObstacleContact& c = fine.contacts[0];
  const std::vector<Vec3>& line = fine.rods[1].centerline;
  const double s = c.intervals[0].centroid * (line.size() - 1) / fine.rods[1].length;
  const int i = static_cast<int>(s);
  const Vec3 p = line[i] + (s - i) * (line[i + 1] - line[i]);
  const Vec3 arm = Vec3(p.x() + 0.0147, 0.0, p.z() - 0.1436);
  BOOST_TEST(std::abs(arm.normalized().cross(c.force.normalized()).y()) < 0.02);
}
