// pcr workspace MODEL --samples N [--threads T] [--seed S] [options]: random inputs within the bounds,
// forward kinematics in T threads (workspace.hpp), the reached platform poses.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "pcr/core/error.hpp"
#include "pcr/robots/io/workspace_writers.hpp"
#include "progress_bar.hpp"
#include "solve_command.hpp"

namespace pcr_app {
namespace {

/// "stability: 812 stable, 180 unstable, ..." over the checked samples (nothing when none was checked).
void write_verdict_counts(std::ostream& out, const pcr::WorkspaceResult& r) {
  std::map<std::string, std::int64_t> counts;
  for (const pcr::WorkspaceSample& s : r.samples)
    if (s.stability.verdict != pcr::StabilityVerdict::NotChecked) ++counts[to_string(s.stability.verdict)];
  if (counts.empty()) return;
  out << "stability:";
  const char* separator = " ";
  for (const char* verdict : {"stable", "unstable", "critical", "unknown"}) {
    if (!counts.count(verdict)) continue;
    out << separator << counts[verdict] << ' ' << verdict;
    separator = ", ";
  }
  out << " (of the converged samples)\n";
}

/// Counts, time and per platform the box of the reached positions [mm] and the largest tilt [deg].
void write_workspace_summary(std::ostream& out, const pcr::RobotModel& model, const pcr::WorkspaceResult& r) {
  const std::int64_t n = static_cast<std::int64_t>(r.samples.size());
  char line[256];
  std::snprintf(
      line, sizeof line,
      "model %s workspace: %lld samples (seed %llu, from %lld), %lld converged, %lld failed; %d thread%s, "
      "%.3f s\n",
      model.name().c_str(), static_cast<long long>(n), static_cast<unsigned long long>(r.seed),
      static_cast<long long>(r.first_sample), static_cast<long long>(n - r.failures),
      static_cast<long long>(r.failures), r.threads, r.threads == 1 ? "" : "s", r.wall_time_seconds);
  out << line;
  if (r.failures == n) return;
  write_verdict_counts(out, r);
  out << "reached positions [mm]:   x from    to      y from    to      z from    to   max tilt [deg]\n";
  for (size_t p = 0; p < model.platforms().size(); ++p) {
    pcr::Vec3 lower = pcr::Vec3::Constant(1e300), upper = pcr::Vec3::Constant(-1e300);
    double tilt = 0.0;
    for (const pcr::WorkspaceSample& s : r.samples) {
      if (!s.converged()) continue;
      lower = lower.cwiseMin(s.platforms[p].position * 1e3);
      upper = upper.cwiseMax(s.platforms[p].position * 1e3);
      tilt = std::max(tilt,
                      std::acos(std::clamp(s.platforms[p].rotation()(2, 2), -1.0, 1.0)) * 57.295779513082321);
    }
    std::snprintf(line, sizeof line, "  %-20s %8.1f %8.1f   %8.1f %8.1f   %8.1f %8.1f   %8.2f\n",
                  model.platforms()[p].name.c_str(), lower[0], upper[0], lower[1], upper[1], lower[2],
                  upper[2], tilt);
    out << line;
  }
}

int write_workspace_outputs(const SolveArguments& args, const pcr::RobotModel& model,
                            const pcr::WorkspaceResult& result, std::ostream& out, std::ostream& err) {
  int code = kConverged;
  try {
    if (args.json) {
      pcr::write_workspace_json(out, model, result);
    } else {
      write_workspace_summary(out, model, result);
    }
    if (!args.json_file.empty()) {
      std::ofstream file = open_output("--json-file", args.json_file);
      pcr::write_workspace_json(file, model, result);
      close_output(file, "--json-file", args.json_file);
    }
    if (!args.csv.empty()) {
      std::ofstream file = open_output("--csv", args.csv);
      pcr::write_workspace_csv(file, model, result);
      close_output(file, "--csv", args.csv);
    }
  } catch (const pcr::InputError& e) {
    err << "pcr workspace: " << e.what() << "\n";
    code = kOutputFailed;
  }
  if (!args.png_path.empty()) {
    make_parent_directories(args.png_path);
    const pcr::FigureOutcome figure = pcr::write_workspace_png(
        args.png_path, model, result,
        std::to_string(result.threads) + " thread" + (result.threads == 1 ? "" : "s"));
    if (!figure.ok) {
      err << "pcr workspace: --png " << args.png_path << ": " << figure.message << "\n";
      code = kOutputFailed;
    }
  }
  return code;
}

}  // namespace

int workspace_command(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  const SolveArguments args = parse_solve_arguments("workspace", argc, argv, 2);
  if (args.help) {
    print_solve_usage(out, "workspace");
    return kConverged;
  }
  const std::shared_ptr<const pcr::RobotModel> model = load_model(args.model_path);
  pcr::WorkspaceOptions options;
  options.samples = args.samples;
  options.threads = args.threads;
  options.seed = args.seed;
  options.kinematics = kinematics_options(args);
  const auto assembly = std::make_shared<const pcr::RobotAssembly>(model, options.kinematics.assembly);
  ProgressBar bar(err, "pcr workspace", args.samples, stderr_is_terminal());
  options.progress = [&bar](std::int64_t done, std::int64_t) { bar.update(done); };
  const pcr::WorkspaceResult result = pcr::sample_workspace(assembly, options);
  bar.finish();
  const int written = write_workspace_outputs(args, *model, result, out, err);
  if (result.failures == static_cast<std::int64_t>(result.samples.size())) {
    err << "pcr workspace: no sample converged\n";
    return kSolveFailed;
  }
  return written;
}

}  // namespace pcr_app
