#include "cli_arguments.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "pcr/robots/robot_assembly.hpp"

namespace pcr_app {
namespace {

/// The commands that accept each option (a space-separated list); options not listed are unknown.
struct OptionScope {
  const char* option;
  const char* commands;
};
constexpr OptionScope kOptionScopes[] = {
    {"--input", "fk ik path"},
    {"--target", "ik"},
    {"--orientation-only", "ik"},
    {"--components", "ik path"},
    {"--link", "fk ik path"},
    {"--inputs", "path"},
    {"--folds", "path"},
    {"--targets", "path"},
    {"--samples", "workspace"},
    {"--threads", "workspace"},
    {"--seed", "workspace"},
    {"--solver", "fk path"},
    {"--contact-method", "fk path"},
    {"--degree", "fk ik path workspace"},
    {"--elements", "fk ik path workspace"},
    {"--formulation", "fk ik path workspace"},
    {"--mixed-points", "fk ik path workspace"},
    {"--tolerance", "fk ik path workspace"},
    {"--points", "fk ik path"},
    {"--objective", "ik path"},
    {"--max-stress", "ik path"},
    {"--json-file", "fk ik path workspace"},
    {"--csv", "fk ik path workspace"},
    {"--vtk", "fk ik"},
    {"--png", "fk ik workspace"},
};

bool accepts(const std::string& command, const std::string& option) {
  for (const OptionScope& scope : kOptionScopes)
    if (option == scope.option)
      return (" " + std::string(scope.commands) + " ").find(" " + command + " ") != std::string::npos;
  return false;
}

double parse_integer(const std::string& text, const std::string& option, double minimum, double maximum) {
  const double value = parse_number(text, option);
  if (value != std::floor(value) || value < minimum || value > maximum) {
    std::ostringstream message;
    message << std::fixed << std::setprecision(0) << option << " " << text << ": expected an integer from "
            << minimum << " to " << maximum;
    throw UsageError(message.str());
  }
  return value;
}

int parse_count(const std::string& text, const std::string& option, int minimum) {
  return static_cast<int>(parse_integer(text, option, minimum, 1e6));
}

std::uint64_t parse_seed(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || text[0] == '-' || text[0] == '+' || end != text.c_str() + text.size() ||
      errno == ERANGE)
    throw UsageError("--seed " + text + ": expected an integer from 0 to 18446744073709551615");
  return value;
}

NamedArgument parse_named(const std::string& option, const std::string& text) {
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size())
    throw UsageError(option + " " + text + ": expected NAME=VALUE");
  return {option, text.substr(0, equals), text.substr(equals + 1)};
}

std::string expect(const std::string& option, const std::string& value,
                   std::initializer_list<const char*> valid) {
  std::string list;
  for (const char* v : valid) {
    if (value == v) return value;
    list += (list.empty() ? "" : ", ") + std::string(v);
  }
  throw UsageError(option + " " + value + ": expected one of " + list);
}

/// Options of the rods' discretisation, the solve and the outputs; false when `arg` is not one of them.
bool apply_solve_option(SolveArguments& a, const std::string& arg, const std::string& value) {
  if (arg == "--solver") {
    a.solver = expect(arg, value, {"newton", "ipopt"});
  } else if (arg == "--contact-method") {
    a.contact_method = expect(arg, value, {"semismooth", "ipopt"});
  } else if (arg == "--degree") {
    a.degree = parse_count(value, arg, 2);
  } else if (arg == "--elements") {
    a.elements = parse_count(value, arg, 1);
  } else if (arg == "--formulation") {
    a.formulation = expect(arg, value, {"auto", "mixed", "condensed", "primal"});
  } else if (arg == "--mixed-points") {
    a.mixed_points = expect(arg, value, {"midpoints", "greville"});
  } else if (arg == "--objective") {
    a.objective = expect(arg, value, {"distance", "effort", "energy"});
  } else if (arg == "--max-stress") {
    a.max_stress = parse_number(value, arg);
    if (!(a.max_stress > 0.0)) throw UsageError("--max-stress " + value + ": must be positive (Pa)");
  } else if (arg == "--tolerance") {
    a.tolerance = parse_number(value, arg);
    if (!(a.tolerance > 0.0)) throw UsageError("--tolerance " + value + ": must be positive");
  } else if (arg == "--folds") {
    a.folds = expect(arg, value, {"stop", "snap"});
  } else if (arg == "--points") {
    a.centerline_points = parse_count(value, arg, 2);
  } else if (arg == "--json-file") {
    a.json_file = value;
  } else if (arg == "--csv") {
    a.csv = value;
  } else if (arg == "--vtk") {
    a.vtk_path = value;
  } else if (arg == "--png") {
    a.png_path = value;
  } else {
    return false;
  }
  return true;
}

/// What to solve for: inputs, targets, files of them, samples.
void apply_problem_option(SolveArguments& a, const std::string& arg, const std::string& value) {
  if (arg == "--input") {
    a.inputs.push_back(parse_named(arg, value));
  } else if (arg == "--target" || arg == "--orientation-only") {
    a.targets.push_back(parse_named(arg, value));
  } else if (arg == "--components") {
    a.components.push_back(parse_named(arg, value));
  } else if (arg == "--link") {
    a.links.push_back(value);
  } else if (arg == "--inputs") {
    a.inputs_file = value;
  } else if (arg == "--targets") {
    a.targets_file = value;
  } else if (arg == "--samples") {
    a.samples = static_cast<std::int64_t>(parse_integer(value, arg, 1, 1e8));
  } else if (arg == "--threads") {
    a.threads = static_cast<int>(parse_integer(value, arg, 1, 256));
  } else if (arg == "--seed") {
    a.seed = parse_seed(value);
  }
}

/// What each command needs besides its options.
void check_command(const SolveArguments& a) {
  if (a.model_path.empty()) throw UsageError("missing MODEL (a URDF file)");
  if (a.command == "ik" && a.targets.empty())
    throw UsageError(
        "no target (give --target LINK=x,y,z[,qw,qx,qy,qz] or --orientation-only LINK=qw,qx,qy,qz)");
  if (a.command == "path") {
    if (a.inputs_file.empty() == a.targets_file.empty())
      throw UsageError(
          "give one of --inputs FILE.csv (forward kinematics along its rows) or --targets "
          "FILE.csv (inverse kinematics along its rows)");
    if (!a.inputs_file.empty() && (!a.components.empty() || !a.objective.empty() || a.max_stress > 0.0))
      throw UsageError("--components, --objective and --max-stress are for a path of --targets");
    if (!a.folds.empty() && (a.inputs_file.empty() || a.solver == "ipopt"))
      throw UsageError("--folds is for a path of --inputs solved by Newton");
    if (!a.targets_file.empty() && !a.solver.empty())
      throw UsageError("--solver is for a path of --inputs (inverse kinematics picks its solver)");
  }
  if (a.command == "workspace" && a.samples <= 0) throw UsageError("missing --samples N");
}

}  // namespace

double parse_number(const std::string& text, const std::string& what) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || errno == ERANGE || !std::isfinite(value))
    throw UsageError(what + ": '" + text + "' is not a finite number");
  return value;
}

std::vector<double> parse_numbers(const std::string& text, const std::string& what) {
  std::vector<double> values;
  std::string item;
  std::istringstream stream(text);
  while (std::getline(stream, item, ',')) values.push_back(parse_number(item, what));
  if (!text.empty() && text.back() == ',') throw UsageError(what + ": trailing comma");
  return values;
}

SolveArguments parse_solve_arguments(const std::string& command, int argc, const char* const* argv,
                                     int first) {
  SolveArguments a;
  a.command = command;
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      a.help = true;
    } else if (arg == "--json") {
      a.json = true;
    } else if (arg == "--stability" &&
               (command == "fk" || command == "ik" || command == "path" || command == "workspace")) {
      a.stability = true;
    } else if (arg.size() > 1 && arg[0] == '-') {
      if (!accepts(command, arg))
        throw UsageError("unknown option '" + arg + "' for pcr " + command + " (see pcr " + command +
                         " --help)");
      if (i + 1 >= argc) throw UsageError(arg + ": missing value");
      const std::string value = argv[++i];
      if (!apply_solve_option(a, arg, value)) apply_problem_option(a, arg, value);
    } else if (!a.model_path.empty()) {
      throw UsageError("unexpected argument '" + arg + "' (the model is already '" + a.model_path + "')");
    } else {
      a.model_path = arg;
    }
  }
  if (a.help) return a;
  if (a.elements > 0) {
    // Rejected before the model is read when one rod could not fit in memory (rod_memory_estimate).
    const int degree = a.degree > 0 ? a.degree : pcr::AssemblyOptions{}.discretization.degree;
    const std::string excess = pcr::rod_memory_excess(degree, a.elements);
    if (!excess.empty()) throw UsageError("--elements " + std::to_string(a.elements) + ": " + excess);
  }
  check_command(a);
  return a;
}

}  // namespace pcr_app
