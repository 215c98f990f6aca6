#define BOOST_TEST_MODULE cli
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#define PCR_CLI_WORK_DIRECTORY "pcr_test_cli"
#include "cli_runner.hpp"
#include "mini_json.hpp"

BOOST_AUTO_TEST_CASE(fk_cantilever_json_has_the_expected_keys_and_converges) {
  const Run run = run_pcr("fk " + model("cantilever.urdf") + " --json");
  BOOST_TEST_MESSAGE(run.err);
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  const test_json::Value j = test_json::parse(run.out);
  BOOST_CHECK_EQUAL(j["status"].text, "converged");
  BOOST_CHECK_EQUAL(j["summary"]["status"].text, "converged");
  for (const char* key : {"solver", "iterations", "residual_max_abs", "wall_time_seconds", "message"})
    BOOST_CHECK_MESSAGE(j["summary"].has(key), "summary." << key);
  BOOST_CHECK(j["inputs"].members.empty());     // the cantilever has no actuation input
  BOOST_CHECK(j["platforms"].members.empty());  // and no platform
  const test_json::Value& beam = j["rods"]["beam"];
  for (const char* key : {"length", "axial_force", "base_wrench", "tip_wrench", "centerline"})
    BOOST_CHECK_MESSAGE(beam.has(key), "rods.beam." << key);
  // Fixed length 0.5 m in the model; 1e-12: the length is a fixed variable of the solve (round-off).
  BOOST_CHECK_CLOSE_FRACTION(beam["length"].number, 0.5, 1e-12);
  // The clamped end is at the origin; the free tip carries the 0.1 N dead load of the model
  // (n(L) = the end's load, -0.1 e_z): 1e-9 N = solver tolerance 1e-10 times the force scale (~1 N).
  BOOST_CHECK_SMALL(beam["centerline"][0][0].number, 1e-12);
  BOOST_CHECK_SMALL(beam["tip_wrench"]["force"][0].number, 1e-9);
  BOOST_CHECK_CLOSE_FRACTION(std::abs(beam["tip_wrench"]["force"][2].number), 0.1, 1e-8);
}

BOOST_AUTO_TEST_CASE(fk_planar_json_converges_with_symmetric_platform) {
  const Run run = run_pcr("fk " + model("planar_three_rod.urdf") + " --json");
  BOOST_TEST_MESSAGE(run.err);
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  const test_json::Value j = test_json::parse(run.out);
  BOOST_CHECK_EQUAL(j["status"].text, "converged");
  // Default inputs from planar_three_rod.urdf; 1e-15: one decimal-to-double rounding.
  BOOST_CHECK_CLOSE_FRACTION(j["inputs"]["left"].number, 0.319530906173, 1e-15);
  BOOST_CHECK_CLOSE_FRACTION(j["inputs"]["middle"].number, 0.291204395571, 1e-15);
  BOOST_CHECK_CLOSE_FRACTION(j["inputs"]["right"].number, 0.319530906173, 1e-15);
  // Every rod and load lies in the x-z plane, which is a mirror plane of the model: the platform
  // stays in it (y = 0) and only pitches about y (quaternion x = z = 0). 1e-10 m (rad): solver
  // tolerance 1e-10 on residuals scaled by ~0.3 m.
  const test_json::Value& platform = j["platforms"]["platform"];
  BOOST_CHECK_SMALL(platform["position"][1].number, 1e-10);
  BOOST_CHECK_SMALL(platform["quaternion_wxyz"][1].number, 1e-10);
  BOOST_CHECK_SMALL(platform["quaternion_wxyz"][3].number, 1e-10);
  BOOST_CHECK_EQUAL(j["rods"].members.size(), 3u);
  BOOST_CHECK_EQUAL(j["rods"]["left"]["centerline"].items.size(), 21u);  // default centerline points
}

BOOST_AUTO_TEST_CASE(fk_table_and_files) {
  const fs::path dir = work_directory() / "files";
  const Run run = run_pcr("fk " + model("planar_three_rod.urdf") + " --input middle=0.29 --csv '" +
                          (dir / "csv").string() + "' --vtk '" + (dir / "r.vtk").string() +
                          "' --json-file '" + (dir / "r.json").string() + "'");
  BOOST_TEST_MESSAGE(run.err);
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  BOOST_CHECK(contains(run.out, "converged"));
  BOOST_CHECK(contains(run.out, "290.0000 mm"));  // the input given, in mm
  const std::string summary = read_text(dir / "csv" / "summary.csv");
  BOOST_CHECK_MESSAGE(contains(summary, "\nconverged,"), summary);  // the status on the table's first line
  for (const char* file : {"csv/summary.csv", "csv/platforms.csv", "csv/inputs.csv", "csv/rod_left.csv",
                           "csv/rod_middle.csv", "csv/rod_right.csv", "r.vtk"})
    BOOST_CHECK_MESSAGE(fs::file_size(dir / file) > 0, file);
  BOOST_CHECK_EQUAL(test_json::parse(read_text(dir / "r.json"))["inputs"]["middle"].number, 0.29);
}

BOOST_AUTO_TEST_CASE(unknown_input_name_is_a_usage_error_naming_it) {
  const Run run = run_pcr("fk " + model("planar_three_rod.urdf") + " --input leftt=0.3");
  BOOST_CHECK_EQUAL(run.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(run.err, "leftt"), run.err);
  BOOST_CHECK_MESSAGE(contains(run.err, "left, middle, right"), run.err);  // lists the valid names
  BOOST_CHECK(run.out.empty());
}

BOOST_AUTO_TEST_CASE(out_of_bounds_input_is_a_usage_error) {
  const Run run = run_pcr("fk " + model("planar_three_rod.urdf") + " --input left=0.9");  // upper 0.5
  BOOST_CHECK_EQUAL(run.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(run.err, "left=0.9") && contains(run.err, "bounds"), run.err);
}

BOOST_AUTO_TEST_CASE(missing_model_file_is_a_usage_error_naming_the_file) {
  const Run run = run_pcr("fk /nonexistent/robot_xyz.urdf");
  BOOST_CHECK_EQUAL(run.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(run.err, "/nonexistent/robot_xyz.urdf"), run.err);
}

BOOST_AUTO_TEST_CASE(bad_arguments_are_usage_errors) {
  BOOST_CHECK_EQUAL(run_pcr("fk " + model("cantilever.urdf") + " --solver bfgs").exit_code, 2);
  BOOST_CHECK_EQUAL(run_pcr("fk " + model("cantilever.urdf") + " --tolerance abc").exit_code, 2);
  BOOST_CHECK_EQUAL(run_pcr("fk " + model("cantilever.urdf") + " --frobnicate 1").exit_code, 2);
  const Run points = run_pcr("fk " + model("cantilever.urdf") + " --mixed-points gauss");
  BOOST_CHECK_EQUAL(points.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(points.err, "--mixed-points gauss"), points.err);
  // Both point sets are accepted (the published scheme is kept for comparison).
  BOOST_CHECK_EQUAL(run_pcr("fk " + model("cantilever.urdf") + " --mixed-points greville").exit_code, 0);
  BOOST_CHECK_EQUAL(run_pcr("fk " + model("cantilever.urdf") + " --mixed-points midpoints").exit_code, 0);
  const Run ik = run_pcr("ik " + model("planar_three_rod.urdf") + " --target platform=0,0");
  BOOST_CHECK_EQUAL(ik.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(ik.err, "--target platform=0,0"), ik.err);
  const Run link = run_pcr("ik " + model("planar_three_rod.urdf") + " --target nolink=0,0,0.3");
  BOOST_CHECK_EQUAL(link.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(link.err, "nolink"), link.err);
}

BOOST_AUTO_TEST_CASE(element_counts_that_cannot_fit_in_memory_are_rejected_naming_their_source) {
  // 100,000 elements of degree 6: an estimated 7.6 GiB per rod (rod_memory_estimate), over the 2 GiB
  // limit; rejected before any allocation, exit code 2, naming the option or the model's file and line.
  const Run option = run_pcr("fk " + model("stewart_gough.urdf") + " --elements 100000");
  BOOST_CHECK_EQUAL(option.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(option.err, "--elements 100000") && contains(option.err, "GiB"), option.err);
  // The same count as a model hint: a copy of the cantilever with elements="100000" on its
  // <discretization> line.
  std::string text = read_text(fs::path(PCR_MODEL_DIR) / "cantilever.urdf");
  const size_t at = text.find("elements=\"8\"");
  BOOST_REQUIRE(at != std::string::npos);
  text.replace(at, 12, "elements=\"100000\"");
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
  const fs::path big = work_directory() / "cantilever_100000.urdf";
  std::ofstream(big) << text;
  const Run hint = run_pcr("fk '" + big.string() + "'");
  BOOST_CHECK_EQUAL(hint.exit_code, 2);
  BOOST_CHECK_MESSAGE(contains(hint.err, big.string() + ":" + std::to_string(line) + ":"), hint.err);
  BOOST_CHECK_MESSAGE(contains(hint.err, "elements") && contains(hint.err, "GiB"), hint.err);
  // Within the limit the counts are accepted (the largest count that fits is not run here).
  BOOST_CHECK_EQUAL(run_pcr("fk " + model("cantilever.urdf") + " --elements 40").exit_code, 0);
}

BOOST_AUTO_TEST_CASE(running_out_of_memory_ends_with_exit_code_4_and_a_message) {
  // A count within the up-front limit (an estimated 1.4 GiB per rod) that does not fit in a 600 MB
  // address space (ulimit -v in the child's shell): stewart_gough with 20,000 elements per rod needs
  // about 4 GB (1.06 GB measured at 5,000, linear in the element count). std::bad_alloc must end in
  // exit code 4 with a message, not in an abort (a signal: exit code -1 here).
  const Run run = run_pcr("fk " + model("stewart_gough.urdf") + " --elements 20000", "ulimit -v 600000; ");
  BOOST_CHECK_EQUAL(run.exit_code, 4);
  BOOST_CHECK_MESSAGE(contains(run.err, "out of memory"), run.err);
}

BOOST_AUTO_TEST_CASE(ik_of_an_fk_pose_gives_back_the_fk_inputs) {
  const double left = 0.32, middle = 0.29, right = 0.31;  // within the bounds [0.15, 0.5]
  const Run fk = run_pcr("fk " + model("planar_three_rod.urdf") + " --json --input left=" + number(left) +
                         " --input middle=" + number(middle) + " --input right=" + number(right));
  BOOST_REQUIRE_EQUAL(fk.exit_code, 0);
  const test_json::Value f = test_json::parse(fk.out);
  const test_json::Value& x = f["platforms"]["platform"]["position"];
  const test_json::Value& q = f["platforms"]["platform"]["quaternion_wxyz"];
  std::string target = "platform=";
  for (int k = 0; k < 3; ++k) target += number(x[k].number) + ",";
  for (int k = 0; k < 4; ++k) target += number(q[k].number) + (k < 3 ? "," : "");
  // The pose has 6 rows for the 3 inputs: the in-plane components x, z and the pitch ry are met (a
  // full pose with more rows than inputs is refused, test_cli_tools).
  const Run ik = run_pcr("ik " + model("planar_three_rod.urdf") + " --json --target " + target +
                         " --components platform=x,z,ry");
  BOOST_TEST_MESSAGE(ik.err);
  BOOST_REQUIRE_EQUAL(ik.exit_code, 0);
  const test_json::Value i = test_json::parse(ik.out);
  BOOST_CHECK_EQUAL(i["status"].text, "converged");
  BOOST_CHECK_EQUAL(i["targets"]["platform"]["mode"].text, "pose");
  // 1e-8 m: both solves stop at dimensionless residuals below 1e-10 (the task's tolerance); the input
  // error is that times the conditioning of the pose-to-input map and the length scale 0.3 m, i.e.
  // 3e-9 m for a condition number of 1e2 (measured errors: about 1e-12 m).
  BOOST_CHECK_SMALL(i["inputs"]["left"].number - left, 1e-8);
  BOOST_CHECK_SMALL(i["inputs"]["middle"].number - middle, 1e-8);
  BOOST_CHECK_SMALL(i["inputs"]["right"].number - right, 1e-8);
}

// --stability through the tool (also the sanitizer pass's coverage of the verdict code). The counts are
// those test_stability_verdict checks against an independent discrete energy model: stewart_gough's
// default pose stable, planar_three_rod's default pose 1 unstable mode (its platform tilts out of the
// plane); the table names the verdict; passive_hinge's default pose 1 unstable mode (as
// planar_three_rod's; test_passive_joint_verdict); a model with contact is "unknown" with the reason.
BOOST_AUTO_TEST_CASE(stability_verdict_in_the_json_and_the_table) {
  const Run stewart = run_pcr("fk " + model("stewart_gough.urdf") + " --stability --json");
  BOOST_REQUIRE_EQUAL(stewart.exit_code, 0);
  const test_json::Value s = test_json::parse(stewart.out);
  BOOST_CHECK_EQUAL(s["stability"]["verdict"].text, "stable");
  BOOST_CHECK_EQUAL(s["stability"]["unstable_modes"].number, 0);
  BOOST_CHECK_GT(s["stability"]["margin"].number, 0.0);
  const Run planar = run_pcr("fk " + model("planar_three_rod.urdf") + " --stability --json");
  BOOST_REQUIRE_EQUAL(planar.exit_code, 0);
  const test_json::Value p = test_json::parse(planar.out);
  BOOST_CHECK_EQUAL(p["stability"]["verdict"].text, "unstable");
  BOOST_CHECK_EQUAL(p["stability"]["unstable_modes"].number, 1);
  BOOST_CHECK_LT(p["stability"]["margin"].number, 0.0);
  const Run table =
      run_pcr("ik " + model("planar_three_rod.urdf") + " --stability --target platform=0.01,0,0.29");
  BOOST_REQUIRE_EQUAL(table.exit_code, 0);
  BOOST_CHECK_MESSAGE(contains(table.out, "stability: "), table.out);
  const Run hinge = run_pcr("fk " + model("passive_hinge.urdf") + " --stability --json");
  BOOST_REQUIRE_EQUAL(hinge.exit_code, 0);
  const test_json::Value h = test_json::parse(hinge.out);
  BOOST_CHECK_EQUAL(h["stability"]["verdict"].text, "unstable");
  BOOST_CHECK_EQUAL(h["stability"]["unstable_modes"].number, 1);
  BOOST_CHECK_EQUAL(h["stability"]["platform_unstable_modes"].number, 1);
  const Run post = run_pcr("fk " + model("planar_post.urdf") + " --stability --json");
  BOOST_REQUIRE_EQUAL(post.exit_code, 0);
  const test_json::Value c = test_json::parse(post.out);
  BOOST_CHECK_EQUAL(c["stability"]["verdict"].text, "unstable");  // in the plane: test_contact_verdict
  BOOST_CHECK_EQUAL(c["stability"]["unstable_modes"].number, 1);
  BOOST_CHECK_MESSAGE(contains(c["stability"]["reason"].text, "rod 'middle' touches obstacle 'post'"),
                      c["stability"]["reason"].text);
}

BOOST_AUTO_TEST_CASE(unreachable_ik_target_fails_with_exit_code_1) {
  // 0.9 m above the base: the rods are at most 0.8 m long (stewart_gough.urdf bounds).
  const Run run = run_pcr("ik " + model("stewart_gough.urdf") + " --json --target platform=0,0,0.9");
  BOOST_CHECK_EQUAL(run.exit_code, 1);
  BOOST_CHECK_MESSAGE(contains(run.err, "unreachable"), run.err);
  const test_json::Value j = test_json::parse(run.out);
  BOOST_CHECK_NE(j["status"].text, "converged");
}

BOOST_AUTO_TEST_CASE(png_is_drawn_when_gnuplot_is_installed) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    BOOST_TEST_MESSAGE("gnuplot not installed: the --png case is not run");
    return;
  }
  const fs::path png = work_directory() / "robot.png";
  const Run run = run_pcr("fk " + model("planar_three_rod.urdf") + " --png '" + png.string() + "'");
  BOOST_TEST_MESSAGE(run.err);
  BOOST_REQUIRE_EQUAL(run.exit_code, 0);
  const std::string bytes = read_text(png);
  BOOST_REQUIRE_GT(bytes.size(), 8u);
  BOOST_CHECK_EQUAL(bytes.substr(1, 3), "PNG");  // PNG signature: \x89 P N G \r \n \x1a \n
}

BOOST_AUTO_TEST_CASE(ik_position_and_orientation_targets_are_reached) {
  // 1e-9 (m, and quaternion components): the solver tolerance 1e-10 on dimensionless residuals times
  // the length scale 0.3 m, with a factor 30 of margin for the conditioning.
  const Run position =
      run_pcr("ik " + model("planar_three_rod.urdf") + " --json --target platform=0.01,0,0.29");
  BOOST_TEST_MESSAGE(position.err);
  BOOST_REQUIRE_EQUAL(position.exit_code, 0);
  const test_json::Value p = test_json::parse(position.out);
  BOOST_CHECK_EQUAL(p["targets"]["platform"]["mode"].text, "position");
  const test_json::Value& x = p["platforms"]["platform"]["position"];
  BOOST_CHECK_SMALL(x[0].number - 0.01, 1e-9);
  BOOST_CHECK_SMALL(x[1].number, 1e-9);
  BOOST_CHECK_SMALL(x[2].number - 0.29, 1e-9);

  // R_y(2 deg): (cos 1 deg, 0, sin 1 deg, 0); given unnormalised (x 2) to check the normalisation.
  const double c = std::cos(M_PI / 180), s = std::sin(M_PI / 180);
  const Run orientation =
      run_pcr("ik " + model("planar_three_rod.urdf") +
              " --json --orientation-only platform=" + number(2 * c) + ",0," + number(2 * s) + ",0");
  BOOST_TEST_MESSAGE(orientation.err);
  BOOST_REQUIRE_EQUAL(orientation.exit_code, 0);
  const test_json::Value o = test_json::parse(orientation.out);
  const test_json::Value& q = o["platforms"]["platform"]["quaternion_wxyz"];
  const double sign = q[0].number < 0 ? -1.0 : 1.0;  // q and -q are the same rotation
  BOOST_CHECK_SMALL(sign * q[0].number - c, 1e-9);
  BOOST_CHECK_SMALL(sign * q[1].number, 1e-9);
  BOOST_CHECK_SMALL(sign * q[2].number - s, 1e-9);
  BOOST_CHECK_SMALL(sign * q[3].number, 1e-9);
}

// pcr path --folds on the planar robot with its middle rod fed past a fold (docs/cli.md). The fold's
// place and mode counts are checked against Newton bisection and an independent discrete energy model
// in test_paths_through_folds; here the tool's report: the events in path order with their fields, the
// snap's jump equal to the distance between the poses of the fold and the landing (computed here from
// the two events' poses: 1e-12 m, 1e-9 rad of round-off), the point past a fold failing with `stop`.
BOOST_AUTO_TEST_CASE(path_through_a_fold_reports_fold_snap_and_bifurcation) {
  const fs::path inputs = work_directory() / "fed_middle.csv";
  std::ofstream(inputs) << "middle\n0.291204395571\n0.34\n";
  const std::string path = "path " + model("planar_three_rod.urdf") + " --inputs '" + inputs.string() + "'";
  const Run snap = run_pcr(path + " --folds snap --json");
  BOOST_TEST_MESSAGE(snap.err);
  BOOST_REQUIRE_EQUAL(snap.exit_code, 0);
  const test_json::Value j = test_json::parse(snap.out);
  BOOST_CHECK_EQUAL(j["results"][1]["status"].text, "converged");
  const test_json::Value& events = j["events"];
  BOOST_REQUIRE_EQUAL(events.items.size(), 3u);
  const char* kinds[] = {"fold", "snap", "bifurcation"};
  for (size_t k = 0; k < 3; ++k) {
    BOOST_CHECK_EQUAL(events[k]["kind"].text, kinds[k]);
    BOOST_CHECK(events[k]["path_parameter"].number > 0.0 && events[k]["path_parameter"].number < 1.0);
    for (const char* key : {"position", "quaternion_wxyz", "rpy"})
      BOOST_CHECK_MESSAGE(events[k]["platforms"]["platform"].has(key), kinds[k] << " platform." << key);
  }
  const test_json::Value &fold = events[0], &landing = events[1];
  BOOST_CHECK_EQUAL(fold["path_parameter"].number, landing["path_parameter"].number);
  BOOST_CHECK_EQUAL(fold["unstable_modes_before"].number + 1, fold["unstable_modes_after"].number);
  const test_json::Value &a = fold["platforms"]["platform"], &b = landing["platforms"]["platform"];
  double distance = 0.0, dot = 0.0;
  for (size_t i = 0; i < 3; ++i) distance += std::pow(a["position"][i].number - b["position"][i].number, 2);
  for (size_t i = 0; i < 4; ++i) dot += a["quaternion_wxyz"][i].number * b["quaternion_wxyz"][i].number;
  BOOST_CHECK_CLOSE_FRACTION(landing["jump_position"].number, std::sqrt(distance), 1e-12);
  BOOST_CHECK_SMALL(landing["jump_rotation"].number - 2.0 * std::acos(std::min(1.0, std::abs(dot))), 1e-9);
  BOOST_CHECK(landing["jump_position"].number > 1e-3);  // a visible jump (15 mm, docs/cli.md)

  const Run stop = run_pcr(path + " --folds stop --json");
  BOOST_CHECK_EQUAL(stop.exit_code, 1);  // the row past the fold fails
  const test_json::Value s = test_json::parse(stop.out);
  BOOST_CHECK_EQUAL(s["results"][1]["status"].text, "failed");
  const std::string& message = s["results"][1]["summary"]["message"].text;
  BOOST_CHECK_MESSAGE(contains(message, "fold at path parameter"), message);
}
