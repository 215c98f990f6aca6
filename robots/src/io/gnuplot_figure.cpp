#include "pcr/robots/io/gnuplot_figure.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pcr/robots/io/robot_outline.hpp"
#include "pcr/solve/solve_summary.hpp"

namespace pcr {
namespace {

namespace fs = std::filesystem;
constexpr double kMillimetre = 1e3;

/// 'text' for a POSIX shell: single quotes, an inner ' written as '\''.
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// 'text' for gnuplot: single-quoted strings take everything literally except '' for a quote.
std::string gnuplot_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

/// A fresh directory under the system's temporary directory (mkdtemp: unique, mode 0700).
std::string make_temporary_directory() {
  std::string pattern = (fs::temp_directory_path() / "pcr-figure-XXXXXX").string();
  if (!mkdtemp(pattern.data())) return "";
  return pattern;
}

void write_point(std::ostream& out, const Vec3& x) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%.9g %.9g %.9g\n", x[0] * kMillimetre, x[1] * kMillimetre,
                x[2] * kMillimetre);
  out << buffer;
}

std::string read_text(const fs::path& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

FigureOutcome write_solution_png(const std::string& png_path, const RobotModel& model,
                                 const RobotSolution& solution, const std::string& title_suffix,
                                 const std::string& gnuplot) {
  FigureOutcome outcome;
  for (const RodResult& rod : solution.rods)
    for (const Vec3& x : rod.centerline)
      if (!x.allFinite()) {
        outcome.message = "rod '" + rod.name + "' has non-finite coordinates; no picture drawn";
        return outcome;
      }
  if (std::system(("command -v " + shell_quote(gnuplot) + " > /dev/null 2>&1").c_str()) != 0) {
    outcome.message =
        "gnuplot is not installed (no '" + gnuplot + "' on PATH): install it (apt-get install gnuplot-nox)";
    return outcome;
  }
  const std::string directory = make_temporary_directory();
  if (directory.empty()) {
    outcome.message = "cannot create a temporary directory under " + fs::temp_directory_path().string();
    return outcome;
  }
  const fs::path dir(directory);
  // Two blank lines end a gnuplot data set, so separate rods or outlines are never joined.
  {
    std::ofstream rods(dir / "rods.dat");
    for (const RodResult& rod : solution.rods) {
      for (const Vec3& x : rod.centerline) write_point(rods, x);
      rods << "\n\n";
    }
    std::ofstream base(dir / "base.dat"), platforms(dir / "platforms.dat");
    for (const Outline& outline : robot_outlines(model, solution)) {
      std::ofstream& out = outline.platform < 0 ? base : platforms;
      for (const Vec3& x : outline.points) write_point(out, x);
      if (outline.closed) write_point(out, outline.points.front());  // close the polygon
      out << "\n\n";
    }
    // gnuplot refuses an empty data file: a cantilever has no platform; write a NaN point it skips
    if (model.platforms().empty()) platforms << "NaN NaN NaN\n";
  }
  // Equal scales: every axis spans the same length (the largest extent plus a margin), centred on
  // the robot's bounding box, so the cube of ranges fits the picture whatever the robot's shape.
  Vec3 lower = Vec3::Constant(1e300), upper = Vec3::Constant(-1e300);
  auto extend = [&](const Vec3& x) {
    lower = lower.cwiseMin(x);
    upper = upper.cwiseMax(x);
  };
  for (const RodResult& rod : solution.rods)
    for (const Vec3& x : rod.centerline) extend(x);
  for (const Outline& outline : robot_outlines(model, solution))
    for (const Vec3& x : outline.points) extend(x);
  if (!(lower.array() <= upper.array()).all()) lower = upper = Vec3::Zero();
  const Vec3 centre = 0.5 * (lower + upper) * kMillimetre;
  const double half = std::max(0.55 * (upper - lower).maxCoeff() * kMillimetre, 1.0);
  const std::string absolute_png = fs::absolute(png_path).string();
  const std::string title = model.name() + (title_suffix.empty() ? "" : " - " + title_suffix) + ": " +
                            to_string(solution.summary.status);
  {
    std::ofstream script(dir / "figure.gp");
    script << "set terminal pngcairo size 1000,900 noenhanced font 'Sans,11'\n"
           << "set output " << gnuplot_quote(absolute_png) << "\n"
           << "set title " << gnuplot_quote(title) << "\n"
           << "set xlabel 'x [mm]'\nset ylabel 'y [mm]'\nset zlabel 'z [mm]' rotate parallel\n"
           << "set view equal xyz\nset view 68, 30, 1.3\nset xyplane relative 0\nset grid\n"
           << "set key top right\n";
    const char* axes = "xyz";
    for (int k = 0; k < 3; ++k)
      script << "set " << axes[k] << "range [" << centre[k] - half << ":" << centre[k] + half << "]\n";
    script
        << "splot 'rods.dat' with lines lw 2.5 lc rgb '#1f5fbf' title 'rods', \\\n"
        << "      'platforms.dat' with linespoints lw 3 pt 7 ps 1.2 lc rgb '#d62728' title 'platform', \\\n"
        << "      'base.dat' with linespoints lw 2 dt 2 pt 5 ps 1 lc rgb '#303030' title 'base'\n";
  }
  std::error_code error;
  fs::remove(absolute_png, error);  // so that a stale picture never passes for a new one
  const fs::path log = dir / "gnuplot.log";
  const std::string command = "cd " + shell_quote(directory) + " && " + shell_quote(gnuplot) +
                              " figure.gp > " + shell_quote(log.string()) + " 2>&1";
  const int status = std::system(command.c_str());
  const bool written = fs::exists(absolute_png, error) && fs::file_size(absolute_png, error) > 0;
  if (status != 0 || !written) {
    outcome.message = "gnuplot failed (exit status " + std::to_string(status) + ") drawing '" + png_path +
                      "'; script and data kept in " + directory + ": " + read_text(log);
    return outcome;
  }
  fs::remove_all(dir, error);
  outcome.ok = true;
  return outcome;
}

}  // namespace pcr
