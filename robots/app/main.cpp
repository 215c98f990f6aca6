// The pcr command-line tool.
#include <cstring>
#include <iostream>
#include <string>

#include "demo_basis.hpp"
#include "pcr/robots/version.hpp"

namespace {

void print_usage(std::ostream& out) {
  out << "pcr " << pcr::version() << " — parallel continuum robots\n"
      << "usage: pcr <command> [options]\n"
      << "commands:\n"
      << "  demo [--out DIR]   spline basis tables and a sample curve; with --out also DIR/basis.csv\n";
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
    return argc < 2 ? 1 : 0;
  }
  if (std::strcmp(argv[1], "demo") == 0) return demo_command(argc, argv);
  std::cerr << "pcr: unknown command '" << argv[1] << "'\n";
  return 1;
}
