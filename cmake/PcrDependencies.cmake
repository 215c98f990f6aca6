# Every dependency comes from Debian's packages (scripts/install-deps.sh).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)

# Ipopt 3.11.9 ships only a pkg-config file; keep its -DHAVE_CSTDDEF (needed by coin/IpTypes.hpp).
find_package(PkgConfig REQUIRED)
pkg_check_modules(IPOPT REQUIRED IMPORTED_TARGET ipopt)

# urdfdom 3.0 has no urdf_parser target: use the variables its config sets.
find_package(urdfdom REQUIRED)
# TinyXML (2.6) is what urdfdom itself parses with; pcr reads its extension elements with it.
find_path(TINYXML_INCLUDE_DIR tinyxml.h REQUIRED)
find_library(TINYXML_LIBRARY tinyxml REQUIRED)

if(PCR_BUILD_TESTS)
  find_package(Boost 1.71 REQUIRED COMPONENTS unit_test_framework)
endif()
if(PCR_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()
