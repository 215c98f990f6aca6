// Picture of a sampled workspace (workspace_writers.hpp): the converged samples' platform positions as a
// 3-D point cloud and its projections, coloured by tilt, drawn by gnuplot.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "gnuplot_run.hpp"
#include "pcr/robots/io/workspace_writers.hpp"

namespace pcr {
namespace {

constexpr double kMillimetre = 1e3;
constexpr double kDegree = 57.295779513082321;  // 180 / pi

/// Angle [rad] between a platform's z axis R e_z and the world's z axis: acos of R(2, 2).
double tilt(const Pose& pose) {
  return std::acos(std::clamp(pose.rotation()(2, 2), -1.0, 1.0));
}

std::string thousands(std::int64_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return out;
}

}  // namespace

FigureOutcome write_workspace_png(const std::string& png_path, const RobotModel& model,
                                  const WorkspaceResult& result, const std::string& title_suffix,
                                  const std::string& gnuplot) {
  std::ostringstream points;
  Vec3 lower = Vec3::Constant(1e300), upper = Vec3::Constant(-1e300);
  std::int64_t drawn = 0;
  for (const WorkspaceSample& s : result.samples) {
    if (!s.converged()) continue;
    for (const Pose& pose : s.platforms) {
      if (!pose.position.allFinite()) continue;
      const Vec3 x = pose.position * kMillimetre;
      lower = lower.cwiseMin(x);
      upper = upper.cwiseMax(x);
      char line[128];
      std::snprintf(line, sizeof line, "%.6f %.6f %.6f %.4f\n", x[0], x[1], x[2], tilt(pose) * kDegree);
      points << line;
      ++drawn;
    }
  }
  if (drawn == 0) return {false, "no converged sample: nothing to draw"};
  // Equal scales in all views: one half-width for every axis, centred on the cloud's bounding box.
  const Vec3 centre = 0.5 * (lower + upper);
  const double half = std::max(0.55 * (upper - lower).maxCoeff(), 1.0);
  auto range = [&](int k) {
    std::ostringstream r;
    r << "[" << centre[k] - half << ":" << centre[k] + half << "]";
    return r.str();
  };
  const std::int64_t reached = static_cast<std::int64_t>(result.samples.size()) - result.failures;
  const std::string title = model.name() + " workspace: " + thousands(reached) + " of " +
                            thousands(static_cast<std::int64_t>(result.samples.size())) +
                            " samples reached (" + thousands(result.failures) + " failed), seed " +
                            std::to_string(result.seed) + (title_suffix.empty() ? "" : " - " + title_suffix);
  std::ostringstream script;
  script << "set multiplot layout 2,2 title " << io_detail::gnuplot_quote(title) << "\n"
         << "set palette rgbformulae 22,13,-31\nset cblabel 'tilt [deg]'\nset grid\nunset key\n"
         << "set xrange " << range(0) << "\nset yrange " << range(1) << "\nset zrange " << range(2) << "\n"
         << "set title 'platform positions'\n"
         << "set xlabel 'x [mm]'\nset ylabel 'y [mm]'\nset zlabel 'z [mm]' rotate parallel\n"
         << "set view equal xyz\nset view 62, 32, 1.1\nset xyplane relative 0\n"
         << "unset colorbox\n"  // the projections carry the colour scale
         << "splot 'points.dat' using 1:2:3:4 with points pt 7 ps 0.35 lc palette\n"
         << "set colorbox\nset size ratio -1\n"
         << "set title 'top view'\nset xlabel 'x [mm]'\nset ylabel 'y [mm]'\n"
         << "plot 'points.dat' using 1:2:4 with points pt 7 ps 0.35 lc palette\n"
         << "set title 'front view'\nset ylabel 'z [mm]'\nset yrange " << range(2) << "\n"
         << "plot 'points.dat' using 1:3:4 with points pt 7 ps 0.35 lc palette\n"
         << "set title 'side view'\nset xlabel 'y [mm]'\nset xrange " << range(1) << "\n"
         << "plot 'points.dat' using 2:3:4 with points pt 7 ps 0.35 lc palette\n"
         << "unset multiplot\n";
  return io_detail::run_gnuplot(png_path, 1400, 1100, {{"points.dat", points.str()}}, script.str(), gnuplot);
}

}  // namespace pcr
