#pragma once
// Writers of a sampled workspace (workspace.hpp, `pcr workspace`): every sample with its status, the
// platform poses of the converged ones; a picture of the reachable positions. SI units, world frame;
// formats in docs/results_format.md.
#include <ostream>
#include <string>

#include "pcr/robots/io/gnuplot_figure.hpp"
#include "pcr/robots/workspace.hpp"

namespace pcr {

/// CSV, one row per sample: sample (its index), the inputs by name, NAME.x, .y, .z, .qw, .qx, .qy, .qz
/// per platform (empty fields when the sample failed), status, iterations, residual_max_abs,
/// wall_time_seconds, message (quoted), and where a sample has a verdict (WorkspaceOptions' kinematics
/// stability_verdict): stability, unstable_modes, stability_margin, stability_reason (as the path CSV).
void write_workspace_csv(std::ostream& out, const RobotModel& model, const WorkspaceResult& result);

/// JSON object {model, seed, first_sample, samples, failures, threads, wall_time_seconds, inputs: [names],
/// points: [{index, status, inputs, platforms (converged only), iterations, residual_max_abs, message,
/// stability (checked samples only: the object of the fk JSON)}],
/// non_finite_values}; returns how many numbers were not finite (written as null).
int write_workspace_json(std::ostream& out, const RobotModel& model, const WorkspaceResult& result);

/// PNG (gnuplot, 1400 x 1100): the converged samples' platform positions [mm] as a 3-D point cloud and
/// its three projections (top x-y, front x-z, side y-z), coloured by the platform's tilt (angle of its
/// z axis from the world z axis, deg); equal scales; title with the model, counts and title_suffix.
FigureOutcome write_workspace_png(const std::string& png_path, const RobotModel& model,
                                  const WorkspaceResult& result, const std::string& title_suffix,
                                  const std::string& gnuplot = "gnuplot");

}  // namespace pcr
