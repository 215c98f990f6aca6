#include "pcr/robots/io/gnuplot_figure.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "gnuplot_run.hpp"
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

}  // namespace

FigureOutcome write_solution_png(const std::string& png_path, const RobotModel& model,
                                 const RobotSolution& solution, const std::string& title_suffix,
                                 const std::string& gnuplot) {
  for (const RodResult& rod : solution.rods)
    for (const Vec3& x : rod.centerline)
      if (!x.allFinite())
        return {false, "rod '" + rod.name + "' has non-finite coordinates; no picture drawn"};
  const std::vector<Outline> outlines = robot_outlines(model, solution);
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
  script << "splot 'rods.dat' with lines lw 2.5 lc rgb '#1f5fbf' title 'rods', \\\n"
         << "      'platforms.dat' with linespoints lw 3 pt 7 ps 1.2 lc rgb '#d62728' title 'platform', \\\n"
         << "      'base.dat' with linespoints lw 2 dt 2 pt 5 ps 1 lc rgb '#303030' title 'base'\n";
  return io_detail::run_gnuplot(png_path, 1000, 900, robot_data(model, solution, outlines), script.str(),
                                gnuplot);
}

}  // namespace pcr
