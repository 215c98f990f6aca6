// Python bindings of the results: SolveSummary, RodResult, Stability, contacts, RobotSolution (read-only
// values).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"

namespace py = pybind11;

namespace pcr::python {
namespace {

using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// n x 3 array of points, one row per point.
Points point_rows(const std::vector<Vec3>& points) {
  Points rows(static_cast<int>(points.size()), 3);
  for (size_t i = 0; i < points.size(); ++i) rows.row(static_cast<int>(i)) = points[i].transpose();
  return rows;
}

void bind_summary(py::module_& m) {
  py::class_<SolveSummary>(m, "SolveSummary", "What a solve did: status, iterations, residual, time.")
      .def_property_readonly(
          "status", [](const SolveSummary& s) { return to_string(s.status); },
          "'converged', 'max_iterations', 'infeasible', 'singular', 'diverged', "
          "'invalid_input' or 'failed'")
      .def_property_readonly("converged", &SolveSummary::converged)
      .def_readonly("solver", &SolveSummary::solver)
      .def_readonly("iterations", &SolveSummary::iterations)
      .def_readonly("jacobian_evaluations", &SolveSummary::jacobian_evaluations)
      .def_readonly("residual_max_abs", &SolveSummary::residual_max_abs)
      .def_readonly("residual_round_off", &SolveSummary::residual_round_off)
      .def_readonly("residual_by_kind", &SolveSummary::residual_by_kind)
      .def_readonly("objective", &SolveSummary::objective)
      .def_readonly("wall_time_seconds", &SolveSummary::wall_time_seconds)
      .def_readonly("message", &SolveSummary::message)
      .def("__repr__", [](const SolveSummary& s) { return "<pcr.SolveSummary " + s.brief_report() + ">"; });
}

void bind_rod_result(py::module_& m) {
  py::class_<RodResult>(m, "RodResult", "One rod of a robot solution (world frame, SI units).")
      .def_readonly("name", &RodResult::name)
      .def_readonly("length", &RodResult::length, "[m]")
      .def_readonly("base_force", &RodResult::base_force, "n(0) [N]: the rod's force on its start link")
      .def_readonly("base_moment", &RodResult::base_moment, "m(0) [N m], about the end point")
      .def_readonly("tip_force", &RodResult::tip_force, "n(L) [N]: the end link's force on the rod")
      .def_readonly("tip_moment", &RodResult::tip_moment, "m(L) [N m]")
      .def_readonly("axial_force", &RodResult::axial_force, "n(0) . d3(0) [N], positive in tension")
      .def_readonly("min_axial_stretch", &RodResult::min_axial_stretch)
      .def_property_readonly(
          "centerline", [](const RodResult& r) { return point_rows(r.centerline); },
          "n x 3 array of centerline points [m], base first");
}

void bind_stability(py::module_& m) {
  py::class_<Stability>(m, "Stability",
                        "Stability verdict of an equilibrium (docs/design.md §4): verdict 'stable', "
                        "'unstable', 'critical', 'unknown' (reason says why) or 'not_checked'.")
      .def_property_readonly("verdict", [](const Stability& s) { return to_string(s.verdict); })
      .def_readonly("unstable_modes", &Stability::unstable_modes)
      .def_readonly("neutral_modes", &Stability::neutral_modes)
      .def_readonly("margin", &Stability::margin,
                    "smallest eigenvalue of the dimensionless reduced stiffness")
      .def_readonly("length_scale", &Stability::length_scale, "[m]")
      .def_readonly("energy_scale", &Stability::energy_scale, "[J]")
      .def_readonly("reason", &Stability::reason)
      .def_readonly("rod_unstable_modes", &Stability::rod_unstable_modes)
      .def_readonly("platform_unstable_modes", &Stability::border_unstable_modes,
                    "negative eigenvalues of the platforms' reduced stiffness")
      .def("__repr__", [](const Stability& s) {
        return "<pcr.Stability " + std::string(to_string(s.verdict)) + ", " +
               std::to_string(s.unstable_modes) + " unstable modes>";
      });
}

void bind_contacts(py::module_& m) {
  py::class_<ContactInterval>(m, "ContactInterval",
                              "An arc-length interval of a rod in contact (world frame).")
      .def_readonly("s_begin", &ContactInterval::s_begin, "[m]")
      .def_readonly("s_end", &ContactInterval::s_end, "[m]")
      .def_readonly("force", &ContactInterval::force, "resultant contact force on the rod [N]")
      .def_readonly("centroid", &ContactInterval::centroid, "arc length of the force's centroid [m]");
  py::class_<ObstacleContact>(m, "ObstacleContact",
                              "The contact of one rod with one obstacle (docs/contact.md), world frame.")
      .def_readonly("rod", &ObstacleContact::rod)
      .def_readonly("obstacle", &ObstacleContact::obstacle)
      .def_readonly("intervals", &ObstacleContact::intervals)
      .def_readonly("force", &ObstacleContact::force, "resultant of all intervals [N]")
      .def_readonly("min_gap", &ObstacleContact::min_gap,
                    "smallest gap along the centerline [m]; negative: penetration between collocation points")
      .def_readonly("min_gap_arc_length", &ObstacleContact::min_gap_arc_length, "[m]")
      .def_readonly("penetration_tolerance", &ObstacleContact::penetration_tolerance,
                    "penetration accepted without a warning [m]")
      .def_readonly("concentrated", &ObstacleContact::concentrated,
                    "a point force (sharp obstacle, point contact or adhesive roller)")
      .def_readonly("adhesive", &ObstacleContact::adhesive, "a roller with the adhesion (no-slip) law")
      .def_readonly("tangential_force", &ObstacleContact::tangential_force,
                    "adhesive rollers: the force's part along the rod's tangent at the contact [N]")
      .def_readonly("arc_lengths", &ObstacleContact::arc_lengths, "contact cell midpoints s_j [m]")
      .def_readonly("densities", &ObstacleContact::densities, "contact force density per cell [N/m]")
      .def_readonly("gaps", &ObstacleContact::gaps, "gap at each cell midpoint [m]")
      .def_readonly("forces", &ObstacleContact::forces,
                    "per cell: its resultant contact force on the rod [N]; sharp obstacles: the point force")
      .def("__repr__", [](const ObstacleContact& c) {
        return "<pcr.ObstacleContact " + c.rod + " on " + c.obstacle + ", " +
               std::to_string(c.intervals.size()) + " intervals>";
      });
}

void bind_contact_gaps(py::module_& m) {
  py::class_<RodContactGap>(m, "RodContactGap", "The smallest gap of a contact rod along its centerline.")
      .def_readonly("rod", &RodContactGap::rod)
      .def_readonly("obstacle", &RodContactGap::obstacle)
      .def_readonly("min_gap", &RodContactGap::min_gap, "[m]; negative: penetration")
      .def_readonly("arc_length", &RodContactGap::arc_length, "[m]")
      .def_readonly("tolerance", &RodContactGap::tolerance, "[m]")
      .def_property_readonly("penetrates", &RodContactGap::penetrates,
                             "deeper than the tolerance (a warning)");
}

void bind_robot_solution(py::module_& m) {
  py::class_<RobotSolution>(m, "RobotSolution", "Inputs, platform poses, rods and the summary of one solve.")
      .def_readonly("summary", &RobotSolution::summary)
      .def_property_readonly("converged", [](const RobotSolution& s) { return s.summary.converged(); })
      .def_readonly("inputs", &RobotSolution::inputs, "model input order [m or rad]")
      .def_readonly("platforms", &RobotSolution::platforms, "world poses, model platform order")
      .def_readonly("rods", &RobotSolution::rods)
      .def_readonly("passive_joints", &RobotSolution::passive_joints, "model passive-joint order")
      .def_readonly("contacts", &RobotSolution::contacts, "per rod and obstacle it may touch (empty without)")
      .def_readonly("contact_gaps", &RobotSolution::contact_gaps, "per contact rod: its smallest gap")
      .def_readonly("jacobian_sign", &RobotSolution::jacobian_sign)
      .def_readonly("jacobian_sign_changed", &RobotSolution::jacobian_sign_changed)
      .def_readonly("stability", &RobotSolution::stability_verdict,
                    "the verdict when the solver's option stability_verdict=True, else not_checked")
      .def("__repr__", [](const RobotSolution& s) {
        return "<pcr.RobotSolution " + std::string(to_string(s.summary.status)) + ", " +
               std::to_string(s.platforms.size()) + " platforms, " + std::to_string(s.rods.size()) + " rods>";
      });
}

}  // namespace

void bind_results(py::module_& m) {
  bind_summary(m);
  bind_rod_result(m);
  bind_stability(m);
  bind_contacts(m);
  bind_contact_gaps(m);
  bind_robot_solution(m);
}

}  // namespace pcr::python
