// Cost of the B-spline basis and its first two derivatives at one point (The NURBS Book A2.3), degree
// p = 2..8 on an open uniform knot vector with 16 elements: allocation-free and allocating variants.
#include <benchmark/benchmark.h>

#include "pcr/splines/basis.hpp"

namespace {

// Parameters spread over the elements so that the span search is not always the same.
constexpr int kNumPoints = 64;
double point(int k) {
  return (k + 0.37) / kNumPoints;
}

void BM_BasisDerivatives_NoAlloc(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const pcr::KnotVector knots = pcr::KnotVector::open_uniform(p, 16);
  pcr::MatX values(3, p + 1);
  int first = 0, k = 0;
  for (auto _ : state) {
    pcr::basis_derivatives(knots, point(k), 2, first, values);
    benchmark::DoNotOptimize(values.data());
    benchmark::DoNotOptimize(first);
    k = (k + 1) % kNumPoints;
  }
}

void BM_BasisDerivatives_Alloc(benchmark::State& state) {
  const int p = static_cast<int>(state.range(0));
  const pcr::KnotVector knots = pcr::KnotVector::open_uniform(p, 16);
  int k = 0;
  for (auto _ : state) {
    pcr::BasisDerivatives basis = pcr::basis_derivatives(knots, point(k), 2);
    benchmark::DoNotOptimize(basis.values.data());
    k = (k + 1) % kNumPoints;
  }
}

}  // namespace

BENCHMARK(BM_BasisDerivatives_NoAlloc)->DenseRange(2, 8);
BENCHMARK(BM_BasisDerivatives_Alloc)->DenseRange(2, 8);
BENCHMARK_MAIN();
