// Obstacles and contact forces in the VTK file and the gnuplot figure (part of test_io):
// models/planar_post.urdf solved by FK at its default inputs, its middle rod lying on the round post.
#include <unistd.h>
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "mini_json.hpp"
#include "pcr/robots/io/gnuplot_figure.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace {

using pcr::Vec3;

// The post of planar_post.urdf (world frame): a capsule of radius 0.02 m around this segment.
const Vec3 kPostStart(-0.0147, -0.02, 0.1436), kPostEnd(-0.0147, 0.02, 0.1436);
constexpr double kPostRadius = 0.02;

double distance_to_post_axis(const Vec3& x) {
  const Vec3 e = kPostEnd - kPostStart;
  const double t = std::clamp((x - kPostStart).dot(e) / e.squaredNorm(), 0.0, 1.0);
  return (x - kPostStart - t * e).norm();
}

struct PostSolution {
  std::shared_ptr<const pcr::RobotModel> model;
  pcr::RobotSolution solution;
  Vec3 json_contact_force = Vec3::Zero();  // the JSON's "contacts" total of the middle rod on the post
};

PostSolution solve_planar_post() {
  PostSolution out;
  out.model =
      std::make_shared<const pcr::RobotModel>(pcr::load_robot_model(PCR_MODEL_DIR "/planar_post.urdf"));
  pcr::ForwardKinematics fk(out.model);
  out.solution = fk.solve(out.model->default_input_values());
  BOOST_REQUIRE(out.solution.summary.status == pcr::SolveStatus::Converged);
  std::ostringstream json;
  pcr::write_solution_json(json, *out.model, out.solution);
  const test_json::Value j = test_json::parse(json.str());
  BOOST_REQUIRE_EQUAL(j["contacts"].items.size(), 1u);
  for (int k = 0; k < 3; ++k) out.json_contact_force[k] = j["contacts"][0]["force"][k].number;
  return out;
}

/// A legacy VTK polydata file as read back: points, cells by keyword, cell and point arrays by name.
struct Vtk {
  std::vector<Vec3> points;
  std::map<std::string, std::vector<std::vector<size_t>>> cells;
  std::map<std::string, std::vector<int>> cell_scalars;
  std::map<std::string, std::vector<Vec3>> point_vectors;
  size_t cell_data = 0, point_data = 0;
};

Vtk read_vtk(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int i = 0; i < 4; ++i) std::getline(in, line);
  BOOST_CHECK_EQUAL(line, "DATASET POLYDATA");
  Vtk vtk;
  std::string word, type;
  size_t n = 0, total_cells = 0;
  in >> word >> n >> type;
  BOOST_REQUIRE_EQUAL(word, "POINTS");
  vtk.points.resize(n);
  for (Vec3& p : vtk.points) in >> p[0] >> p[1] >> p[2];
  while (in >> word) {
    if (word == "VERTICES" || word == "LINES" || word == "POLYGONS") {
      size_t size = 0, read = 0;
      in >> n >> size;
      auto& cells = vtk.cells[word];
      cells.resize(n);
      for (auto& cell : cells) {
        size_t count = 0;
        in >> count;
        cell.resize(count);
        for (size_t& i : cell) in >> i;
        read += count + 1;
      }
      BOOST_CHECK_EQUAL(read, size);  // the size declared is the number of integers that follow
      total_cells += n;
    } else if (word == "CELL_DATA") {
      in >> vtk.cell_data;
    } else if (word == "POINT_DATA") {
      in >> vtk.point_data;
    } else if (word == "SCALARS") {
      std::string name, lookup, table;
      int components = 0;
      in >> name >> type >> components >> lookup >> table;
      auto& values = vtk.cell_scalars[name];
      values.resize(vtk.cell_data);
      for (int& v : values) in >> v;
    } else if (word == "VECTORS") {
      std::string name;
      in >> name >> type;
      auto& values = vtk.point_vectors[name];
      values.resize(vtk.point_data);
      for (Vec3& v : values) in >> v[0] >> v[1] >> v[2];
    } else {
      BOOST_ERROR("unexpected VTK keyword " << word);
      break;
    }
  }
  BOOST_CHECK(in.eof());
  BOOST_CHECK_EQUAL(vtk.cell_data, total_cells);
  for (const auto& [keyword, cells] : vtk.cells)
    for (const auto& cell : cells)
      for (size_t i : cell) BOOST_CHECK_LT(i, vtk.points.size());
  return vtk;
}

}  // namespace

BOOST_AUTO_TEST_CASE(vtk_of_planar_post_has_the_post_and_the_contact_forces) {
  const PostSolution post = solve_planar_post();
  const auto path =
      std::filesystem::temp_directory_path() / ("pcr_test_io_post_" + std::to_string(getpid()) + ".vtk");
  pcr::write_solution_vtk(path.string(), *post.model, post.solution);
  const Vtk vtk = read_vtk(path.string());
  std::filesystem::remove(path);

  // The post's cells: every point on the capsule's surface (1e-12 m: rounding of the rings' cos / sin at
  // the 0.1 m scale), and they exist.
  const std::vector<int>& obstacle = vtk.cell_scalars.at("obstacle");
  BOOST_REQUIRE_EQUAL(obstacle.size(), vtk.cell_data);
  size_t post_cells = 0, index = 0;
  double deviation = 0.0;
  for (const char* keyword : {"VERTICES", "LINES", "POLYGONS"}) {
    if (!vtk.cells.count(keyword)) continue;
    for (const auto& cell : vtk.cells.at(keyword)) {
      if (obstacle[index++] != 0) continue;
      ++post_cells;
      BOOST_CHECK_EQUAL(std::string(keyword), "POLYGONS");
      for (size_t i : cell)
        deviation = std::max(deviation, std::abs(distance_to_post_axis(vtk.points[i]) - kPostRadius));
    }
  }
  BOOST_CHECK_GT(post_cells, 0u);
  BOOST_CHECK_SMALL(deviation, 1e-12);

  // One force vector per point, finite; their sum is the JSON's contact total (1e-12 N: the cells'
  // resultants summed in another order than the intervals', against a total of 0.15 N).
  BOOST_REQUIRE_EQUAL(vtk.point_data, vtk.points.size());
  for (const char* name : {"contact_force", "contact_force_density"}) {
    BOOST_REQUIRE_EQUAL(vtk.point_vectors.at(name).size(), vtk.points.size());
    for (const Vec3& f : vtk.point_vectors.at(name)) BOOST_CHECK(f.allFinite());
  }
  Vec3 total = Vec3::Zero();
  for (const Vec3& f : vtk.point_vectors.at("contact_force")) total += f;
  BOOST_CHECK_GT(post.json_contact_force.norm(), 0.1);
  BOOST_CHECK_SMALL((total - post.json_contact_force).norm(), 1e-12);
  // The density pushes the rod away from the post's axis: at every rod point that carries one, it points
  // along the point's offset from the axis (the axis runs along y) within 0.35 rad: the density is the
  // one of the cell whose midpoint is nearest to the point, at most half a cell (0.29 m / 24 / 2 = 6 mm)
  // away along a rod lying 20.5 mm from the axis, i.e. 0.3 rad of the post's circumference.
  const auto& density = vtk.point_vectors.at("contact_force_density");
  int loaded = 0;
  for (size_t i = 0; i < vtk.points.size(); ++i) {
    if (density[i].norm() == 0.0) continue;
    ++loaded;
    Vec3 offset = vtk.points[i] - kPostStart;
    offset.y() = 0.0;
    BOOST_CHECK_GT(density[i].normalized().dot(offset.normalized()), std::cos(0.35));
  }
  BOOST_CHECK_GT(loaded, 0);
}

BOOST_AUTO_TEST_CASE(gnuplot_script_of_planar_post_draws_the_post_and_the_force_arrows) {
  const PostSolution post = solve_planar_post();
  const pcr::FigureScript figure = pcr::solution_figure_script(*post.model, post.solution, "fk");
  BOOST_CHECK(figure.script.find("'obstacles.dat' with lines") != std::string::npos);
  BOOST_CHECK(figure.script.find("'contact_forces.dat' using 1:2:3:4:5:6 with vectors") != std::string::npos);
  std::map<std::string, std::string> files(figure.files.begin(), figure.files.end());
  BOOST_REQUIRE(files.count("obstacles.dat") && files.count("contact_forces.dat"));
  BOOST_CHECK(!files.count("obstacle_points.dat"));  // the post is no point obstacle
  // Every obstacle vertex in mm on the post's surface (1e-6 mm: the 9 digits written for ~100 mm).
  std::istringstream obstacles(files.at("obstacles.dat"));
  int vertices = 0;
  double deviation = 0.0;
  for (Vec3 x; obstacles >> x[0] >> x[1] >> x[2]; ++vertices)
    deviation = std::max(deviation, std::abs(distance_to_post_axis(x / 1e3) - kPostRadius));
  BOOST_CHECK_SMALL(deviation, 1e-9);
  BOOST_CHECK_GT(vertices, 0);
  // The arrows share one scale: their sum is parallel to the contact force (1e-6 rad: 9 digits written).
  std::istringstream forces(files.at("contact_forces.dat"));
  Vec3 sum = Vec3::Zero(), x, d;
  int arrows = 0;
  for (; forces >> x[0] >> x[1] >> x[2] >> d[0] >> d[1] >> d[2]; ++arrows) sum += d;
  BOOST_CHECK_GT(arrows, 0);
  BOOST_CHECK_SMALL(sum.normalized().cross(post.json_contact_force.normalized()).norm(), 1e-6);
}

BOOST_AUTO_TEST_CASE(csv_of_planar_post_lists_the_post_and_the_contact_forces) {
  const PostSolution post = solve_planar_post();
  const auto dir =
      std::filesystem::temp_directory_path() / ("pcr_test_io_post_csv_" + std::to_string(getpid()));
  pcr::write_solution_csv(dir.string(), *post.model, post.solution);
  auto lines_of = [&](const char* name) {
    std::ifstream file(dir / name);
    std::vector<std::string> lines;
    for (std::string line; std::getline(file, line);) lines.push_back(line);
    return lines;
  };
  const std::vector<std::string> obstacles = lines_of("obstacles.csv"), contacts = lines_of("contacts.csv");
  std::filesystem::remove_all(dir);
  BOOST_REQUIRE_EQUAL(obstacles.size(), 2u);
  BOOST_CHECK_EQUAL(obstacles[0], "obstacle,type,link,x,y,z,dx,dy,dz,ex,ey,ez,radius,length");
  // The post as declared (world frame, no link; 17 digits read back exactly), fields that do not apply
  // empty.
  std::vector<std::string> row_of_post;
  {
    std::istringstream row(obstacles[1] + ",");
    for (std::string field; std::getline(row, field, ',');) row_of_post.push_back(field);
  }
  BOOST_REQUIRE_EQUAL(row_of_post.size(), 14u);
  BOOST_CHECK_EQUAL(row_of_post[0], "\"post\"");
  BOOST_CHECK_EQUAL(row_of_post[1], "capsule");
  BOOST_CHECK_EQUAL(row_of_post[2], "\"\"");
  const std::vector<double> numbers{-0.0147, -0.02, 0.1436, -0.0147, 0.02, 0.1436, 0.02};
  const std::vector<int> columns{3, 4, 5, 9, 10, 11, 12};
  for (size_t k = 0; k < columns.size(); ++k)
    BOOST_CHECK_EQUAL(std::stod(row_of_post[columns[k]]), numbers[k]);
  for (int k : {6, 7, 8, 13}) BOOST_CHECK(row_of_post[k].empty());
  BOOST_REQUIRE_GT(contacts.size(), 1u);
  BOOST_CHECK_EQUAL(contacts[0], "rod,obstacle,concentrated,s,magnitude,gap,fx,fy,fz");
  // One row per collocation cell of the middle rod, in increasing arc length within the rod; the forces
  // sum to the JSON's total
  // (1e-12 N of 0.15 N: the cells summed in another order than the intervals, each read back exactly).
  Vec3 total = Vec3::Zero();
  double previous = -1.0;
  for (size_t i = 1; i < contacts.size(); ++i) {
    std::istringstream row(contacts[i]);
    std::vector<std::string> fields;
    for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
    BOOST_REQUIRE_EQUAL(fields.size(), 9u);
    BOOST_CHECK_EQUAL(fields[0], "\"middle\"");
    BOOST_CHECK_EQUAL(fields[2], "false");
    const double s = std::stod(fields[3]);
    BOOST_CHECK(s > previous && s < post.solution.rods[1].length);
    previous = s;
    for (int k = 0; k < 3; ++k) total[k] += std::stod(fields[6 + k]);
  }
  BOOST_CHECK_SMALL((total - post.json_contact_force).norm(), 1e-12);
}
