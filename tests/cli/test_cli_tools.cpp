// The pcr tool's path and workspace commands, the JSON's input Jacobian and compliance, tool-link poses,
// partial targets (--components) and the refusal of targets with more rows than inputs, run as a program.
#define BOOST_TEST_MODULE cli_tools
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#define PCR_CLI_WORK_DIRECTORY "pcr_test_cli_tools"
#include "cli_runner.hpp"
#include "mini_json.hpp"

namespace {

/// Writes text to a file of the work directory; returns its path, quoted for the shell.
std::string write_file(const std::string& name, const std::string& text) {
  const fs::path path = work_directory() / name;
  std::ofstream(path) << text;
  return "'" + path.string() + "'";
}

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

/// Rows of planar_three_rod inputs near the defaults (0.3195, 0.2912, 0.3195 m), within the bounds.
const char* const kPlanarInputs =
    "# lengths [m]\nleft,middle,right\n0.3195,0.2912,0.3195\n0.3215,0.2902,0.3185\n0.3235,0.2892,0.3175\n";

}  // namespace

BOOST_AUTO_TEST_CASE(path_over_inputs_gives_fk_at_every_row) {
  const std::string inputs = write_file("planar_inputs.csv", kPlanarInputs);
  const fs::path csv = work_directory() / "path.csv";
  const Run run = run_pcr("path " + model("planar_three_rod.urdf") + " --inputs " + inputs +
                          " --json --csv '" + csv.string() + "'");
  BOOST_TEST_MESSAGE(run.err);
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  BOOST_CHECK(!contains(run.err, "\r"));  // no progress bar when stderr is not a terminal
  const test_json::Value j = test_json::parse(run.out);
  BOOST_CHECK_EQUAL(j["command"].text, "path");
  BOOST_CHECK_EQUAL(j["points"].number, 3);
  BOOST_CHECK_EQUAL(j["failures"].number, 0);
  BOOST_REQUIRE_EQUAL(j["results"].items.size(), 3u);
  const double middle[3] = {0.2912, 0.2902, 0.2892};
  for (size_t k = 0; k < 3; ++k) {
    const test_json::Value& point = j["results"][k];
    BOOST_CHECK_EQUAL(point["status"].text, "converged");
    BOOST_CHECK_EQUAL(point["inputs"]["middle"].number, middle[k]);
    // Each point as pcr fk solves it alone (cold, a separate process): the same equilibrium near the
    // defaults; 1e-9 m: both solves stop at dimensionless residuals below 1e-10, times the length scale
    // 0.3 m and a margin for the conditioning.
    const Run fk = run_pcr("fk " + model("planar_three_rod.urdf") + " --json --input left=" +
                           number(point["inputs"]["left"].number) + " --input middle=" + number(middle[k]) +
                           " --input right=" + number(point["inputs"]["right"].number));
    BOOST_REQUIRE_EQUAL(fk.exit_code, 0);
    const test_json::Value f = test_json::parse(fk.out);
    for (size_t c = 0; c < 3; ++c)
      BOOST_CHECK_SMALL(point["platforms"]["platform"]["position"][c].number -
                            f["platforms"]["platform"]["position"][c].number,
                        1e-9);
    BOOST_CHECK(point.has("input_jacobian") && point.has("compliance"));
  }
  // CSV: a header, one row per point, the inputs and the platform pose by name.
  std::istringstream lines(read_text(csv));
  std::string header, row;
  std::getline(lines, header);
  BOOST_CHECK(contains(header, "point,left,middle,right,platform.x,platform.y,platform.z,platform.qw"));
  BOOST_CHECK(contains(header, ",status,iterations,residual_max_abs,wall_time_seconds,message"));
  int rows = 0;
  while (std::getline(lines, row)) {
    ++rows;
    BOOST_CHECK(contains(row, ",converged,"));
  }
  BOOST_CHECK_EQUAL(rows, 3);
}

// With --stability the CSV carries each point's verdict after the message (stability, unstable_modes,
// stability_margin, stability_reason), the same as the JSON of the same run, and the table a column of it;
// without it, no such columns.
// planar_three_rod near its defaults: 1 unstable mode (the tilt out of the plane; test_stability_verdict).
BOOST_AUTO_TEST_CASE(path_csv_carries_the_stability_verdict) {
  const std::string inputs = write_file("planar_inputs_verdict.csv", kPlanarInputs);
  const fs::path csv = work_directory() / "path_verdict.csv";
  const Run run = run_pcr("path " + model("planar_three_rod.urdf") + " --inputs " + inputs +
                          " --stability --json --csv '" + csv.string() + "'");
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  const test_json::Value j = test_json::parse(run.out);
  std::istringstream lines(read_text(csv));
  std::string header, row;
  std::getline(lines, header);
  BOOST_CHECK(contains(header, ",message,stability,unstable_modes,stability_margin,stability_reason"));
  for (size_t k = 0; k < 3; ++k) {
    BOOST_REQUIRE(std::getline(lines, row));
    const test_json::Value& v = j["results"][k]["stability"];
    BOOST_CHECK_EQUAL(v["verdict"].text, "unstable");
    BOOST_CHECK_EQUAL(v["unstable_modes"].number, 1);
    BOOST_CHECK_MESSAGE(contains(row, ",unstable,1," + number(v["margin"].number)), row);
  }
  // The table on stdout: a stability column, "unstable (1)" on every point.
  const Run table =
      run_pcr("path " + model("planar_three_rod.urdf") + " --inputs " + inputs + " --stability");
  BOOST_REQUIRE_EQUAL(table.exit_code, 0);
  BOOST_CHECK_MESSAGE(contains(table.out, "[mm]  stability\n"), table.out);
  std::size_t unstable_points = 0;
  for (std::size_t at = table.out.find("unstable (1)\n"); at != std::string::npos;
       at = table.out.find("unstable (1)\n", at + 1))
    ++unstable_points;
  BOOST_CHECK_EQUAL(unstable_points, 3u);
  const Run plain = run_pcr("path " + model("planar_three_rod.urdf") + " --inputs " + inputs + " --csv '" +
                            csv.string() + "'");
  BOOST_REQUIRE_EQUAL(plain.exit_code, 0);
  std::istringstream plain_lines(read_text(csv));
  std::getline(plain_lines, header);
  BOOST_CHECK(!contains(header, "stability"));
}

BOOST_AUTO_TEST_CASE(path_inputs_not_in_the_file_take_input_options_or_defaults) {
  const std::string inputs = write_file("middle_only.csv", "middle\n0.2902\n");
  const Run run = run_pcr("path " + model("planar_three_rod.urdf") + " --inputs " + inputs +
                          " --input left=0.321 --json");
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  const test_json::Value point = test_json::parse(run.out)["results"][0];
  BOOST_CHECK_EQUAL(point["inputs"]["left"].number, 0.321);
  BOOST_CHECK_EQUAL(point["inputs"]["middle"].number, 0.2902);
  BOOST_CHECK_EQUAL(point["inputs"]["right"].number, 0.319530906173);  // the model's default
}

BOOST_AUTO_TEST_CASE(path_file_errors_name_the_file_line_and_column) {
  const std::string planar = model("planar_three_rod.urdf");
  const Run unknown =
      run_pcr("path " + planar + " --inputs " + write_file("bad1.csv", "left,middel\n0.3,0.29\n"));
  BOOST_CHECK_EQUAL(unknown.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(unknown.err, "middel") && contains(unknown.err, "left, middle, right"),
                      unknown.err);
  const Run bounds = run_pcr("path " + planar + " --inputs " + write_file("bad2.csv", "left\n0.3\n\n0.9\n"));
  BOOST_CHECK_EQUAL(bounds.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(bounds.err, "bad2.csv:4") && contains(bounds.err, "bounds"), bounds.err);
  const Run text = run_pcr("path " + planar + " --inputs " + write_file("bad3.csv", "left\n0.3x\n"));
  BOOST_CHECK_EQUAL(text.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(text.err, "bad3.csv:2") && contains(text.err, "0.3x"), text.err);
  const Run both = run_pcr("path " + planar + " --inputs a.csv --targets b.csv");
  BOOST_CHECK_EQUAL(both.exit_code, 2);
  const Run quaternion = run_pcr("path " + planar + " --targets " +
                                 write_file("bad4.csv", "platform.x,platform.qw,platform.qy\n0,1,0\n"));
  BOOST_CHECK_EQUAL(quaternion.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(quaternion.err, "part of a quaternion"), quaternion.err);
}

BOOST_AUTO_TEST_CASE(path_of_fk_poses_as_targets_gives_back_the_inputs) {
  // FK along input rows, then IK along the poses it reached: the in-plane components x, z (columns
  // without y) and the pitch ry (--components) on the 3-input planar robot.
  const std::string inputs = write_file("round_trip_inputs.csv", kPlanarInputs);
  const Run fk = run_pcr("path " + model("planar_three_rod.urdf") + " --inputs " + inputs + " --json");
  BOOST_REQUIRE_EQUAL(fk.exit_code, 0);
  const test_json::Value f = test_json::parse(fk.out);
  std::string targets = "platform.x,platform.z,platform.qw,platform.qx,platform.qy,platform.qz\n";
  for (const test_json::Value& point : f["results"].items) {
    const test_json::Value& p = point["platforms"]["platform"];
    targets += number(p["position"][0].number) + "," + number(p["position"][2].number);
    for (size_t k = 0; k < 4; ++k) targets += "," + number(p["quaternion_wxyz"][k].number);
    targets += "\n";
  }
  const Run ik =
      run_pcr("path " + model("planar_three_rod.urdf") + " --targets " +
              write_file("round_trip_targets.csv", targets) + " --components platform=x,z,ry --json");
  BOOST_TEST_MESSAGE(ik.err);
  BOOST_REQUIRE_EQUAL(ik.exit_code, 0);
  const test_json::Value i = test_json::parse(ik.out);
  BOOST_REQUIRE_EQUAL(i["results"].items.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const test_json::Value& point = i["results"][k];
    BOOST_CHECK_EQUAL(point["status"].text, "converged");
    const test_json::Value& components = point["targets"]["platform"]["components"];
    BOOST_REQUIRE_EQUAL(components.items.size(), 3u);
    BOOST_CHECK_EQUAL(components[0].text, "x");
    BOOST_CHECK_EQUAL(components[1].text, "z");
    BOOST_CHECK_EQUAL(components[2].text, "ry");
    // 1e-8 m: as ik_of_an_fk_pose_gives_back_the_fk_inputs (test_cli): residuals below 1e-10 times the
    // conditioning of the pose-to-input map and the length scale.
    for (const char* name : {"left", "middle", "right"})
      BOOST_CHECK_SMALL(point["inputs"][name].number - f["results"][k]["inputs"][name].number, 1e-8);
  }
}

BOOST_AUTO_TEST_CASE(path_with_an_unreachable_point_exits_1_and_keeps_every_point) {
  // 0.9 m above the base is out of reach (rods at most 0.8 m); the points around it are reachable.
  const std::string targets =
      write_file("unreachable.csv", "platform.x,platform.y,platform.z\n0,0,0.42\n0,0,0.9\n0,0,0.43\n");
  const Run run = run_pcr("path " + model("stewart_gough.urdf") + " --targets " + targets + " --json");
  BOOST_CHECK_EQUAL(run.exit_code, 1);
  BOOST_CHECK_MESSAGE(contains(run.err, "1 of 3 points failed") && contains(run.err, "point 1"), run.err);
  const test_json::Value j = test_json::parse(run.out);
  BOOST_REQUIRE_EQUAL(j["results"].items.size(), 3u);
  BOOST_CHECK_EQUAL(j["failures"].number, 1);
  BOOST_CHECK_EQUAL(j["results"][0]["status"].text, "converged");
  BOOST_CHECK_NE(j["results"][1]["status"].text, "converged");
  BOOST_CHECK_EQUAL(j["results"][2]["status"].text, "converged");
}

BOOST_AUTO_TEST_CASE(progress_bar_is_drawn_on_a_terminal) {
  if (std::system("command -v script > /dev/null 2>&1") != 0) {
    BOOST_TEST_MESSAGE("script (util-linux) not installed: the terminal case is not run");
    return;
  }
  // script runs the tool on a pseudo-terminal; its output (stdout and stderr) is what the terminal shows.
  const std::string inputs = write_file("bar_inputs.csv", kPlanarInputs);
  const std::string command =
      "'" + std::string(PCR_TOOL) + "' path " + model("planar_three_rod.urdf") + " --inputs " + inputs;
  const fs::path screen = work_directory() / "screen.txt";
  const int status =
      std::system(("script -qec \"" + command + "\" /dev/null > '" + screen.string() + "' 2>&1").c_str());
  BOOST_CHECK_EQUAL(status, 0);
  const std::string text = read_text(screen);
  BOOST_CHECK_MESSAGE(contains(text, "pcr path [") && contains(text, "] 3/3"), text);
}

BOOST_AUTO_TEST_CASE(workspace_samples_do_not_depend_on_the_threads) {
  const std::string slider = model("slider_actuated.urdf");
  const fs::path one = work_directory() / "ws1.csv", two = work_directory() / "ws2.csv";
  const Run a =
      run_pcr("workspace " + slider + " --samples 6 --seed 3 --threads 1 --csv '" + one.string() + "'");
  const Run b = run_pcr("workspace " + slider + " --samples 6 --seed 3 --threads 2 --csv '" + two.string() +
                        "' --json");
  BOOST_TEST_MESSAGE(a.err + b.err);
  BOOST_REQUIRE_EQUAL(a.exit_code, 0);
  BOOST_REQUIRE_EQUAL(b.exit_code, 0);
  BOOST_CHECK(contains(a.out, "6 samples (seed 3"));
  // Every CSV field but the wall time is the same, to the last digit (17 significant digits).
  auto without_time = [](const std::string& text) {
    std::istringstream lines(text);
    std::string line, out;
    while (std::getline(lines, line)) {
      std::vector<std::string> fields;
      std::string field;
      std::istringstream cells(line);
      while (std::getline(cells, field, ',')) fields.push_back(field);
      for (size_t c = 0; c < fields.size(); ++c)
        if (c != 14) out += fields[c] + ",";  // column 14: wall_time_seconds (header checked below)
      out += "\n";
    }
    return out;
  };
  const std::string csv1 = read_text(one), csv2 = read_text(two);
  BOOST_CHECK(
      contains(csv1,
               "sample,slider0,slider1,slider2,platform.x,platform.y,platform.z,platform.qw,platform.qx,"
               "platform.qy,platform.qz,status,iterations,residual_max_abs,wall_time_seconds,message"));
  BOOST_CHECK_EQUAL(std::count(csv1.begin(), csv1.end(), '\n'), 7);
  BOOST_CHECK_EQUAL(without_time(csv1), without_time(csv2));
  const test_json::Value j = test_json::parse(b.out);
  BOOST_CHECK_EQUAL(j["samples"].number, 6);
  BOOST_CHECK_EQUAL(j["seed"].number, 3);
  BOOST_CHECK_EQUAL(j["threads"].number, 2);
  BOOST_REQUIRE_EQUAL(j["points"].items.size(), 6u);
  int failed = 0;
  for (const test_json::Value& p : j["points"].items) {
    failed += p["status"].text == "converged" ? 0 : 1;
    BOOST_CHECK_EQUAL(p.has("platforms"), p["status"].text == "converged");
    for (size_t i = 0; i < 3; ++i) {  // slider travel [-0.05, 0.15] m
      BOOST_CHECK_GE(p["inputs"][i].number, -0.05);
      BOOST_CHECK_LE(p["inputs"][i].number, 0.15);
    }
  }
  BOOST_CHECK_EQUAL(j["failures"].number, failed);
  // Another seed, other inputs.
  const Run c = run_pcr("workspace " + slider + " --samples 1 --seed 4 --json");
  BOOST_CHECK_NE(test_json::parse(c.out)["points"][0]["inputs"][0].number,
                 j["points"][0]["inputs"][0].number);
}

// --stability: a verdict per converged sample in the CSV's last four columns, counted in the summary.
BOOST_AUTO_TEST_CASE(workspace_with_the_stability_verdict) {
  const fs::path csv = work_directory() / "ws_stability.csv";
  const Run run = run_pcr("workspace " + model("slider_actuated.urdf") + " --samples 3 --stability --csv '" +
                          csv.string() + "'");
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  // slider_actuated's samples within its bounds: all stable (its default state is, and no sample folds).
  BOOST_CHECK_MESSAGE(contains(run.out, "stability: 3 stable"), run.out);
  std::istringstream rows(read_text(csv));
  std::string header, row;
  std::getline(rows, header);
  const std::string tail = ",message,stability,unstable_modes,stability_margin,stability_reason";
  BOOST_CHECK_MESSAGE(
      header.size() > tail.size() && header.compare(header.size() - tail.size(), tail.size(), tail) == 0,
      header);
  int stable = 0;
  while (std::getline(rows, row)) stable += contains(row, ",stable,0,") ? 1 : 0;
  BOOST_CHECK_EQUAL(stable, 3);
}

BOOST_AUTO_TEST_CASE(workspace_usage_errors_and_picture) {
  const std::string slider = model("slider_actuated.urdf");
  BOOST_CHECK_EQUAL(run_pcr("workspace " + slider).exit_code, 2);  // no --samples
  BOOST_CHECK_EQUAL(run_pcr("workspace " + slider + " --samples 2 --solver ipopt").exit_code, 2);
  BOOST_CHECK_EQUAL(run_pcr("workspace " + slider + " --samples 2 --threads 0").exit_code, 2);
  BOOST_CHECK_EQUAL(run_pcr("workspace " + slider + " --samples 2 --seed -1").exit_code, 2);
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    BOOST_TEST_MESSAGE("gnuplot not installed: the --png case is not run");
    return;
  }
  const fs::path png = work_directory() / "workspace.png";
  const Run run = run_pcr("workspace " + slider + " --samples 4 --png '" + png.string() + "'");
  BOOST_TEST_MESSAGE(run.err);
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  BOOST_CHECK_EQUAL(read_text(png).substr(1, 3), "PNG");  // PNG signature: \x89 P N G
}

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
