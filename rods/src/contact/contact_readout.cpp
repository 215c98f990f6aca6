// The contact set of a solved rod (rod_contact.hpp): per obstacle the densities and gaps at the
// midpoints, the runs of cells in contact with their resultants, and the smallest sampled gap.
#include <algorithm>
#include <limits>
#include <sstream>

#include "pcr/rods/rod_contact.hpp"
#include "pcr/splines/basis.hpp"

namespace pcr {
namespace {

// Smallest gap to `obstacle` at 8 points per collocation cell (and the ends), and its arc length.
void sampled_min_gap(const CollocationRod& rod, const RodVariables& vars, const VecX& x,
                     const Obstacle& obstacle, double radius, ObstacleContact& out) {
  const int samples = 8 * (rod.num_control_points() - 1) + 1;
  std::vector<Vec3> positions;
  std::vector<double> stretches;
  rod.sample_centerline(x, vars, rod.sample_basis(samples), positions, stretches);
  const double L = rod.length(x, vars);
  out.min_gap = std::numeric_limits<double>::infinity();
  for (int i = 0; i < samples; ++i) {
    const double g = obstacle_gap(obstacle, positions[i], radius).gap;
    if (g < out.min_gap) {
      out.min_gap = g;
      out.min_gap_arc_length = L * i / (samples - 1);
    }
  }
}

// Runs of cells that carry force (density > density_tolerance), merged across cells between them that
// touch (gap < gap_tolerance) but carry none: the collocated densities of a contact interval may
// alternate between large and zero values from cell to cell (rod_contact.hpp).
std::vector<ContactInterval> contact_intervals(const ObstacleContact& c, const std::vector<Vec3>& forces,
                                               const std::vector<double>& tau, double L,
                                               double density_tolerance, double gap_tolerance) {
  std::vector<ContactInterval> intervals;
  std::vector<double> weights;  // per interval: sum of |F_j|
  int last = -1;                // last cell carrying force of the open interval
  for (int j = 0; j < static_cast<int>(forces.size()); ++j) {
    if (c.densities[j] <= density_tolerance) continue;
    bool bridged = last >= 0;
    for (int i = last + 1; bridged && i < j; ++i) bridged = c.gaps[i] < gap_tolerance;
    if (!bridged) {
      intervals.push_back({L * tau[j], L * tau[j], Vec3::Zero()});
      weights.push_back(0.0);
    }
    for (int i = bridged ? last + 1 : j; i <= j; ++i) {
      intervals.back().force += forces[i];
      intervals.back().centroid += c.arc_lengths[i] * forces[i].norm();
      weights.back() += forces[i].norm();
    }
    intervals.back().s_end = L * tau[j + 1];
    last = j;
  }
  for (size_t i = 0; i < intervals.size(); ++i) intervals[i].centroid /= weights[i];
  return intervals;
}

// The point contact of the sharp obstacle `k` (the i-th sharp one): section, force and gap.
ObstacleContact sharp_contact(const CollocationRod& rod, const RodVariables& vars,
                              const RodContactVariables& contact, const VecX& x, int k, int i) {
  const Obstacle& obstacle = contact.options.obstacles[k];
  const double L = rod.length(x, vars);
  const int offset = contact.sharp_offsets[i];
  const double u = std::clamp(x[offset], 0.0, 1.0), lambda = x[offset + 1];
  ObstacleContact c;
  c.rod = rod.model().name;
  c.obstacle = obstacle.name;
  c.concentrated = true;
  const BasisDerivatives b = basis_derivatives(rod.knots(), u, 0);
  Vec3 p = Vec3::Zero();
  const int cp = rod.control_point_size(), po = rod.point_layout().p;
  for (int j = 0; j < b.values.cols(); ++j)
    p += b.values(0, j) * x.segment<3>(vars.control_point_offset + (b.first + j) * cp + po);
  const Vec3 force = L * x.segment<3>(offset + 2);
  c.arc_lengths.push_back(u * L);
  c.densities.push_back(force.norm());
  c.gaps.push_back(obstacle_gap(obstacle, p, contact.options.radius).gap);
  if (lambda > 1e-8 * rod.force_scale() / rod.length_scale())
    c.intervals.push_back({u * L, u * L, force, u * L});
  c.force = c.intervals.empty() ? Vec3::Zero() : force;
  c.adhesive = i < static_cast<int>(contact.tangential_offsets.size()) && contact.tangential_offsets[i] >= 0;
  if (c.adhesive && !c.intervals.empty()) c.tangential_force = L * x[contact.tangential_offsets[i]];
  c.forces.push_back(c.force);
  return c;
}

}  // namespace

std::vector<ObstacleContact> read_rod_contact(const CollocationRod& rod, const RodVariables& vars,
                                              const RodContactVariables& contact, const VecX& x) {
  const RodContactOptions& o = contact.options;
  const std::vector<double> tau = rod.knots().greville();
  const double L = rod.length(x, vars);
  const double density_tolerance = 1e-8 * rod.force_scale() / rod.length_scale();
  const double gap_tolerance = 1e-6 * rod.length_scale();
  const int cp = rod.control_point_size(), po = rod.point_layout().p;
  std::vector<ObstacleContact> result;
  for (int k = 0; k < static_cast<int>(o.obstacles.size()); ++k) {
    ObstacleContact c;
    const auto sharp = std::find(contact.sharp.begin(), contact.sharp.end(), k);
    if (sharp != contact.sharp.end()) {
      c = sharp_contact(rod, vars, contact, x, k, static_cast<int>(sharp - contact.sharp.begin()));
    } else {
      const int column = static_cast<int>(
          std::find(contact.distributed.begin(), contact.distributed.end(), k) - contact.distributed.begin());
      c.rod = rod.model().name;
      c.obstacle = o.obstacles[k].name;
      std::vector<Vec3> forces;  // per cell: lambda_j nu_j L (tau_{j+1} - tau_j)
      for (size_t j = 0; j < contact.midpoints.size(); ++j) {
        const double u = contact.midpoints[j];
        const BasisDerivatives b = basis_derivatives(rod.knots(), u, 0);
        Vec3 p = Vec3::Zero();
        for (int i = 0; i < b.values.cols(); ++i)
          p += b.values(0, i) * x.segment<3>(vars.control_point_offset + (b.first + i) * cp + po);
        const ObstacleGap g = obstacle_gap(o.obstacles[k], p, o.radius);
        const double lambda = x[contact.multiplier_offsets[j] + column];
        c.arc_lengths.push_back(u * L);
        c.densities.push_back(lambda);
        c.gaps.push_back(g.gap);
        forces.push_back(lambda * g.normal * L * (tau[j + 1] - tau[j]));
      }
      c.intervals = contact_intervals(c, forces, tau, L, density_tolerance, gap_tolerance);
      c.forces = forces;
      for (const ContactInterval& interval : c.intervals) c.force += interval.force;
    }
    sampled_min_gap(rod, vars, x, o.obstacles[k], o.radius, c);
    if (c.concentrated && c.gaps[0] < c.min_gap) {  // a sharp obstacle's gap varies fast near its section
      c.min_gap = c.gaps[0];
      c.min_gap_arc_length = c.arc_lengths[0];
    }
    c.penetration_tolerance = kPenetrationTolerance * o.radius;
    result.push_back(std::move(c));
  }
  return result;
}

std::vector<RodContactGap> rod_contact_gaps(const std::vector<ObstacleContact>& contacts) {
  std::vector<RodContactGap> gaps;
  for (const ObstacleContact& c : contacts) {
    if (gaps.empty() || gaps.back().rod != c.rod) {
      gaps.push_back({c.rod, c.obstacle, c.min_gap, c.min_gap_arc_length, c.penetration_tolerance});
    } else if (c.min_gap < gaps.back().min_gap) {
      gaps.back() = {c.rod, c.obstacle, c.min_gap, c.min_gap_arc_length, c.penetration_tolerance};
    }
  }
  return gaps;
}

std::string contact_penetration_warning(const std::vector<RodContactGap>& gaps) {
  std::ostringstream out;
  for (const RodContactGap& g : gaps) {
    if (!g.penetrates()) continue;
    out << (out.tellp() > 0 ? "; " : "") << "rod '" << g.rod << "' penetrates obstacle '" << g.obstacle
        << "' by " << -g.min_gap << " m at s = " << g.arc_length
        << " m between its collocation points (tolerated: " << g.tolerance
        << " m, 0.1 x contact radius); the contact is not resolved: give the rod more elements "
           "(<discretization elements=...>)";
  }
  return out.str();
}

}  // namespace pcr
