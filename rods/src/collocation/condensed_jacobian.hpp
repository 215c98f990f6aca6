#pragma once
// Private to pcr_rods: the condensed form's field rows (equations.hpp, condensed_field) with their
// Jacobian written out, for the Newton hot path (point_block.hpp takes it instead of Dual numbers); the
// same with distributed loads (condensed_forms.cpp: the integral I(u) of p summed over the control points,
// or T of the first active one plus the active ones' part).
#include <type_traits>

#include "pcr/rods/collocation/equations.hpp"

namespace pcr::collocation {

inline constexpr int kCondensedLocal = CondensedZ::layout.size();

/// r (6) = condensed_field(z) and J = dr/dz (6 x kCondensedLocal, row-major).
void condensed_field_jacobian(const Eigen::Matrix<double, kCondensedLocal, 1>& z, const PointConstants& c,
                              const Vec3& moment_point, double* r, double* J);

/// The kernel of the condensed field rows: Dual numbers through operator() (pattern detection), the
/// written-out Jacobian through jacobian().
struct CondensedFieldKernel {
  PointConstants c;
  Vec3 moment_point;

  template <typename Local, typename T>
  void operator()(const Local& z, T* r) const {
    condensed_field(z, c, moment_point, r);
  }
  void jacobian(const Eigen::Matrix<double, kCondensedLocal, 1>& z, double* r, double* J) const {
    condensed_field_jacobian(z, c, moment_point, r, J);
  }
};

/// The condensed form with loads, I(u) = sum_j J_j(u) P_j over every control point up to the active ones.
struct CondensedSummedZ {
  enum Entry { q, q_u, p_u, p, wrench, L, I, kEntries };
  static constexpr LocalLayout<kEntries> layout{{{{kCondensedPoint.q, 4, 0},
                                                  {kCondensedPoint.q, 4, 1},
                                                  {kCondensedPoint.p, 3, 1},
                                                  {kCondensedPoint.p, 3, 0},
                                                  {kDirect, kWrenchSize},
                                                  {kDirect, 1},
                                                  {kCondensedPoint.p, 3, kIntegral}}}};
};
inline constexpr int kCondensedSummedLocal = CondensedSummedZ::layout.size();

/// r (6) = the constitutive rows with n(s), m(s) of the loads (condensed_wrench_from_integral) at u, from
/// z of CondensedSummedZ, and J = dr/dz (6 x kCondensedSummedLocal, row-major).
void condensed_loaded_field_jacobian(const Eigen::Matrix<double, kCondensedSummedLocal, 1>& z,
                                     const PointConstants& c, const Vec3& moment_point, double u, double* r,
                                     double* J);

/// The kernel of the condensed field rows with loads at u, for CondensedSummedZ and CondensedLoadedZ
/// (whose first entries are those of CondensedSummedZ, and I = T_first + I_active): Dual numbers through
/// operator(), the written-out Jacobian through jacobian().
template <typename Z>
struct CondensedLoadedFieldKernel {
  PointConstants c;
  Vec3 moment_point;
  double u;

  template <typename Local, typename T>
  void operator()(const Local& z, T* r) const {
    using S = typename Local::Scalar;
    V3<S> n, m;
    condensed_wrench_from_integral<Z, S>(z, integral(z), c, moment_point, u, n, m);
    const S L = get<Z, Z::L>(z)[0];
    constitutive_rows<S>(get<Z, Z::q>(z), get<Z, Z::q_u>(z) / L, get<Z, Z::p_u>(z) / L, n, m, c, r);
  }
  void jacobian(const Eigen::Matrix<double, Z::layout.size(), 1>& z, double* r, double* J) const {
    if constexpr (std::is_same_v<Z, CondensedSummedZ>) {
      condensed_loaded_field_jacobian(z, c, moment_point, u, r, J);
    } else {
      // The summed layout's local vector (I in place of T_first, I_active), its I columns to both.
      Eigen::Matrix<double, kCondensedSummedLocal, 1> zs;
      constexpr int nI = CondensedSummedZ::layout.offset(CondensedSummedZ::I);
      zs.head<nI>() = z.template head<nI>();
      zs.tail<3>() = integral(z);
      Eigen::Matrix<double, 6, kCondensedSummedLocal, Eigen::RowMajor> Js;
      condensed_loaded_field_jacobian(zs, c, moment_point, u, r, Js.data());
      Eigen::Map<Eigen::Matrix<double, 6, Z::layout.size(), Eigen::RowMajor>> D(J);
      D.template leftCols<nI>() = Js.leftCols<nI>();
      D.template block<6, 3>(0, Z::layout.offset(Z::T_first)) = Js.rightCols<3>();
      D.template block<6, 3>(0, Z::layout.offset(Z::I_active)) = Js.rightCols<3>();
    }
  }

 private:
  // I(u) of the local vector.
  template <typename Local>
  static V3<typename Local::Scalar> integral(const Local& z) {
    if constexpr (std::is_same_v<Z, CondensedSummedZ>) {
      return get<Z, Z::I>(z);
    } else {
      return get<Z, Z::T_first>(z) + get<Z, Z::I_active>(z);
    }
  }
};

}  // namespace pcr::collocation
