#include <cstdio>
#include <fstream>

#include "pcr/core/error.hpp"
#include "pcr/robots/io/obstacle_geometry.hpp"
#include "pcr/robots/io/robot_outline.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

namespace {

struct Cell {
  std::vector<int> points;
  int part = 0;
  int obstacle = -1;
};

/// The points with their contact force arrays, and the cells, of a solved robot.
struct PolyData {
  std::string path;  // for messages
  std::vector<Vec3> points, forces, densities;
  std::vector<Cell> vertices, lines, polygons;

  Cell add_points(const std::vector<Vec3>& xs, const std::string& what) {
    Cell cell;
    for (const Vec3& x : xs) {
      require(x.allFinite(), "write_solution_vtk: ", what,
              " has a non-finite coordinate; nothing written to '", path, "'");
      cell.points.push_back(static_cast<int>(points.size()));
      points.push_back(x);
    }
    forces.resize(points.size(), Vec3::Zero());
    densities.resize(points.size(), Vec3::Zero());
    return cell;
  }

  void add_rods_and_outlines(const RobotModel& model, const RobotSolution& solution,
                             const ContactForceSamples& contact) {
    for (size_t r = 0; r < solution.rods.size(); ++r) {
      Cell cell = add_points(solution.rods[r].centerline, "rod '" + solution.rods[r].name + "'");
      cell.part = static_cast<int>(r);
      for (size_t i = 0; i < cell.points.size(); ++i) {
        forces[cell.points[i]] = contact.nodal[r][i];
        densities[cell.points[i]] = contact.density[r][i];
      }
      if (cell.points.size() >= 2) lines.push_back(cell);
    }
    for (const Outline& outline : robot_outlines(model, solution)) {
      Cell cell = add_points(outline.points, "outline '" + outline.name + "'");
      cell.part = outline.platform < 0 ? -1 : -2 - outline.platform;
      if (outline.closed)
        polygons.push_back(cell);
      else if (cell.points.size() >= 2)
        lines.push_back(cell);
    }
  }

  /// Obstacle cells (part -1000 - k, obstacle k), then a vertex per concentrated contact force.
  void add_obstacles_and_point_forces(const RobotModel& model, const RobotSolution& solution,
                                      const ContactForceSamples& contact) {
    for (const ObstacleMesh& mesh : obstacle_meshes(model, solution)) {
      const Cell all = add_points(mesh.points, "obstacle '" + mesh.name + "'");
      auto cell_of = [&](const std::vector<int>& local) {
        Cell cell{{}, -1000 - mesh.obstacle, mesh.obstacle};
        for (int i : local) cell.points.push_back(all.points[i]);
        return cell;
      };
      for (int v : mesh.vertices) vertices.push_back(cell_of({v}));
      for (const std::vector<int>& line : mesh.lines) lines.push_back(cell_of(line));
      for (const std::vector<int>& polygon : mesh.polygons) polygons.push_back(cell_of(polygon));
    }
    for (size_t k = 0; k < contact.points.size(); ++k) {
      Cell cell = add_points({contact.points[k]}, "a concentrated contact force's point");
      cell.part = contact.rods[k];
      forces[cell.points[0]] = contact.forces[k];
      vertices.push_back(cell);
    }
  }
};

void write_vectors(std::ostream& file, const std::vector<Vec3>& xs) {
  char buffer[96];
  for (const Vec3& x : xs) {
    std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g\n", x[0], x[1], x[2]);
    file << buffer;
  }
}

void write_cells(std::ostream& file, const char* keyword, const std::vector<Cell>& cells) {
  if (cells.empty()) return;
  size_t size = 0;
  for (const Cell& c : cells) size += c.points.size() + 1;
  file << keyword << " " << cells.size() << " " << size << "\n";
  for (const Cell& c : cells) {
    file << c.points.size();
    for (int i : c.points) file << " " << i;
    file << "\n";
  }
}

}  // namespace

// Legacy VTK format ("File Formats for VTK Version 4.2", Kitware): header, POINTS, then the cells
// grouped VERTICES, LINES, POLYGONS, so CELL_DATA lists the vertices' values first, then the lines', then
// the polygons'. POINT_DATA: the contact forces (docs/results_format.md, "VTK").
void write_solution_vtk(const std::string& path, const RobotModel& model, const RobotSolution& solution) {
  PolyData data;
  data.path = path;
  const ContactForceSamples contact = contact_force_samples(solution);
  data.add_rods_and_outlines(model, solution, contact);
  data.add_obstacles_and_point_forces(model, solution, contact);

  std::ofstream file(path);
  require(static_cast<bool>(file), "write_solution_vtk: cannot write '", path, "'");
  file << "# vtk DataFile Version 3.0\n"
       << "pcr " << model.name() << " " << to_string(solution.summary.status) << "\n"
       << "ASCII\nDATASET POLYDATA\n"
       << "POINTS " << data.points.size() << " double\n";
  write_vectors(file, data.points);
  write_cells(file, "VERTICES", data.vertices);
  write_cells(file, "LINES", data.lines);
  write_cells(file, "POLYGONS", data.polygons);
  file << "CELL_DATA " << data.vertices.size() + data.lines.size() + data.polygons.size() << "\n";
  for (const bool obstacle : {false, true}) {
    file << (obstacle ? "SCALARS obstacle int 1\n" : "SCALARS part int 1\n") << "LOOKUP_TABLE default\n";
    for (const std::vector<Cell>* cells : {&data.vertices, &data.lines, &data.polygons})
      for (const Cell& c : *cells) file << (obstacle ? c.obstacle : c.part) << "\n";
  }
  file << "POINT_DATA " << data.points.size() << "\nVECTORS contact_force double\n";
  write_vectors(file, data.forces);
  file << "VECTORS contact_force_density double\n";
  write_vectors(file, data.densities);
  file.close();
  require(!file.fail(), "write_solution_vtk: error while writing '", path, "'");
}

}  // namespace pcr
