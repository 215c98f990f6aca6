#pragma once
// A residual block at one collocation point of one rod (the rod forms of rods/src/collocation).
//
// The equations at a point depend on a small local vector z (values and u-derivatives of p, q, n, m
// at the point, and the rod length L; layout.hpp names it per kernel). z is gathered from the p+1 active
// control points with the basis values cached at construction: z_g = sum_i B_d(u)[i] c_i[component]
// (d: a u-derivative, the integral from 0, or the selector of one point). The kernel is evaluated with
// Dual<NL> numbers, which gives dr/dz exactly; the chain rule dz/dc_i = B_d(u)[i] scatters it into one
// dense Jacobian per control point (and dr/dz directly into the direct blocks, e.g. the length). A kernel
// with a member jacobian(z, r, dr) gives dr/dz itself (written out where the Dual numbers cost most,
// e.g. condensed_jacobian.cpp); Dual numbers then serve only the pattern detection below.
//
// Structural sparsity: control point components that no local group reads, and basis functions whose
// value is zero at the point, give zero columns. The kernel's own zero derivatives dr_row/dz_k come from
// detect_kernel_pattern: the kernel evaluated with dual numbers at two pseudo-random z (entries of
// [0.5, 1.5]); a derivative of a smooth (rational) kernel that vanishes at a random point is identically
// zero with probability one. Only for kernels whose constants enter additively or as nonzero factors
// (material stiffness), so that a zero constant (e.g. no load yet) cannot hide a dependency; then the
// pattern does not depend on the constants either, and one detection serves every point of a rod that
// uses the same kernel function. Constants that are the same at every point of the rod (the distributed
// loads of the condensed form) may multiply: a zero load then drops those dependencies for every point of
// that problem alike (a load step at load factor 0 builds its own problem). The problem's Jacobian check
// compares every left-out entry with finite differences.
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "pcr/core/error.hpp"
#include "pcr/math/dual.hpp"
#include "pcr/rods/collocation/layout.hpp"
#include "pcr/solve/residual_block.hpp"

namespace pcr::collocation {

/// Basis values at a point: B[i][slot] = the basis row `slot` (layout.hpp: u-derivatives 0..2,
/// kIntegral, kSelected) of the function first + i, i < count.
struct PointBasis {
  int first = 0;
  int count = 0;
  std::vector<std::array<double, kBasisSlots>> B;
};

/// depends[row * NL + k]: dr_row / dz_k is not identically zero.
template <int NL, int NR>
using KernelPattern = std::array<bool, NR * NL>;

template <int NL, int NR>
KernelPattern<NL, NR> dense_kernel_pattern() {
  KernelPattern<NL, NR> depends;
  depends.fill(true);
  return depends;
}

/// The kernel's nonzero derivatives (see the file comment for when this is valid).
template <int NL, int NR, typename Kernel>
KernelPattern<NL, NR> detect_kernel_pattern(const Kernel& kernel) {
  KernelPattern<NL, NR> depends;
  depends.fill(false);
  std::uint32_t state = 12345u;  // fixed-seed linear congruential generator: reproducible patterns
  for (int trial = 0; trial < 2; ++trial) {
    Eigen::Matrix<Dual<NL>, NL, 1> z;
    for (int k = 0; k < NL; ++k) {
      state = state * 1664525u + 1013904223u;
      z[k] = Dual<NL>::variable(0.5 + (state >> 8) * (1.0 / 16777216.0), k);
    }
    std::array<Dual<NL>, NR> r;
    kernel(z, r.data());
    for (int row = 0; row < NR; ++row)
      for (int k = 0; k < NL; ++k)
        if (r[row].v[k] != 0.0) depends[row * NL + k] = true;
  }
  return depends;
}

/// The gather of a local vector named by the layout struct Z (layout.hpp) with its read ranges, groups
/// and direct blocks known at compile time: sums of the basis values times the control points, the first
/// term, then the others added in order, without run-time dispatch on widths or copies of run-time
/// length. Its functions are always inlined: left to itself GCC made some of them
/// calls, with up to 5 % more instructions on a warm R5b path (bench_time_split).
namespace layout_gather {

inline constexpr int kMaxComponents = 13;

struct SlotRange {
  int begin, end;
};

/// Every entry of Z reads a basis row that exists and control point components within kMaxComponents.
template <typename Z>
constexpr bool reads_known_components() {
  for (const LocalEntry& e : Z::layout.entries)
    if (e.component != kDirect &&
        (e.component < 0 || e.component + e.dim > kMaxComponents || e.slot < 0 || e.slot >= kBasisSlots))
      return false;
  return true;
}

/// The components [begin, end) that the entries of Z read with basis row `slot` (empty: begin >= end).
template <typename Z>
constexpr SlotRange slot_range(int slot) {
  SlotRange r{kMaxComponents, 0};
  for (const LocalEntry& e : Z::layout.entries) {
    if (e.component == kDirect || e.slot != slot) continue;
    r.begin = e.component < r.begin ? e.component : r.begin;
    r.end = e.component + e.dim > r.end ? e.component + e.dim : r.end;
  }
  return r;
}

/// sum[c] = sum_i B[i][Slot] c_i[Begin + c], c < Width: the first term, then the others added in order.
template <int Slot, int Begin, int Width>
[[gnu::always_inline]] inline void accumulate(const double* const* values, const PointBasis& basis,
                                              double* sum) {
  const double b0 = basis.B[0][Slot];
  for (int c = 0; c < Width; ++c) sum[c] = b0 * values[0][Begin + c];
  for (int i = 1; i < basis.count; ++i) {
    const double b = basis.B[i][Slot];
    const double* v = values[i] + Begin;
    for (int c = 0; c < Width; ++c) sum[c] += b * v[c];
  }
}

template <typename Z, int Slot>
[[gnu::always_inline]] inline void accumulate_slot(const double* const* values, const PointBasis& basis,
                                                   double (&sums)[kBasisSlots][kMaxComponents]) {
  constexpr SlotRange r = slot_range<Z>(Slot);
  if constexpr (r.begin < r.end)
    accumulate<Slot, r.begin, r.end - r.begin>(values, basis, sums[Slot] + r.begin);
}

/// The number of direct entries of Z before entry E (its index among the direct blocks).
template <typename Z>
constexpr int direct_index(int entry) {
  int j = 0;
  for (int i = 0; i < entry; ++i) j += Z::layout.entries[i].component == kDirect ? 1 : 0;
  return j;
}

template <typename Z, int E>
[[gnu::always_inline]] inline void copy_entry(const double (&sums)[kBasisSlots][kMaxComponents],
                                              const double* const* values, int count, double* z) {
  constexpr LocalEntry e = Z::layout.entries[E];
  constexpr int offset = Z::layout.offset(E);
  if constexpr (e.component == kDirect) {
    const double* from = values[count + direct_index<Z>(E)];
    for (int c = 0; c < e.dim; ++c) z[offset + c] = from[c];
  } else {
    for (int c = 0; c < e.dim; ++c) z[offset + c] = sums[e.slot][e.component + c];
  }
}

template <typename Z, std::size_t... Slot, std::size_t... E>
[[gnu::always_inline]] inline void gather(const double* const* values, const PointBasis& basis, double* z,
                                          std::index_sequence<Slot...>, std::index_sequence<E...>) {
  double sums[kBasisSlots][kMaxComponents];
  (accumulate_slot<Z, static_cast<int>(Slot)>(values, basis, sums), ...);
  (copy_entry<Z, static_cast<int>(E)>(sums, values, basis.count, z), ...);
}

/// z (Z::layout.size() values) from the control points (values[0 .. basis.count)) and the direct blocks
/// after them.
template <typename Z>
[[gnu::always_inline]] inline void gather(const double* const* values, const PointBasis& basis, double* z) {
  static_assert(reads_known_components<Z>(),
                "layout_gather: an entry reads an unknown basis row or component");
  gather<Z>(values, basis, z, std::make_index_sequence<kBasisSlots>(),
            std::make_index_sequence<Z::layout.entries.size()>());
}

}  // namespace layout_gather

/// Z: the layout struct naming the local vector (layout.hpp); its gather is compiled for it
/// (layout_gather), its groups and direct blocks (Z::layout) serve the pattern and the chain rule.
template <typename Z, int NR, typename Kernel>
class PointBlock final : public ResidualBlock {
  static constexpr int NL = Z::layout.size();

 public:
  /// variables: the `basis.count` control point blocks, then one block per direct entry of Z.
  PointBlock(std::string kind, std::string name, std::vector<VariableId> variables, int control_point_size,
             PointBasis basis, Kernel kernel, const KernelPattern<NL, NR>& depends)
      : ResidualBlock(std::move(kind), std::move(name), NR, std::move(variables)),
        cp_size_(control_point_size),
        depends_(depends),
        basis_(std::move(basis)),
        groups_(Z::layout.groups()),
        direct_(Z::layout.direct()),
        kernel_(std::move(kernel)) {
    require(basis_.count >= 1 && static_cast<int>(basis_.B.size()) == basis_.count, "PointBlock '",
            this->name(), "': ", basis_.count, " basis functions, ", basis_.B.size(), " rows");
    require(tiles_local_vector(), "PointBlock '", this->name(),
            "': its groups and direct blocks do not cover the ", NL, " local entries once each");
  }

  bool structural_nonzero(int k, int row, int column) const override {
    if (k >= basis_.count) return depends(row, direct_[k - basis_.count].local + column);
    for (const LocalGroup& g : groups_)
      if (column >= g.component && column < g.component + g.dim && basis_.B[k][g.derivative] != 0.0 &&
          depends(row, g.local + column - g.component))
        return true;
    return false;
  }

  void structural_mask(int k, int size, char* mask) const override {
    if (k >= basis_.count) {
      const DirectBlock& d = direct_[k - basis_.count];
      for (int row = 0; row < NR; ++row)
        for (int c = 0; c < size; ++c) mask[row * size + c] = depends(row, d.local + c) ? 1 : 0;
      return;
    }
    std::fill(mask, mask + NR * size, char{0});
    for (const LocalGroup& g : groups_) {
      if (basis_.B[k][g.derivative] == 0.0) continue;
      for (int row = 0; row < NR; ++row)
        for (int c = 0; c < g.dim; ++c)
          if (depends(row, g.local + c)) mask[row * size + g.component + c] = 1;
    }
  }

  void evaluate(const double* const* values, double* residual, double* const* jacobians) const override {
    if (jacobians == nullptr) {
      Eigen::Matrix<double, NL, 1> z;
      layout_gather::gather<Z>(values, basis_, z.data());
      kernel_(z, residual);
      return;
    }
    Eigen::Matrix<double, NL, 1> zv;
    layout_gather::gather<Z>(values, basis_, zv.data());
    if constexpr (HasWrittenJacobian<Kernel>::value) {
      Eigen::Matrix<double, NR, NL, Eigen::RowMajor> dr;
      kernel_.jacobian(zv, residual, dr.data());
      scatter([&dr](int row, int k) { return dr(row, k); }, jacobians);
    } else {
      using D = Dual<NL>;
      Eigen::Matrix<D, NL, 1> z;
      for (int k = 0; k < NL; ++k) z[k] = D::variable(zv[k], k);
      std::array<D, NR> r;
      kernel_(z, r.data());
      for (int row = 0; row < NR; ++row) residual[row] = r[row].a;
      scatter([&r](int row, int k) { return r[row].v[k]; }, jacobians);
    }
  }

 private:
  // Kernels with a member jacobian(z, r, dr) (dr: NR x NL row-major) give dr/dz themselves.
  template <typename K, typename = void>
  struct HasWrittenJacobian : std::false_type {};
  template <typename K>
  struct HasWrittenJacobian<K, std::void_t<decltype(&K::jacobian)>> : std::true_type {};

  // The chain rule: dr/dz (dr(row, k)) into the control point and direct blocks' Jacobians.
  template <typename Derivative>
  void scatter(const Derivative& dr, double* const* jacobians) const {
    for (int i = 0; i < basis_.count; ++i) {
      double* J = jacobians[i];
      if (J == nullptr) continue;
      std::fill(J, J + NR * cp_size_, 0.0);
      for (const LocalGroup& g : groups_) {
        const double b = basis_.B[i][g.derivative];
        if (b == 0.0) continue;
        for (int row = 0; row < NR; ++row)
          for (int c = 0; c < g.dim; ++c) J[row * cp_size_ + g.component + c] += dr(row, g.local + c) * b;
      }
    }
    for (size_t j = 0; j < direct_.size(); ++j) {
      double* J = jacobians[basis_.count + j];
      if (J == nullptr) continue;
      const DirectBlock& d = direct_[j];
      for (int row = 0; row < NR; ++row)
        for (int c = 0; c < d.size; ++c) J[row * d.size + c] = dr(row, d.local + c);
    }
  }

  bool depends(int row, int local) const { return depends_[row * NL + local]; }

  // The groups' and direct blocks' entries of z cover [0, NL) once each (gather writes no other).
  bool tiles_local_vector() const {
    std::array<int, NL> written{};
    const auto mark = [&written](int local, int dim) {
      for (int k = local; k < local + dim; ++k)
        if (k >= 0 && k < NL) ++written[k];
      return local >= 0 && local + dim <= NL;
    };
    bool inside = true;
    for (const LocalGroup& g : groups_) inside = mark(g.local, g.dim) && inside;
    for (const DirectBlock& d : direct_) inside = mark(d.local, d.size) && inside;
    return inside && std::all_of(written.begin(), written.end(), [](int n) { return n == 1; });
  }

  int cp_size_;
  KernelPattern<NL, NR> depends_;
  PointBasis basis_;
  std::vector<LocalGroup> groups_;
  std::vector<DirectBlock> direct_;
  Kernel kernel_;
};

/// A PointBlock whose kernel's local vector is named by the layout struct Z (layout.hpp): NL, the local
/// groups and the direct blocks follow from Z::layout; `variables` lists the basis.count control points,
/// then one variable block per direct entry of Z in entry order.
template <typename Z, int NR, typename Kernel>
std::shared_ptr<const ResidualBlock> make_point_block(
    std::string kind, std::string name, std::vector<VariableId> variables, int cp_size,
    const PointBasis& basis, Kernel kernel,
    const KernelPattern<Z::layout.size(), NR>& depends = dense_kernel_pattern<Z::layout.size(), NR>()) {
  require(static_cast<int>(variables.size()) == basis.count + Z::layout.num_direct(), "PointBlock '", name,
          "': ", variables.size(), " variable blocks for ", basis.count, " control points and ",
          Z::layout.num_direct(), " direct blocks");
  return std::make_shared<PointBlock<Z, NR, Kernel>>(std::move(kind), std::move(name), std::move(variables),
                                                     cp_size, basis, std::move(kernel), depends);
}

}  // namespace pcr::collocation
