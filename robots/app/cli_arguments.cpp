#include "cli_arguments.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "pcr/robots/robot_assembly.hpp"

namespace pcr_app {
namespace {

int parse_count(const std::string& text, const std::string& option, int minimum) {
  const double value = parse_number(text, option);
  if (value != std::floor(value) || value < minimum || value > 1e6)
    throw UsageError(option + " " + text + ": expected an integer >= " + std::to_string(minimum));
  return static_cast<int>(value);
}

NamedArgument parse_named(const std::string& option, const std::string& text) {
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size())
    throw UsageError(option + " " + text + ": expected NAME=VALUE");
  return {option, text.substr(0, equals), text.substr(equals + 1)};
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
      continue;
    }
    if (arg == "--json") {
      a.json = true;
      continue;
    }
    if (arg == "--stability") {
      a.stability = true;
      continue;
    }
    if (arg.size() > 1 && arg[0] == '-') {
      if (i + 1 >= argc) throw UsageError(arg + ": missing value");
      const std::string value = argv[++i];
      if (arg == "--input") {
        a.inputs.push_back(parse_named(arg, value));
      } else if (arg == "--target" && command == "ik") {
        a.targets.push_back(parse_named(arg, value));
      } else if (arg == "--orientation-only" && command == "ik") {
        a.targets.push_back(parse_named(arg, value));
      } else if (arg == "--solver" && command == "fk") {
        if (value != "newton" && value != "ipopt")
          throw UsageError("--solver " + value + ": expected newton or ipopt");
        a.solver = value;
      } else if (arg == "--degree") {
        a.degree = parse_count(value, arg, 2);
      } else if (arg == "--elements") {
        a.elements = parse_count(value, arg, 1);
      } else if (arg == "--formulation") {
        if (value != "auto" && value != "mixed" && value != "primal" && value != "condensed")
          throw UsageError("--formulation " + value + ": expected auto, mixed, condensed or primal");
        a.formulation = value;
      } else if (arg == "--mixed-points") {
        if (value != "midpoints" && value != "greville")
          throw UsageError("--mixed-points " + value + ": expected midpoints or greville");
        a.mixed_points = value;
      } else if (arg == "--objective" && command == "ik") {
        if (value != "distance" && value != "effort" && value != "energy")
          throw UsageError("--objective " + value + ": expected distance, effort or energy");
        a.objective = value;
      } else if (arg == "--max-stress" && command == "ik") {
        a.max_stress = parse_number(value, arg);
        if (!(a.max_stress > 0.0)) throw UsageError("--max-stress " + value + ": must be positive (Pa)");
      } else if (arg == "--tolerance") {
        a.tolerance = parse_number(value, arg);
        if (!(a.tolerance > 0.0)) throw UsageError("--tolerance " + value + ": must be positive");
      } else if (arg == "--points") {
        a.centerline_points = parse_count(value, arg, 2);
      } else if (arg == "--json-file") {
        a.json_file = value;
      } else if (arg == "--csv") {
        a.csv_dir = value;
      } else if (arg == "--vtk") {
        a.vtk_path = value;
      } else if (arg == "--png") {
        a.png_path = value;
      } else {
        throw UsageError("unknown option '" + arg + "' for pcr " + command + " (see pcr " + command +
                         " --help)");
      }
      continue;
    }
    if (!a.model_path.empty())
      throw UsageError("unexpected argument '" + arg + "' (the model is already '" + a.model_path + "')");
    a.model_path = arg;
  }
  if (a.help) return a;
  if (a.elements > 0) {
    // Rejected before the model is read when one rod could not fit in memory (rod_memory_estimate).
    const int degree = a.degree > 0 ? a.degree : pcr::AssemblyOptions{}.discretization.degree;
    const std::string excess = pcr::rod_memory_excess(degree, a.elements);
    if (!excess.empty()) throw UsageError("--elements " + std::to_string(a.elements) + ": " + excess);
  }
  if (a.model_path.empty()) throw UsageError("missing MODEL (a URDF file)");
  if (command == "ik" && a.targets.empty())
    throw UsageError(
        "no target (give --target LINK=x,y,z[,qw,qx,qy,qz] or --orientation-only LINK=qw,qx,qy,qz)");
  return a;
}

void print_solve_usage(std::ostream& out, const std::string& command) {
  if (command == "fk")
    out << "usage: pcr fk MODEL [--input NAME=VALUE ...] [--solver newton|ipopt] [options]\n"
        << "  forward kinematics: inputs not given take the model's defaults (SI: m, rad)\n";
  else
    out << "usage: pcr ik MODEL --target LINK=x,y,z[,qw,qx,qy,qz] [--orientation-only LINK=qw,qx,qy,qz] ...\n"
        << "  inverse kinematics: position target (3 numbers, m) or pose target (7 numbers: position and\n"
        << "  unit quaternion w,x,y,z, normalised); --input NAME=VALUE sets the starting inputs\n"
        << "  --objective distance|effort|energy   what the inputs minimise among those reaching the\n"
        << "                     targets: distance to the starting inputs (default), actuation effort\n"
        << "                     (squared axial forces of the fed rods at their feed points) or the\n"
        << "                     elastic energy of all rods\n"
        << "  --max-stress PA    limit on every rod's outer-fibre stress |N|/A + |M_perp| c/I [Pa]\n";
  out << "options:\n"
      << "  --degree P --elements E --formulation auto|mixed|condensed|primal   discretisation of rods\n"
      << "                     without model hints (auto, the default: primal only for thick rods,\n"
      << "                     d/L >= 1/4, else mixed solved in the condensed form: n, m from the\n"
      << "                     closed-form balance; mixed keeps the mixed unknowns)\n"
      << "  --mixed-points midpoints|greville   where the mixed form collocates its field equations\n"
      << "                     (default midpoints; greville: the published scheme, README)\n"
      << "  --tolerance T      max-abs of the dimensionless residuals (default 1e-10); a looser T saves\n"
      << "                     iterations, e.g. for many solves along a path: on the teleoperation\n"
      << "                     robot (R5b) the solver added about 1e-2 T m to the inputs (README)\n"
      << "  --points N         centerline points per rod in the results (default 21)\n"
      << "  --stability        stability verdict of the result: stable, or unstable with the number\n"
      << "                     of unstable modes, and a margin (costs about one more cold solve)\n"
      << "  --json             JSON to stdout instead of the table\n"
      << "  --json-file FILE   JSON to FILE (the table is still printed)\n"
      << "  --csv DIR          DIR/platforms.csv, DIR/inputs.csv, DIR/rod_<name>.csv\n"
      << "  --vtk FILE         legacy VTK polydata (rods and outlines) for ParaView\n"
      << "  --png FILE         3-D picture drawn by gnuplot\n"
      << "exit codes: 0 converged, 1 solve failed, 2 bad usage or input (also an element count whose\n"
      << "                     rods could not fit in memory), 3 an output could not be written,\n"
      << "                     4 out of memory or an internal error (a message on stderr)\n";
}

}  // namespace pcr_app
