// The pcr command-line tool: dispatches to the subcommands.
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "demo_basis.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/version.hpp"
#include "solve_command.hpp"

namespace {

void print_usage(std::ostream& out) {
  out << "pcr " << pcr::version() << " — parallel continuum robots\n"
      << "usage: pcr <command> [options]\n"
      << "commands:\n"
      << "  fk MODEL [--input NAME=VALUE ...]        forward kinematics (pcr fk --help)\n"
      << "  ik MODEL --target LINK=x,y,z[,qw,qx,qy,qz]  inverse kinematics (pcr ik --help)\n"
      << "  path MODEL --inputs FILE.csv | --targets FILE.csv   FK or IK along the rows (pcr path --help)\n"
      << "  workspace MODEL --samples N [--threads T]   reachable poses from random inputs (pcr workspace\n"
      << "                     --help)\n"
      << "  demo [--out DIR]   spline basis tables and a sample curve; with --out also DIR/basis.csv\n"
      << "exit codes: 0 success, 1 solve failed, 2 bad usage or input, 3 an output could not be written,\n"
      << "            4 out of memory or an internal error (a message on stderr)\n";
}

// pcr demo [--out DIR]
int demo_command(int argc, char** argv) {
  std::string out_dir;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
      out_dir = argv[++i];
    } else {
      std::cerr << "pcr demo: unexpected argument '" << argv[i] << "' (usage: pcr demo [--out DIR])\n";
      return 1;
    }
  }
  return pcr_app::run_demo_basis(std::cout, std::cerr, out_dir);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0) {
    print_usage(std::cout);
    return argc < 2 ? pcr_app::kBadUsage : 0;
  }
  const std::string command = argv[1];
  if (command != "fk" && command != "ik" && command != "path" && command != "workspace" &&
      command != "demo") {
    std::cerr << "pcr: unknown command '" << command << "' (commands: fk, ik, path, workspace, demo)\n";
    return pcr_app::kBadUsage;
  }
  try {
    if (command == "demo") return demo_command(argc, argv);
    if (command == "fk") return pcr_app::fk_command(argc, argv, std::cout, std::cerr);
    if (command == "ik") return pcr_app::ik_command(argc, argv, std::cout, std::cerr);
    if (command == "path") return pcr_app::path_command(argc, argv, std::cout, std::cerr);
    return pcr_app::workspace_command(argc, argv, std::cout, std::cerr);
  } catch (const pcr_app::UsageError& e) {
    std::cerr << "pcr " << command << ": " << e.what() << "\n";
  } catch (const pcr::InputError& e) {  // bad model file, target link, ...
    std::cerr << "pcr " << command << ": " << e.what() << "\n";
  } catch (const std::bad_alloc&) {
    std::cerr << "pcr " << command
              << ": out of memory (fewer elements per rod, --elements, or a lower --degree need less)\n";
    return pcr_app::kInternalError;
  } catch (const std::exception& e) {
    std::cerr << "pcr " << command << ": internal error: " << e.what() << "\n";
    return pcr_app::kInternalError;
  } catch (...) {
    std::cerr << "pcr " << command << ": internal error (an unknown exception)\n";
    return pcr_app::kInternalError;
  }
  return pcr_app::kBadUsage;
}
