#pragma once
// The shooting reference's centerline, behind a header that does not include rod_ode.hpp, so that the
// shooting and the collocation solvers sit in separate translation units of the cross-check test.
#include <string>
#include <vector>

#include "pcr/core/types.hpp"
#include "pcr/rods/rod_model.hpp"

namespace pcr::test {

struct ShootingCenterline {
  bool converged = false;
  std::string report;
  std::vector<Vec3> points;  ///< p(s) at the requested s
};

/// Dormand-Prince shooting at integration_relative_tolerance = integration_absolute_tolerance = tolerance,
/// residual tolerance 1e-12.
ShootingCenterline shooting_centerline(const RodModel& model, const std::vector<double>& s, double tolerance);

}  // namespace pcr::test
