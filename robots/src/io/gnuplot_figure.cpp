#include "pcr/robots/io/gnuplot_figure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "gnuplot_run.hpp"
#include "pcr/robots/io/obstacle_geometry.hpp"
#include "pcr/robots/io/robot_outline.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {
namespace {

constexpr double kMillimetre = 1e3;

void write_point(std::ostream& out, const Vec3& x) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%.9g %.9g %.9g\n", x[0] * kMillimetre, x[1] * kMillimetre,
                x[2] * kMillimetre);
  out << buffer;
}

/// rods.dat, base.dat, platforms.dat: two blank lines end a gnuplot data set, so separate rods or
/// outlines are never joined.
std::vector<io_detail::GnuplotFile> robot_data(const RobotModel& model, const RobotSolution& solution,
                                               const std::vector<Outline>& outlines) {
  std::ostringstream rods, base, platforms;
  for (const RodResult& rod : solution.rods) {
    for (const Vec3& x : rod.centerline) write_point(rods, x);
    rods << "\n\n";
  }
  for (const Outline& outline : outlines) {
    std::ostringstream& out = outline.platform < 0 ? base : platforms;
    for (const Vec3& x : outline.points) write_point(out, x);
    if (outline.closed) write_point(out, outline.points.front());  // close the polygon
    out << "\n\n";
  }
  // gnuplot refuses an empty data file: a cantilever has no platform; write a NaN point it skips
  if (model.platforms().empty()) platforms << "NaN NaN NaN\n";
  return {{"rods.dat", rods.str()}, {"base.dat", base.str()}, {"platforms.dat", platforms.str()}};
}

/// obstacles.dat (every facet and line of the obstacles as a polyline, facets closed) and
/// obstacle_points.dat (point obstacles); empty texts when there are none.
void obstacle_data(const std::vector<ObstacleMesh>& meshes, std::string& lines, std::string& points) {
  std::ostringstream l, p;
  for (const ObstacleMesh& mesh : meshes) {
    for (const std::vector<int>& polygon : mesh.polygons) {
      for (int i : polygon) write_point(l, mesh.points[i]);
      write_point(l, mesh.points[polygon.front()]);
      l << "\n\n";
    }
    for (const std::vector<int>& line : mesh.lines) {
      for (int i : line) write_point(l, mesh.points[i]);
      l << "\n\n";
    }
    for (int i : mesh.vertices) write_point(p, mesh.points[i]);
  }
  lines = l.str();
  points = p.str();
}

/// contact_forces.dat: x y z dx dy dz [mm] per rod point (or section) with contact force, the longest
/// arrow `longest` mm; "" when no force acts. `largest` gets the largest force [N].
std::string force_data(const RobotSolution& solution, double longest, double& largest) {
  const ContactForceSamples samples = contact_force_samples(solution);
  std::vector<std::pair<Vec3, Vec3>> arrows;  // (point, force)
  for (size_t r = 0; r < samples.nodal.size(); ++r)
    for (size_t i = 0; i < samples.nodal[r].size(); ++i)
      if (samples.nodal[r][i].norm() > 0.0)
        arrows.push_back({solution.rods[r].centerline[i], samples.nodal[r][i]});
  for (size_t k = 0; k < samples.points.size(); ++k) arrows.push_back({samples.points[k], samples.forces[k]});
  largest = 0.0;
  for (const auto& arrow : arrows) largest = std::max(largest, arrow.second.norm());
  if (!(largest > 0.0) || !std::isfinite(largest)) return "";
  std::ostringstream out;
  char buffer[160];
  for (const auto& [x, f] : arrows) {
    const Vec3 d = f * (longest / largest);
    std::snprintf(buffer, sizeof buffer, "%.9g %.9g %.9g %.9g %.9g %.9g\n", x[0] * kMillimetre,
                  x[1] * kMillimetre, x[2] * kMillimetre, d[0], d[1], d[2]);
    out << buffer;
  }
  return out.str();
}

}  // namespace

FigureScript solution_figure_script(const RobotModel& model, const RobotSolution& solution,
                                    const std::string& title_suffix) {
  const std::vector<Outline> outlines = robot_outlines(model, solution);
  const std::vector<ObstacleMesh> meshes = obstacle_meshes(model, solution);
  // Equal scales: every axis spans the same length (the largest extent plus a margin), centred on
  // the robot's bounding box, so the cube of ranges fits the picture whatever the robot's shape.
  Vec3 lower = Vec3::Constant(1e300), upper = Vec3::Constant(-1e300);
  auto extend = [&](const Vec3& x) {
    lower = lower.cwiseMin(x);
    upper = upper.cwiseMax(x);
  };
  for (const RodResult& rod : solution.rods)
    for (const Vec3& x : rod.centerline) extend(x);
  for (const Outline& outline : outlines)
    for (const Vec3& x : outline.points) extend(x);
  for (const ObstacleMesh& mesh : meshes)
    for (const Vec3& x : mesh.points) extend(x);
  if (!(lower.array() <= upper.array()).all()) lower = upper = Vec3::Zero();
  const Vec3 centre = 0.5 * (lower + upper) * kMillimetre;
  const double half = std::max(0.55 * (upper - lower).maxCoeff() * kMillimetre, 1.0);
  const std::string title = model.name() + (title_suffix.empty() ? "" : " - " + title_suffix) + ": " +
                            to_string(solution.summary.status);
  std::ostringstream script;
  script << "set title " << io_detail::gnuplot_quote(title) << "\n"
         << "set xlabel 'x [mm]'\nset ylabel 'y [mm]'\nset zlabel 'z [mm]' rotate parallel\n"
         << "set view equal xyz\nset view 68, 30, 1.3\nset xyplane relative 0\nset grid\n"
         << "set key top right\n";
  const char* axes = "xyz";
  for (int k = 0; k < 3; ++k)
    script << "set " << axes[k] << "range [" << centre[k] - half << ":" << centre[k] + half << "]\n";
  FigureScript figure;
  for (io_detail::GnuplotFile& f : robot_data(model, solution, outlines))
    figure.files.emplace_back(std::move(f.name), std::move(f.text));
  script << "splot 'rods.dat' with lines lw 2.5 lc rgb '#1f5fbf' title 'rods', \\\n"
         << "      'platforms.dat' with linespoints lw 3 pt 7 ps 1.2 lc rgb '#d62728' title 'platform', \\\n"
         << "      'base.dat' with linespoints lw 2 dt 2 pt 5 ps 1 lc rgb '#303030' title 'base'";
  std::string obstacle_lines, obstacle_points;
  obstacle_data(meshes, obstacle_lines, obstacle_points);
  if (!obstacle_lines.empty()) {
    figure.files.emplace_back("obstacles.dat", obstacle_lines);
    script << ", \\\n      'obstacles.dat' with lines lw 1 lc rgb '#2ca02c' title 'obstacles'";
  }
  if (!obstacle_points.empty()) {
    figure.files.emplace_back("obstacle_points.dat", obstacle_points);
    script << ", \\\n      'obstacle_points.dat' with points pt 6 ps 1.5 lc rgb '#2ca02c' title 'obstacle "
              "points'";
  }
  double largest = 0.0;
  const std::string forces = force_data(solution, 0.15 * 2.0 * half, largest);
  if (!forces.empty()) {
    figure.files.emplace_back("contact_forces.dat", forces);
    char label[96];
    std::snprintf(label, sizeof label, "contact forces (longest %.3g N)", largest);
    script << ", \\\n      'contact_forces.dat' using 1:2:3:4:5:6 with vectors head filled lw 1.5 lc rgb "
              "'#ff7f0e' title "
           << io_detail::gnuplot_quote(label);
  }
  script << "\n";
  figure.script = script.str();
  return figure;
}

FigureOutcome write_solution_png(const std::string& png_path, const RobotModel& model,
                                 const RobotSolution& solution, const std::string& title_suffix,
                                 const std::string& gnuplot) {
  for (const RodResult& rod : solution.rods)
    for (const Vec3& x : rod.centerline)
      if (!x.allFinite())
        return {false, "rod '" + rod.name + "' has non-finite coordinates; no picture drawn"};
  const FigureScript figure = solution_figure_script(model, solution, title_suffix);
  std::vector<io_detail::GnuplotFile> files;
  for (const auto& [name, text] : figure.files) files.push_back({name, text});
  return io_detail::run_gnuplot(png_path, 1000, 900, files, figure.script, gnuplot);
}

}  // namespace pcr
