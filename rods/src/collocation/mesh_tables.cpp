// Per-mesh tables of collocation rods and their process-wide registry (mesh_tables.hpp).
#include "mesh_tables.hpp"

#include <map>
#include <mutex>
#include <utility>

namespace pcr::collocation {
namespace {

constexpr size_t kMaxKeptMeshes = 64;

std::shared_ptr<const MeshTables> build_tables(int degree, int elements) {
  auto t = std::make_shared<MeshTables>();
  t->degree = degree;
  t->elements = elements;
  const KnotVector knots = KnotVector::open_uniform(degree, elements);
  t->greville = knots.greville();
  const int n = knots.num_basis();
  // Interpolation matrix: row i holds the p + 1 functions active at tau_i (a band of width p each side).
  t->greville_lu.resize(n, degree, degree);
  for (int i = 0; i < n; ++i) {
    const BasisDerivatives d = basis_derivatives(knots, t->greville[i], 0);
    for (int k = 0; k <= degree; ++k) t->greville_lu.at(i, d.first + k) = d.values(0, k);
  }
  t->greville_regular = t->greville_lu.factorize();
  const int points = 4 * n + 1;
  t->check_basis.reserve(points);
  for (int k = 0; k < points; ++k)
    t->check_basis.push_back(basis_derivatives(knots, static_cast<double>(k) / (points - 1), 1));
  return t;
}

struct Registry {
  std::mutex mutex;
  std::map<std::pair<int, int>, std::shared_ptr<const MeshTables>> tables;
};

Registry& registry() {
  static Registry r;  // thread-safe initialisation (C++11)
  return r;
}

}  // namespace

std::shared_ptr<const MeshTables> mesh_tables(int degree, int elements) {
  Registry& r = registry();
  const std::pair<int, int> key{degree, elements};
  {
    const std::lock_guard<std::mutex> lock(r.mutex);
    const auto it = r.tables.find(key);
    if (it != r.tables.end()) return it->second;
  }
  // Built outside the lock (another thread may build the same; the first kept wins, both are equal).
  std::shared_ptr<const MeshTables> built = build_tables(degree, elements);
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (r.tables.size() >= kMaxKeptMeshes && r.tables.count(key) == 0) return built;
  return r.tables.emplace(key, std::move(built)).first->second;
}

bool interpolate_at_greville(const MeshTables& tables, const MatX& values, MatX& points) {
  if (!tables.greville_regular) return false;
  points = values;
  for (int c = 0; c < points.cols(); ++c) tables.greville_lu.solve_in_place(points.col(c).data());
  return true;
}

}  // namespace pcr::collocation
