#pragma once
// `pcr demo`: a self-contained tour of the spline core (cubic basis, Greville points, a sample curve).
#include <iosfwd>
#include <string>

namespace pcr_app {

/// Prints the demo tables to `out`; when out_dir is not empty, also writes out_dir/basis.csv (u, N_i, N_i'
/// at 101 points; the directory is created if needed).
/// Returns the process exit code (0 on success; 1 with a message on `err` if the file cannot be written).
int run_demo_basis(std::ostream& out, std::ostream& err, const std::string& out_dir);

}  // namespace pcr_app
