#pragma once
// Command-line arguments of `pcr fk`, `pcr ik`, `pcr path` and `pcr workspace` (one parser for all; each
// option is accepted by the commands listed in cli_arguments.cpp; usage in cli_usage.cpp).
#include <cstdint>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pcr_app {

/// Bad usage: exit code 2; the message names the offending argument.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A NAME=VALUE argument as given, with the option that carried it (for messages).
struct NamedArgument {
  std::string option;  ///< "--input", "--target", "--orientation-only", "--components"
  std::string name;
  std::string value;
  std::string text() const { return option + " " + name + "=" + value; }
};

struct SolveArguments {
  std::string command;                    ///< "fk", "ik", "path" or "workspace"
  std::string model_path;                 ///< the positional MODEL
  std::vector<NamedArgument> inputs;      ///< --input NAME=VALUE
  std::vector<NamedArgument> targets;     ///< --target and --orientation-only, in the order given
  std::vector<NamedArgument> components;  ///< --components LINK=x,y,z,rx,ry,rz (a subset)
  std::vector<std::string> links;         ///< --link NAME: more link poses to report
  std::string inputs_file, targets_file;  ///< path: --inputs FILE.csv or --targets FILE.csv
  std::int64_t samples = 0;               ///< workspace: --samples N
  int threads = 1;                        ///< workspace: --threads T
  std::uint64_t seed = 1;                 ///< workspace: --seed S
  std::string solver;                     ///< "", "newton" or "ipopt"
  std::string contact_method;             ///< fk, path: "", "semismooth" or "ipopt"
  int degree = 0, elements = 0;           ///< 0 = not given
  std::string formulation;                ///< "", "auto", "mixed", "condensed" or "primal"
  std::string mixed_points;               ///< "", "midpoints" or "greville"
  std::string objective;                  ///< ik, path: "", "distance", "effort" or "energy"
  double max_stress = 0.0;                ///< ik, path: rod stress limit [Pa], 0 = none
  double tolerance = 0.0;                 ///< 0 = not given
  int centerline_points = 0;              ///< 0 = not given
  bool json = false;
  bool stability = false;  ///< --stability (fk, ik, path): the stability verdict of the result
  /// path of --inputs: --folds stop|snap, pseudo-arclength continuation between the points, folds
  /// reported ("": the points solved one after the other by forward kinematics).
  std::string folds;
  /// --csv: a directory for fk and ik (one file per table), a file for path and workspace (one table).
  std::string json_file, csv, vtk_path, png_path;
  bool help = false;
};

/// Parses argv[first..argc) of `pcr <command> ...`; throws UsageError.
SolveArguments parse_solve_arguments(const std::string& command, int argc, const char* const* argv,
                                     int first);

/// A finite number, the whole text; throws UsageError naming `what`.
double parse_number(const std::string& text, const std::string& what);
/// Comma-separated finite numbers; throws UsageError naming `what`.
std::vector<double> parse_numbers(const std::string& text, const std::string& what);

void print_solve_usage(std::ostream& out, const std::string& command);

}  // namespace pcr_app
