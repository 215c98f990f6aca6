#pragma once
// A 3-D picture of a solved robot drawn by gnuplot (an external program): rods as lines, the
// platforms' and the base's outlines (robot_outline.hpp) as closed polygons, obstacles as wireframes
// and contact forces as arrows (obstacle_geometry.hpp), equal axis scales, mm.
// The data and the script go to a temporary directory, removed on success and kept on failure.
#include <string>
#include <utility>
#include <vector>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr {

/// Running gnuplot is an outcome like a solve: ok, or a message saying why not.
struct FigureOutcome {
  bool ok = false;
  std::string message;
};

/// The gnuplot script of write_solution_png (after its terminal and output lines) and its data files
/// (name, text): rods.dat, platforms.dat, base.dat; with obstacles obstacles.dat (their facets and lines
/// as closed polylines) and obstacle_points.dat; with active contacts contact_forces.dat (x y z dx dy dz
/// [mm] of an arrow per rod point or section carrying contact force, the longest 15 % of the axis span).
struct FigureScript {
  std::string script;
  std::vector<std::pair<std::string, std::string>> files;
};
FigureScript solution_figure_script(const RobotModel& model, const RobotSolution& solution,
                                    const std::string& title_suffix);

/// Writes png_path (pngcairo terminal, 1000 x 900 pixels). title_suffix goes after the model name in
/// the title, followed by the solve status. gnuplot = the program to run (looked up on PATH).
FigureOutcome write_solution_png(const std::string& png_path, const RobotModel& model,
                                 const RobotSolution& solution, const std::string& title_suffix,
                                 const std::string& gnuplot = "gnuplot");

}  // namespace pcr
