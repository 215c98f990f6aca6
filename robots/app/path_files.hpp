#pragma once
// The CSV files of `pcr path`: --inputs (a column per input, named after it) and --targets (columns
// LINK.x, LINK.y, LINK.z, LINK.qw, LINK.qx, LINK.qy, LINK.qz). Format: docs/cli.md "Paths".
#include <string>
#include <vector>

#include "pcr/robots/kinematics.hpp"

namespace pcr_app {

/// A CSV of numbers: a header line of names, then rows of as many numbers. Blank lines and lines
/// starting with '#' are skipped; spaces around fields are ignored.
struct NumberTable {
  std::string file;
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::vector<int> lines;  ///< the file's line number of each row
};

/// Reads FILE; UsageError naming file and line for a missing file, a row of the wrong length, a field
/// that is not a finite number, no header or no row.
NumberTable read_number_table(const std::string& file);

/// The inputs of each row: `base` (the model's defaults with --input) with the table's columns set.
/// UsageError for a column that names no input (listing them) or a value outside its bounds (file, line
/// and column).
std::vector<pcr::VecX> path_inputs(const pcr::RobotModel& model, const NumberTable& table,
                                   const pcr::VecX& base);

/// Targets of a path: one LinkTarget per link named in the header (mode and components by its columns:
/// a position component where its column is given, the orientation where qw, qx, qy, qz all are), the
/// poses of each row. UsageError for an unknown component, a repeated column or a partial quaternion.
struct TargetPath {
  std::vector<pcr::LinkTarget> targets;
  std::vector<std::vector<pcr::Pose>> poses;  ///< per row, one per target
};
TargetPath path_targets(const pcr::RobotModel& model, const NumberTable& table);

}  // namespace pcr_app
