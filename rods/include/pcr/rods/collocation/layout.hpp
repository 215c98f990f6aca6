#pragma once
// Variable layouts of the rod formulations, each named once:
//  - PointLayout: the components of one control point block of a formulation (offsets of P, Q, N, M
//    and the integral T of the condensed form with loads);
//  - LocalLayout: the local vector z that one collocation kernel reads, as a list of entries (a
//    u-derivative or integral of some control point components, or a variable block read directly);
//    the z offsets, the kernel size NL and the PointBlock tables (LocalGroup, DirectBlock) follow from
//    it, and kernels read their entries by name (get<Z, Z::entry>(z)).
#include <array>
#include <vector>

namespace pcr::collocation {

/// Components of one control point block.
struct PointLayout {
  int size;           ///< components per control point
  int p = 0;          ///< P (3): position
  int q = 3;          ///< Q (4): quaternion
  int n = -1;         ///< mixed form: N (3), internal force
  int m = -1;         ///< mixed form: M (3), internal moment
  int integral = -1;  ///< condensed form with loads: T (3), see collocation_rod.hpp
};

inline constexpr PointLayout kPrimalPoint{7};
inline constexpr PointLayout kMixedPoint{13, 0, 3, 7, 10};
inline constexpr PointLayout kCondensedPoint{7};
inline constexpr PointLayout kCondensedLoadedPoint{10, 0, 3, -1, -1, 7};
/// The condensed form's constant wrench block [n (3), h (3)].
inline constexpr int kWrenchSize = 6;

/// Basis rows a local entry can read (PointBasis::B[i][slot]): the u-derivatives 0..2 of the basis,
/// integral_0^u of it, and a selector (1 for the one control point read as it is, else 0).
inline constexpr int kIntegral = 3;
inline constexpr int kSelected = 4;
inline constexpr int kBasisSlots = 5;

/// Marks a LocalEntry read from a variable block directly (not through the basis).
inline constexpr int kDirect = -1;

/// One entry of a kernel's local vector z: sum_i B[i][slot] c_i[component .. component + dim) over the
/// control points c_i of the point's basis, or (component == kDirect) the dim values of a variable block.
struct LocalEntry {
  int component;
  int dim;
  int slot = 0;
};

/// A group of local variables: z[local .. local+dim) = the `derivative` slot of the control point
/// components [component .. component+dim) (PointBlock's gather table).
struct LocalGroup {
  int local;
  int component;
  int dim;
  int derivative;
};

/// A variable block read directly: z[local .. local+size) = its values.
struct DirectBlock {
  int local;
  int size;
};

/// A kernel's local vector: the entries in order.
template <int K>
struct LocalLayout {
  std::array<LocalEntry, K> entries;

  constexpr int offset(int entry) const {
    int o = 0;
    for (int i = 0; i < entry; ++i) o += entries[i].dim;
    return o;
  }
  constexpr int dim(int entry) const { return entries[entry].dim; }
  /// NL, the length of z.
  constexpr int size() const { return offset(K); }
  /// Number of direct entries (the variable blocks after the control points, in entry order).
  constexpr int num_direct() const {
    int count = 0;
    for (const LocalEntry& e : entries) count += e.component == kDirect ? 1 : 0;
    return count;
  }
  std::vector<LocalGroup> groups() const {
    std::vector<LocalGroup> g;
    for (int i = 0; i < K; ++i)
      if (entries[i].component != kDirect)
        g.push_back({offset(i), entries[i].component, entries[i].dim, entries[i].slot});
    return g;
  }
  std::vector<DirectBlock> direct() const {
    std::vector<DirectBlock> d;
    for (int i = 0; i < K; ++i)
      if (entries[i].component == kDirect) d.push_back({offset(i), entries[i].dim});
    return d;
  }
};

/// The layout `base` followed by the entry `extra` (a kernel that reads another's local vector and one
/// more block).
template <int K>
constexpr LocalLayout<K + 1> append(const LocalLayout<K>& base, LocalEntry extra) {
  LocalLayout<K + 1> out{};
  for (int i = 0; i < K; ++i) out.entries[i] = base.entries[i];
  out.entries[K] = extra;
  return out;
}

/// Entry E of the local vector z of the kernel layout Z (a struct with an enum of entry names and a
/// static LocalLayout `layout`), as a fixed-size segment; scalars are 1-vectors (get<...>(z)[0]).
template <typename Z, int E, typename Vector>
auto get(const Vector& z) {
  return z.template segment<Z::layout.dim(E)>(Z::layout.offset(E));
}

}  // namespace pcr::collocation
