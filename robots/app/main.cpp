// The pcr command-line tool.
#include <cstring>
#include <iostream>

#include "pcr/robots/version.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0) {
    std::cout << "pcr " << pcr::version() << " — parallel continuum robots\n"
              << "usage: pcr <command> [options]\n";
    return argc < 2 ? 1 : 0;
  }
  std::cerr << "pcr: unknown command '" << argv[1] << "'\n";
  return 1;
}
