#include <filesystem>
#include <fstream>

#include "contact_csv.hpp"
#include "csv_fields.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/io/solution_writers.hpp"

namespace pcr {
namespace {

using io_detail::csv_number;

std::ofstream open_file(const std::filesystem::path& path) {
  std::ofstream file(path);
  require(static_cast<bool>(file), "cannot write '", path.string(), "'");
  return file;
}

void close_file(std::ofstream& file, const std::filesystem::path& path) {
  file.close();
  require(!file.fail(), "error while writing '", path.string(), "'");
}

}  // namespace

std::string rod_csv_file_name(const std::string& rod_name) {
  std::string safe = rod_name;
  for (char& c : safe) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
                    c == '_' || c == '-';
    if (!ok) c = '_';
  }
  return "rod_" + safe + ".csv";
}

void write_solution_csv(const std::string& directory, const RobotModel& model,
                        const RobotSolution& solution) {
  namespace fs = std::filesystem;
  const fs::path dir(directory);
  std::error_code error;
  fs::create_directories(dir, error);
  require(fs::is_directory(dir), "write_solution_csv: cannot create directory '", directory, "'",
          error ? " (" + error.message() + ")" : std::string());

  const fs::path summary_path = dir / "summary.csv";
  std::ofstream summary = open_file(summary_path);
  summary << io_detail::kCsvSummaryHeader << ',' << io_detail::kCsvStabilityHeader << '\n'
          << io_detail::csv_summary(solution.summary) << ','
          << io_detail::csv_stability(solution.stability_verdict) << '\n';
  close_file(summary, summary_path);

  const fs::path platforms_path = dir / "platforms.csv";
  std::ofstream platforms = open_file(platforms_path);
  platforms << "platform,x,y,z,qw,qx,qy,qz\n";
  for (size_t p = 0; p < solution.platforms.size() && p < model.platforms().size(); ++p) {
    const Pose& pose = solution.platforms[p];
    platforms << model.platforms()[p].name;
    for (int k = 0; k < 3; ++k) platforms << ',' << csv_number(pose.position[k]);
    for (int k = 0; k < 4; ++k) platforms << ',' << csv_number(pose.orientation[k]);
    platforms << '\n';
  }
  close_file(platforms, platforms_path);

  const fs::path inputs_path = dir / "inputs.csv";
  std::ofstream inputs = open_file(inputs_path);
  inputs << "input,kind,value,lower,upper\n";
  for (size_t i = 0; i < model.inputs().size() && static_cast<int>(i) < solution.inputs.size(); ++i) {
    const ActuationInput& input = model.inputs()[i];
    inputs << input.name << ','
           << (input.kind == ActuationInput::Kind::RodLength ? "rod_length" : "joint_value") << ','
           << csv_number(solution.inputs[static_cast<int>(i)]) << ',' << csv_number(input.lower) << ','
           << csv_number(input.upper) << '\n';
  }
  close_file(inputs, inputs_path);

  for (const RodResult& rod : solution.rods) {
    const fs::path path = dir / rod_csv_file_name(rod.name);
    std::ofstream file = open_file(path);
    file << "s,x,y,z\n";
    const size_t n = rod.centerline.size();
    for (size_t k = 0; k < n; ++k) {
      // RodResult::centerline is sampled at equally spaced arc lengths from 0 to L.
      const double s = n > 1 ? rod.length * static_cast<double>(k) / static_cast<double>(n - 1) : 0.0;
      file << csv_number(s);
      for (int c = 0; c < 3; ++c) file << ',' << csv_number(rod.centerline[k][c]);
      file << '\n';
    }
    close_file(file, path);
  }
  io_detail::write_contact_csv(dir, model, solution);
}

}  // namespace pcr
