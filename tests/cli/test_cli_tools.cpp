// The pcr tool's path and workspace commands, run as a program. The JSON's input Jacobian, tool-link
// poses and partial targets: test_cli_targets.cpp (same executable).
#define BOOST_TEST_MODULE cli_tools
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#define PCR_CLI_WORK_DIRECTORY "pcr_test_cli_tools"
#include "cli_runner.hpp"
#include "mini_json.hpp"

namespace {

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
