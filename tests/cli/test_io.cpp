#define BOOST_TEST_MODULE io
#include <unistd.h>
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "mini_json.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/io/json_writer.hpp"
#include "pcr/robots/io/robot_outline.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// A hand-made solution of planar_three_rod (no solve): the platform at (0, 0, 0.3) unrotated, each
/// rod a straight centerline of 5 points from (k, 0, 0) to (k, 0, 0.3) (the points need not be
/// physical for the writers), known wrenches.
pcr::RobotSolution planar_solution(const pcr::RobotModel& model) {
  pcr::RobotSolution s;
  s.summary.status = pcr::SolveStatus::Converged;
  s.summary.solver = "newton";
  s.summary.iterations = 3;
  s.summary.jacobian_evaluations = 2;
  s.summary.residual_max_abs = 1.25e-13;
  s.summary.residual_round_off = 2.5e-13;
  s.summary.message = "ok \"quoted\"";
  s.inputs = model.default_input_values();
  pcr::Pose platform;
  platform.position = pcr::Vec3(0, 0, 0.3);
  s.platforms = {platform};
  for (int r = 0; r < 3; ++r) {
    pcr::RodResult rod;
    rod.name = model.rods()[r].name;
    rod.length = 0.3 + 0.01 * r;
    rod.axial_force = -0.1 * (r + 1);
    rod.min_axial_stretch = 1.0 - 1e-6 * (r + 1);
    rod.base_force = pcr::Vec3(0.5, -0.25, r);
    rod.base_moment = pcr::Vec3(1e-3, 2e-3, 3e-3);
    rod.tip_force = pcr::Vec3(-0.5, 0.25, -r);
    rod.tip_moment = pcr::Vec3(-1e-3, 0, 1.0 / 3.0);
    for (int k = 0; k < 5; ++k) rod.centerline.emplace_back(0.1 * (r - 1), 0.0, 0.3 * k / 4.0);
    s.rods.push_back(rod);
  }
  return s;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

/// Directories made by fresh_directory, removed when the process ends.
struct MadeDirectories {
  std::vector<std::filesystem::path> paths;
  ~MadeDirectories() {
    std::error_code ignored;
    for (const auto& path : paths) std::filesystem::remove_all(path, ignored);
  }
};

std::filesystem::path fresh_directory(const std::string& name) {
  static MadeDirectories made;
  // Named with the process id: two runs of this test on one machine (two build trees) do not collide.
  const auto dir =
      std::filesystem::temp_directory_path() / ("pcr_test_io_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  made.paths.push_back(dir);
  return dir;
}

}  // namespace

BOOST_AUTO_TEST_CASE(json_quote_escapes_quotes_backslashes_and_control_characters) {
  // Expected literals written by hand from RFC 8259 §7.
  BOOST_CHECK_EQUAL(pcr::json_quote("plain"), "\"plain\"");
  BOOST_CHECK_EQUAL(pcr::json_quote("a\"b\\c"), "\"a\\\"b\\\\c\"");
  BOOST_CHECK_EQUAL(pcr::json_quote("l1\nl2\tx\r\b\f"), "\"l1\\nl2\\tx\\r\\b\\f\"");
  BOOST_CHECK_EQUAL(pcr::json_quote(std::string("\x01\x1f", 2)), "\"\\u0001\\u001f\"");
  BOOST_CHECK_EQUAL(pcr::json_quote(std::string("nul\0!", 5)), "\"nul\\u0000!\"");
  BOOST_CHECK_EQUAL(pcr::json_quote("caf\xc3\xa9 /"), "\"caf\xc3\xa9 /\"");  // UTF-8 and '/' unchanged
}

BOOST_AUTO_TEST_CASE(json_writer_writes_non_finite_numbers_as_null_and_counts_them) {
  std::ostringstream out;
  pcr::JsonWriter json(out, 0);
  pcr::VecX v(4);
  v << 1.5, kNaN, kInf, -kInf;
  json.array(v);
  BOOST_CHECK_EQUAL(out.str(), "[1.5, null, null, null]");
  BOOST_CHECK_EQUAL(json.non_finite_count(), 3);
  BOOST_CHECK(json.complete());
}

BOOST_AUTO_TEST_CASE(json_writer_numbers_round_trip_exactly) {
  // 17 significant digits identify every double (IEEE 754-2008 §5.12.2), so parsing gives back the
  // same bits: the comparison is exact.
  const std::vector<double> numbers{0.1, 1.0 / 3.0,  -2.5e17, 1e-300, 4.9406564584124654e-324,
                                    0.0, 123456789.0};
  std::ostringstream out;
  pcr::JsonWriter json(out);
  json.begin_array();
  for (double x : numbers) json.value(x);
  json.end_array();
  const test_json::Value parsed = test_json::parse(out.str());
  BOOST_REQUIRE_EQUAL(parsed.items.size(), numbers.size());
  for (size_t i = 0; i < numbers.size(); ++i) BOOST_CHECK_EQUAL(parsed[i].number, numbers[i]);
}

BOOST_AUTO_TEST_CASE(json_writer_nesting_and_misuse) {
  std::ostringstream out;
  pcr::JsonWriter json(out, 0);
  json.begin_object();
  json.key("a");
  json.begin_array();
  json.value(1);
  json.value(true);
  json.null();
  json.value("s");
  json.end_array();
  json.key("empty");
  json.begin_object();
  json.end_object();
  BOOST_CHECK(!json.complete());
  json.end_object();
  BOOST_CHECK(json.complete());
  BOOST_CHECK_EQUAL(out.str(), "{\"a\":[1,true,null,\"s\"],\"empty\":{}}");

  std::ostringstream other;
  pcr::JsonWriter bad(other);
  bad.begin_object();
  BOOST_CHECK_THROW(bad.value(1.0), pcr::InputError);  // a member needs a key
  BOOST_CHECK_THROW(bad.end_array(), pcr::InputError);
  bad.key("k");
  BOOST_CHECK_THROW(bad.key("k2"), pcr::InputError);  // two keys in a row
}

BOOST_AUTO_TEST_CASE(solution_json_is_parsed_back_with_every_field) {
  const pcr::RobotModel model = pcr::load_robot_model(PCR_MODEL_DIR "/planar_three_rod.urdf");
  pcr::RobotSolution s = planar_solution(model);
  s.rods[1].axial_force = kNaN;  // must come out as null, counted
  std::ostringstream out;
  const int non_finite = pcr::write_solution_json(out, model, s);
  BOOST_CHECK_EQUAL(non_finite, 1);
  const test_json::Value j = test_json::parse(out.str());
  BOOST_CHECK_EQUAL(j["model"].text, "planar_three_rod");
  BOOST_CHECK_EQUAL(j["status"].text, "converged");
  BOOST_CHECK_EQUAL(j["non_finite_values"].number, 1.0);
  // Exact comparisons: 17-digit numbers round-trip (see json_writer_numbers_round_trip_exactly).
  for (size_t i = 0; i < model.inputs().size(); ++i)
    BOOST_CHECK_EQUAL(j["inputs"][model.inputs()[i].name].number, s.inputs[static_cast<int>(i)]);
  BOOST_CHECK_EQUAL(j["inputs"].members.size(), 3u);
  const test_json::Value& platform = j["platforms"]["platform"];
  BOOST_CHECK_EQUAL(platform["position"][2].number, 0.3);
  BOOST_CHECK_EQUAL(platform["quaternion_wxyz"][0].number, 1.0);
  BOOST_CHECK_EQUAL(platform["quaternion_wxyz"].items.size(), 4u);
  const test_json::Value& left = j["rods"]["left"];
  BOOST_CHECK_EQUAL(left["length"].number, 0.3);
  BOOST_CHECK_EQUAL(left["axial_force"].number, -0.1);
  BOOST_CHECK_EQUAL(left["min_axial_stretch"].number, 1.0 - 1e-6);
  BOOST_CHECK_EQUAL(left["base_wrench"]["force"][1].number, -0.25);
  BOOST_CHECK_EQUAL(left["tip_wrench"]["moment"][2].number, 1.0 / 3.0);
  BOOST_CHECK_EQUAL(left["centerline"].items.size(), 5u);
  BOOST_CHECK_EQUAL(left["centerline"][4][2].number, 0.3);
  BOOST_CHECK(j["rods"]["middle"]["axial_force"].type == test_json::Value::Type::Null);
  const test_json::Value& summary = j["summary"];
  BOOST_CHECK_EQUAL(summary["solver"].text, "newton");
  BOOST_CHECK_EQUAL(summary["status"].text, "converged");
  BOOST_CHECK_EQUAL(summary["iterations"].number, 3.0);
  BOOST_CHECK_EQUAL(summary["jacobian_evaluations"].number, 2.0);
  BOOST_CHECK_EQUAL(summary["residual_max_abs"].number, 1.25e-13);
  BOOST_CHECK_EQUAL(summary["residual_round_off"].number, 2.5e-13);
  BOOST_CHECK_EQUAL(summary["message"].text, "ok \"quoted\"");
  BOOST_CHECK(summary.has("wall_time_seconds"));
  BOOST_CHECK(!j.has("targets"));
}

BOOST_AUTO_TEST_CASE(vtk_file_has_one_polyline_per_rod_and_the_outlines) {
  const pcr::RobotModel model = pcr::load_robot_model(PCR_MODEL_DIR "/planar_three_rod.urdf");
  const pcr::RobotSolution s = planar_solution(model);
  const auto path = fresh_directory("vtk") / "robot.vtk";
  pcr::write_solution_vtk(path.string(), model, s);
  std::istringstream in(read_text(path));
  std::string line;
  std::getline(in, line);
  BOOST_CHECK_EQUAL(line, "# vtk DataFile Version 3.0");
  std::getline(in, line);
  std::getline(in, line);
  BOOST_CHECK_EQUAL(line, "ASCII");
  std::getline(in, line);
  BOOST_CHECK_EQUAL(line, "DATASET POLYDATA");
  std::string word, type;
  size_t num_points = 0;
  in >> word >> num_points >> type;
  BOOST_CHECK_EQUAL(word, "POINTS");
  // 3 rods x 5 centerline points + the base's 3 and the platform's 3 attachment points.
  BOOST_REQUIRE_EQUAL(num_points, 21u);
  std::vector<pcr::Vec3> points(num_points);
  for (pcr::Vec3& p : points) in >> p[0] >> p[1] >> p[2];
  auto read_cells = [&](const char* keyword, size_t cells, size_t size) {
    size_t n = 0, total = 0;
    in >> word >> n >> total;
    BOOST_CHECK_EQUAL(word, keyword);
    BOOST_CHECK_EQUAL(n, cells);
    BOOST_CHECK_EQUAL(total, size);
    std::vector<std::vector<size_t>> out(n);
    for (auto& cell : out) {
      size_t count = 0;
      in >> count;
      cell.resize(count);
      for (size_t& i : cell) {
        in >> i;
        BOOST_CHECK_LT(i, num_points);
      }
    }
    return out;
  };
  // The base attachment points (-0.1, 0, 0), (0, 0, 0), (0.1, 0, 0) are collinear: a polyline after
  // the 3 rods; the platform triangle is the one polygon.
  const auto lines = read_cells("LINES", 4, 3 * 6 + 4);
  const auto polygons = read_cells("POLYGONS", 1, 4);
  for (size_t r = 0; r < 3; ++r) {
    BOOST_REQUIRE_EQUAL(lines[r].size(), 5u);
    for (size_t k = 0; k < 5; ++k)  // the points written are the rod's centerline (17 digits: exact)
      BOOST_CHECK((points[lines[r][k]] - s.rods[r].centerline[k]).norm() == 0.0);
  }
  // Platform outline: the attachment points of planar_three_rod.urdf in the frame of the platform at
  // (0, 0, 0.3): (-0.04, 0, 0.3), (0.04, 0, 0.3), (0, 0, 0.28). 1e-15 m: one rounded addition.
  const std::vector<pcr::Vec3> expected{{-0.04, 0, 0.3}, {0.04, 0, 0.3}, {0, 0, 0.28}};
  for (const pcr::Vec3& e : expected) {
    bool found = false;
    for (size_t i : polygons[0]) found = found || (points[i] - e).norm() < 1e-15;
    BOOST_CHECK_MESSAGE(found, "platform attachment point " << e.transpose() << " missing");
  }
  size_t cells = 0;
  in >> word >> cells;
  BOOST_CHECK_EQUAL(word, "CELL_DATA");
  BOOST_CHECK_EQUAL(cells, 5u);
  // The base polyline runs along x in order: -0.15, -0.08, 0.15 (or reversed). 1e-15 m: exact inputs.
  BOOST_REQUIRE_EQUAL(lines[3].size(), 3u);
  const double x0 = points[lines[3][0]].x(), x1 = points[lines[3][1]].x(), x2 = points[lines[3][2]].x();
  BOOST_CHECK_SMALL(x1 + 0.08, 1e-15);
  BOOST_CHECK_CLOSE_FRACTION(std::abs(x0 - x2), 0.3, 1e-14);

  pcr::RobotSolution broken = s;
  broken.rods[0].centerline[2][0] = kNaN;
  BOOST_CHECK_THROW(pcr::write_solution_vtk(path.string(), model, broken), pcr::InputError);
}

BOOST_AUTO_TEST_CASE(csv_files_per_rod_with_arc_length) {
  const pcr::RobotModel model = pcr::load_robot_model(PCR_MODEL_DIR "/planar_three_rod.urdf");
  pcr::RobotSolution s = planar_solution(model);
  s.platforms[0].position[0] = kNaN;  // written as an empty field
  const auto dir = fresh_directory("csv");
  pcr::write_solution_csv((dir / "sub").string(), model, s);
  BOOST_CHECK_EQUAL(read_text(dir / "sub" / "platforms.csv"),
                    "platform,x,y,z,qw,qx,qy,qz\nplatform,,0,0.29999999999999999,1,0,0,0\n");
  std::istringstream rod(read_text(dir / "sub" / "rod_right.csv"));
  std::string line;
  std::vector<std::string> rows;
  while (std::getline(rod, line)) rows.push_back(line);
  BOOST_REQUIRE_EQUAL(rows.size(), 6u);
  BOOST_CHECK_EQUAL(rows[0], "s,x,y,z");
  // s = L k / 4 with L = 0.32: the last row is s = L exactly, at (0.1, 0, 0.3).
  BOOST_CHECK_EQUAL(rows[5], "0.32000000000000001,0.10000000000000001,0,0.29999999999999999");
  // The summary: status, iterations, residual, time, message (quoted, " doubled), then the verdict,
  // not checked here (count and margin empty).
  BOOST_CHECK_EQUAL(read_text(dir / "sub" / "summary.csv"),
                    "status,iterations,residual_max_abs,wall_time_seconds,message,stability,unstable_modes,"
                    "stability_margin,stability_reason\n"
                    "converged,3,1.25e-13,0,\"ok \"\"quoted\"\"\",not_checked,,,\"\"\n");
  s.stability_verdict.verdict = pcr::StabilityVerdict::Unstable;
  s.stability_verdict.unstable_modes = 2;
  s.stability_verdict.margin = -0.5;
  s.stability_verdict.reason = "counted";
  pcr::write_solution_csv((dir / "sub").string(), model, s);
  const std::string summary = read_text(dir / "sub" / "summary.csv");
  BOOST_CHECK_MESSAGE(summary.find(",unstable,2,-0.5,\"counted\"\n") != std::string::npos, summary);
  const std::string inputs = read_text(dir / "sub" / "inputs.csv");
  BOOST_CHECK(inputs.rfind("input,kind,value,lower,upper\nleft,rod_length,", 0) == 0);
  BOOST_CHECK_EQUAL(pcr::rod_csv_file_name("a/b c"), "rod_a_b_c.csv");
}

BOOST_AUTO_TEST_CASE(stewart_platform_outline_is_a_simple_hexagon) {
  // The six attachment points, ordered, must go once around their centroid: the wrapped angle steps
  // sum to +-2 pi and all have the same sign (a polygon without self-crossing).
  const pcr::RobotModel model = pcr::load_robot_model(PCR_MODEL_DIR "/stewart_gough.urdf");
  pcr::RobotSolution s;
  s.inputs = model.default_input_values();
  s.platforms = model.initial_platform_poses();
  const std::vector<pcr::Outline> outlines = pcr::robot_outlines(model, s);
  BOOST_REQUIRE_EQUAL(outlines.size(), 2u);
  BOOST_CHECK_EQUAL(outlines[0].name, "base");
  BOOST_CHECK_EQUAL(outlines[1].platform, 0);
  for (const pcr::Outline& outline : outlines) {
    BOOST_REQUIRE_EQUAL(outline.points.size(), 6u);
    BOOST_CHECK(outline.closed);
    pcr::Vec3 c = pcr::Vec3::Zero();
    for (const pcr::Vec3& p : outline.points) c += p / 6.0;
    double total = 0.0;
    int positive = 0;
    for (size_t k = 0; k < 6; ++k) {
      const pcr::Vec3 a = outline.points[k] - c, b = outline.points[(k + 1) % 6] - c;
      const double step = std::atan2(a.x() * b.y() - a.y() * b.x(), a.x() * b.x() + a.y() * b.y());
      total += step;
      positive += step > 0;
    }
    // 1e-12: rounding of six atan2 steps of O(1) rad
    BOOST_CHECK_CLOSE_FRACTION(std::abs(total), 2 * M_PI, 1e-12);
    BOOST_CHECK(positive == 0 || positive == 6);
  }
}
