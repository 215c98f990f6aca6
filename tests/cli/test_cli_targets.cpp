// The pcr tool run as a program: the JSON's input Jacobian and compliance, tool-link poses, partial
// targets (--components) and the refusal of targets with more rows than inputs.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#define PCR_CLI_WORK_DIRECTORY "pcr_test_cli_targets"
#include "cli_runner.hpp"
#include "mini_json.hpp"

namespace {

/// R(q) e for a unit quaternion q = [w, x, y, z] (written out, independent of the library).
std::vector<double> rotate(const test_json::Value& q, const std::vector<double>& e) {
  const double w = q[0].number, x = q[1].number, y = q[2].number, z = q[3].number;
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  std::vector<double> out(3, 0.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i] += R[i][j] * e[j];
  return out;
}

/// The planar robot with a tool link fixed to its platform 30 mm along x, 50 mm below, pitched by 0.4 rad.
std::string planar_with_tool() {
  std::string text = read_text(fs::path(PCR_MODEL_DIR) / "planar_three_rod.urdf");
  const size_t end = text.rfind("</robot>");
  text.insert(
      end,
      "  <link name=\"tool\"/>\n  <joint name=\"tool_mount\" type=\"fixed\">\n    <parent link=\"platform\"/>"
      "<child link=\"tool\"/>\n    <origin xyz=\"0.03 0 -0.05\" rpy=\"0 0.4 0\"/>\n  </joint>\n");
  return write_file("planar_with_tool.urdf", text);
}

}  // namespace

BOOST_AUTO_TEST_CASE(fk_json_input_jacobian_matches_finite_differences) {
  // Central differences of two more FK runs, input 'middle' +- h, h = 1e-5 m: truncation O(h^2) ~ 1e-10,
  // solver noise (residuals below 1e-10 times the 0.3 m length scale) / h ~ 3e-6; checked to 1e-4.
  const double left = 0.3195, middle = 0.2912, right = 0.3195, h = 1e-5;
  auto fk = [&](double m) {
    const Run run = run_pcr("fk " + model("planar_three_rod.urdf") + " --json --input left=" + number(left) +
                            " --input middle=" + number(m) + " --input right=" + number(right));
    BOOST_REQUIRE_EQUAL(run.exit_code, 0);
    return test_json::parse(run.out);
  };
  const test_json::Value at = fk(middle), plus = fk(middle + h), minus = fk(middle - h);
  const test_json::Value& J = at["input_jacobian"]["platform"];
  BOOST_REQUIRE_EQUAL(J.items.size(), 6u);
  BOOST_REQUIRE_EQUAL(J[0].items.size(), 3u);  // one column per input: left, middle, right
  for (size_t row : {0u, 2u}) {                // x and z [m/m]
    const double fd = (plus["platforms"]["platform"]["position"][row].number -
                       minus["platforms"]["platform"]["position"][row].number) /
                      (2 * h);
    BOOST_CHECK_SMALL(J[row][1].number - fd, 1e-4);
  }
  // In-plane rotation about y: angle 2 atan2(q_y, q_w) [rad/m].
  auto pitch = [](const test_json::Value& j) {
    const test_json::Value& q = j["platforms"]["platform"]["quaternion_wxyz"];
    return 2 * std::atan2(q[2].number, q[0].number);
  };
  BOOST_CHECK_SMALL(J[4][1].number - (pitch(plus) - pitch(minus)) / (2 * h),
                    1e-4 * std::abs(J[4][1].number) + 1e-4);
  // Compliance 6 x 6. The in-plane pitch compliance d theta_y / d torque_y against the rigid pin-jointed
  // model (rods as axial springs EA / L, closed form in test_singular_poses): 0.00284 rad/(N m) at the
  // default inputs, which the elastic rods exceed by 5 % as they sag under their weight
  // (docs/benchmarks.md, "Nearly singular platform poses"); these inputs are within 3e-5 m of the
  // defaults. 10 %: that 5 % and as much again.
  const test_json::Value& C = at["compliance"]["platform"];
  BOOST_REQUIRE_EQUAL(C.items.size(), 6u);
  for (size_t k = 0; k < 6; ++k) BOOST_REQUIRE_EQUAL(C[k].items.size(), 6u);
  BOOST_CHECK_CLOSE_FRACTION(C[4][4].number, 0.00284, 0.1);
  BOOST_CHECK_GT(C[0][0].number, 0.0);  // in-plane translations yield along the force
  BOOST_CHECK_GT(C[2][2].number, 0.0);
}

BOOST_AUTO_TEST_CASE(tool_link_poses_are_reported_and_reached) {
  const std::string robot = planar_with_tool();
  const Run fk = run_pcr("fk " + robot +
                         " --json --link tool --input left=0.3215 --input middle=0.2902 "
                         "--input right=0.3185");
  BOOST_TEST_MESSAGE(fk.err);
  BOOST_REQUIRE_EQUAL(fk.exit_code, 0);
  const test_json::Value f = test_json::parse(fk.out);
  const test_json::Value& platform = f["platforms"]["platform"];
  const test_json::Value& tool = f["links"]["tool"];
  // The tool's origin is the platform's pose applied to the mount offset (0.03, 0, -0.05) m; 1e-15 m:
  // round-off of one rotation.
  const std::vector<double> arm = rotate(platform["quaternion_wxyz"], {0.03, 0.0, -0.05});
  for (size_t c = 0; c < 3; ++c)
    BOOST_CHECK_SMALL(tool["position"][c].number - platform["position"][c].number - arm[c], 1e-15);
  // IK to that tool pose (its in-plane components: 3 rows for 3 inputs) reaches it and reports it.
  std::string target = "tool=";
  for (size_t k = 0; k < 3; ++k) target += number(tool["position"][k].number) + ",";
  for (size_t k = 0; k < 4; ++k) target += number(tool["quaternion_wxyz"][k].number) + (k < 3 ? "," : "");
  const Run ik = run_pcr("ik " + robot + " --json --target " + target + " --components tool=x,z,ry");
  BOOST_TEST_MESSAGE(ik.err);
  BOOST_REQUIRE_EQUAL(ik.exit_code, 0);
  const test_json::Value i = test_json::parse(ik.out);
  const test_json::Value& reached = i["links"]["tool"];
  const test_json::Value& report = i["targets"]["tool"];
  // 1e-9 m: residuals below 1e-10 times the 0.3 m length scale, with margin.
  for (size_t c = 0; c < 3; ++c) {
    BOOST_CHECK_SMALL(reached["position"][c].number - tool["position"][c].number, 1e-9);
    BOOST_CHECK_EQUAL(report["reached_position"][c].number, reached["position"][c].number);
  }
  BOOST_CHECK_SMALL(report["position_error"].number, 1e-9);
  BOOST_CHECK_SMALL(report["orientation_error"].number, 1e-8);
  for (const char* name : {"left", "middle", "right"})  // 1e-8 m as in the round trips above
    BOOST_CHECK_SMALL(i["inputs"][name].number - f["inputs"][name].number, 1e-8);
  // The table lists the tool under "links:", apart from the platform.
  const Run table = run_pcr("ik " + robot + " --target " + target + " --components tool=x,z,ry");
  BOOST_REQUIRE_EQUAL(table.exit_code, 0);
  BOOST_CHECK_MESSAGE(contains(table.out, "links:") && contains(table.out, "  tool "), table.out);
  BOOST_CHECK_EQUAL(run_pcr("fk " + robot + " --link nolink").exit_code, 2);
}

BOOST_AUTO_TEST_CASE(targets_with_more_rows_than_inputs_are_refused_naming_the_counts) {
  const Run run = run_pcr("ik " + model("planar_three_rod.urdf") + " --target platform=0,0,0.3,1,0,0,0");
  BOOST_CHECK_EQUAL(run.exit_code, 2);
  BOOST_CHECK(run.out.empty());
  // The counts, and what the inputs can meet at the reference inputs: the in-plane x, z and pitch ry.
  BOOST_CHECK_MESSAGE(contains(run.err, "6 rows") && contains(run.err, "3 inputs"), run.err);
  BOOST_CHECK_MESSAGE(contains(run.err, "--components platform=x,z,ry"), run.err);
  BOOST_CHECK_MESSAGE(!contains(run.err, "no solution"), run.err);  // refused before any IK solve
  const std::string pose_columns =
      "platform.x,platform.y,platform.z,platform.qw,platform.qx,platform.qy,platform.qz\n";
  const Run path = run_pcr("path " + model("planar_three_rod.urdf") + " --targets " +
                           write_file("too_many.csv", pose_columns + "0,0,0.3,1,0,0,0\n"));
  BOOST_CHECK_EQUAL(path.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(path.err, "6 rows") && contains(path.err, "--components platform=x,z,ry"),
                      path.err);
  const Run rows = run_pcr("path " + model("slider_actuated.urdf") + " --targets " +
                           write_file("four_rows.csv", pose_columns + "0,0,0.42,1,0,0,0\n") +
                           " --components platform=x,y,z,rz");
  BOOST_CHECK_EQUAL(rows.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(rows.err, "4 rows") && contains(rows.err, "3 inputs"), rows.err);
}

BOOST_AUTO_TEST_CASE(partial_orientation_targets_meet_the_selected_components) {
  // Stewart-Gough: position and tilt (rx, ry) of the pose that FK reaches with leg0 at 0.47 m, free
  // rotation about the platform's z axis: 5 rows for 6 inputs.
  const Run fk = run_pcr("fk " + model("stewart_gough.urdf") + " --json --input leg0=0.47");
  BOOST_REQUIRE_EQUAL(fk.exit_code, 0);
  const test_json::Value f = test_json::parse(fk.out);
  const test_json::Value& pose = f["platforms"]["platform"];
  std::string target = "platform=";
  for (size_t k = 0; k < 3; ++k) target += number(pose["position"][k].number) + ",";
  for (size_t k = 0; k < 4; ++k) target += number(pose["quaternion_wxyz"][k].number) + (k < 3 ? "," : "");
  const Run ik = run_pcr("ik " + model("stewart_gough.urdf") + " --json --target " + target +
                         " --components platform=x,y,z,rx,ry");
  BOOST_TEST_MESSAGE(ik.err);
  BOOST_REQUIRE_EQUAL(ik.exit_code, 0);
  const test_json::Value i = test_json::parse(ik.out);
  const test_json::Value& reached = i["platforms"]["platform"];
  // Position and the platform's z axis R e_z match (rx = ry = 0 leaves only a rotation about z):
  // 1e-8 (m, and the axis' components): the reduced-space target tolerance 1e-9 times the length scale,
  // with margin.
  const std::vector<double> axis = rotate(reached["quaternion_wxyz"], {0, 0, 1}),
                            wanted = rotate(pose["quaternion_wxyz"], {0, 0, 1});
  for (size_t c = 0; c < 3; ++c) {
    BOOST_CHECK_SMALL(reached["position"][c].number - pose["position"][c].number, 1e-8);
    BOOST_CHECK_SMALL(axis[c] - wanted[c], 1e-8);
  }
  // Components that a target's mode lacks, unknown names and links without a target are usage errors.
  const std::string stewart = model("stewart_gough.urdf");
  BOOST_CHECK_EQUAL(
      run_pcr("ik " + stewart + " --target platform=0,0,0.4 --components platform=x,rx").exit_code, 2);
  BOOST_CHECK_EQUAL(
      run_pcr("ik " + stewart + " --target platform=0,0,0.4 --components platform=x,w").exit_code, 2);
  BOOST_CHECK_EQUAL(run_pcr("ik " + stewart + " --target platform=0,0,0.4 --components base=x").exit_code, 2);
  const Run tilt = run_pcr("ik " + stewart + " --orientation-only platform=1,0,0,0 --components platform=x");
  BOOST_CHECK_EQUAL(tilt.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(tilt.err, "has no position"), tilt.err);
}
