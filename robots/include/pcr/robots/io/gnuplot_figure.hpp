#pragma once
// A 3-D picture of a solved robot drawn by gnuplot (an external program): rods as lines, the
// platforms' and the base's outlines (robot_outline.hpp) as closed polygons, equal axis scales, mm.
// The data and the script go to a temporary directory, removed on success and kept on failure.
#include <string>

#include "pcr/robots/kinematics.hpp"
#include "pcr/robots/robot_model.hpp"

namespace pcr {

/// Running gnuplot is an outcome like a solve: ok, or a message saying why not.
struct FigureOutcome {
  bool ok = false;
  std::string message;
};

/// Writes png_path (pngcairo terminal, 1000 x 900 pixels). title_suffix goes after the model name in
/// the title, followed by the solve status. gnuplot = the program to run (looked up on PATH).
FigureOutcome write_solution_png(const std::string& png_path, const RobotModel& model,
                                 const RobotSolution& solution, const std::string& title_suffix,
                                 const std::string& gnuplot = "gnuplot");

}  // namespace pcr
