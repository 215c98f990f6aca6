#include "demo_basis.hpp"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <vector>

#include "pcr/splines/basis.hpp"
#include "pcr/splines/spline_curve.hpp"

namespace pcr_app {

namespace {

// One row per point u: the values of all n basis functions (derivative-th derivative).
void print_table(std::ostream& out, const pcr::KnotVector& knots, const std::vector<double>& points,
                 int derivative, const char* name) {
  const pcr::MatX table = pcr::MatX(pcr::collocation_matrix(knots, points, derivative));
  out << "     u  ";
  for (int i = 0; i < knots.num_basis(); ++i) out << std::setw(9) << (name + std::to_string(i));
  out << "\n";
  for (std::size_t r = 0; r < points.size(); ++r) {
    out << std::setw(6) << points[r] << "  ";
    for (int i = 0; i < knots.num_basis(); ++i) out << std::setw(9) << table(r, i);
    out << "\n";
  }
}

// The seed's sample curve: degree 3, six control points in the plane, open uniform knots.
pcr::SplineCurve sample_curve() {
  pcr::MatX P(2, 6);
  P << 0, 0.3, 0.3, 0.5, 0.9, 0.8,  //
      0, 0.25, 0.7, 0.8, 0.3, 1;
  return pcr::SplineCurve(pcr::KnotVector::open_uniform(3, 3), P);
}

bool write_basis_csv(const std::string& path, const pcr::KnotVector& knots) {
  std::ofstream file(path);
  if (!file) return false;
  std::vector<double> points;
  for (int k = 0; k <= 100; ++k) points.push_back(k / 100.0);
  const pcr::MatX N = pcr::MatX(pcr::collocation_matrix(knots, points, 0));
  const pcr::MatX dN = pcr::MatX(pcr::collocation_matrix(knots, points, 1));
  file << "u";
  for (int i = 0; i < knots.num_basis(); ++i) file << ",N" << i;
  for (int i = 0; i < knots.num_basis(); ++i) file << ",dN" << i;
  file << "\n" << std::setprecision(17);
  for (std::size_t r = 0; r < points.size(); ++r) {
    file << points[r];
    for (int i = 0; i < knots.num_basis(); ++i) file << "," << N(r, i);
    for (int i = 0; i < knots.num_basis(); ++i) file << "," << dN(r, i);
    file << "\n";
  }
  return static_cast<bool>(file);
}

}  // namespace

int run_demo_basis(std::ostream& out, std::ostream& err, const std::string& out_dir) {
  const pcr::KnotVector knots = pcr::KnotVector::open_uniform(3, 4);
  const std::vector<double> points{0.0, 0.1, 0.25, 0.4, 0.5, 0.6, 0.75, 0.9, 1.0};
  out << std::fixed << std::setprecision(4);
  out << "Cubic B-spline basis N_i(u), open uniform knots with 4 elements (n = " << knots.num_basis()
      << "):\n";
  print_table(out, knots, points, 0, "N");
  out << "\nFirst derivatives N_i'(u):\n";
  print_table(out, knots, points, 1, "N'");
  out << "\nGreville abscissae:";
  for (double tau : knots.greville()) out << " " << tau;
  out << "\n\nSample curve (degree 3, 6 control points, open uniform knots) C(u):\n     u         x         "
         "y\n";
  const pcr::SplineCurve curve = sample_curve();
  for (int k = 0; k <= 10; ++k) {
    const double u = k / 10.0;
    const pcr::VecX c = curve.evaluate(u);
    out << std::setw(6) << u << std::setw(10) << c[0] << std::setw(10) << c[1] << "\n";
  }
  if (!out_dir.empty()) {
    const std::string path = out_dir + "/basis.csv";
    std::error_code ignored;  // a failure shows up when the file is written
    std::filesystem::create_directories(out_dir, ignored);
    if (!write_basis_csv(path, knots)) {
      err << "pcr demo: cannot write " << path << "\n";
      return 1;
    }
    out << "\nwrote " << path << "\n";
  }
  return 0;
}

}  // namespace pcr_app
