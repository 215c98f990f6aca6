#include <cstdio>
#include <fstream>

#include "pcr/core/error.hpp"
#include "pcr/robots/io/robot_outline.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {

// Legacy VTK format ("File Formats for VTK Version 4.2", Kitware): header, POINTS, then the cells
// grouped LINES before POLYGONS, so CELL_DATA lists the lines' values first.
void write_solution_vtk(const std::string& path, const RobotModel& model, const RobotSolution& solution) {
  struct Cell {
    std::vector<int> points;
    int part;
  };
  std::vector<Vec3> points;
  std::vector<Cell> lines, polygons;
  auto add_points = [&](const std::vector<Vec3>& xs, const std::string& what) {
    Cell cell{{}, 0};
    for (const Vec3& x : xs) {
      require(x.allFinite(), "write_solution_vtk: ", what,
              " has a non-finite coordinate; nothing written to '", path, "'");
      cell.points.push_back(static_cast<int>(points.size()));
      points.push_back(x);
    }
    return cell;
  };
  for (size_t r = 0; r < solution.rods.size(); ++r) {
    Cell cell = add_points(solution.rods[r].centerline, "rod '" + solution.rods[r].name + "'");
    cell.part = static_cast<int>(r);
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

  std::ofstream file(path);
  require(static_cast<bool>(file), "write_solution_vtk: cannot write '", path, "'");
  file << "# vtk DataFile Version 3.0\n"
       << "pcr " << model.name() << " " << to_string(solution.summary.status) << "\n"
       << "ASCII\nDATASET POLYDATA\n"
       << "POINTS " << points.size() << " double\n";
  char buffer[96];
  for (const Vec3& x : points) {
    std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g\n", x[0], x[1], x[2]);
    file << buffer;
  }
  auto write_cells = [&](const char* keyword, const std::vector<Cell>& cells) {
    if (cells.empty()) return;
    size_t size = 0;
    for (const Cell& c : cells) size += c.points.size() + 1;
    file << keyword << " " << cells.size() << " " << size << "\n";
    for (const Cell& c : cells) {
      file << c.points.size();
      for (int i : c.points) file << " " << i;
      file << "\n";
    }
  };
  write_cells("LINES", lines);
  write_cells("POLYGONS", polygons);
  file << "CELL_DATA " << lines.size() + polygons.size() << "\nSCALARS part int 1\nLOOKUP_TABLE default\n";
  for (const Cell& c : lines) file << c.part << "\n";
  for (const Cell& c : polygons) file << c.part << "\n";
  file.close();
  require(!file.fail(), "write_solution_vtk: error while writing '", path, "'");
}

}  // namespace pcr
