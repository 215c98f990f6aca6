#include <cmath>
#include <cstdio>

#include "contact_output.hpp"
#include "pcr/robots/io/solution_writers.hpp"
#include "pcr/solve/solve_summary.hpp"
#include "stability_output.hpp"

namespace pcr {
namespace {

constexpr double kMillimetre = 1e3;             // m -> mm
constexpr double kDegree = 57.295779513082321;  // 180 / pi: rad -> deg

/// printf into a std::string (the table's fixed-width columns).
template <typename... Args>
std::string format(const char* pattern, Args... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, pattern, args...);
  return buffer;
}

/// Value and unit of an input for display: lengths and prismatic joints in mm, angles in degrees.
std::pair<double, const char*> display_input(const RobotModel& model, const ActuationInput& input,
                                             double value) {
  if (input.kind == ActuationInput::Kind::RodLength) return {value * kMillimetre, "mm"};
  const JointType type = model.joints()[input.index].type;
  if (type == JointType::Prismatic) return {value * kMillimetre, "mm"};
  return {value * kDegree, "deg"};
}

/// Value and unit of a joint value for display: prismatic in mm, angles in degrees.
std::pair<double, const char*> display_joint(const Joint& joint, double value) {
  if (joint.type == JointType::Prismatic) return {value * kMillimetre, "mm"};
  return {value * kDegree, "deg"};
}

/// Values that print as zero at the table's precision (half a unit of the last digit) set to +0, so
/// the table shows no "-0.000".
VecX tidy(VecX v, double half_unit) {
  for (int i = 0; i < v.size(); ++i)
    if (std::abs(v[i]) < half_unit) v[i] = 0.0;
  return v;
}

/// One pose row of the platforms' and links' tables.
std::string pose_row(const std::string& name, const Pose& pose) {
  const Vec3 x = tidy(pose.position * kMillimetre, 5e-4), rpy = tidy(pose.rpy() * kDegree, 5e-4);
  const VecX q = tidy(pose.orientation, 5e-7);
  return format("  %-14s %9.3f %9.3f %9.3f   %8.3f %8.3f %8.3f   %.6f %.6f %.6f %.6f\n", name.c_str(), x[0],
                x[1], x[2], rpy[0], rpy[1], rpy[2], q[0], q[1], q[2], q[3]);
}

std::string pose_header(const char* title) {
  return format("%-16s %9s %9s %9s   %8s %8s %8s   %s\n", title, "x [mm]", "y [mm]", "z [mm]", "roll",
                "pitch", "yaw [deg]", "quaternion [w x y z]");
}

}  // namespace

void write_link_table(std::ostream& out, const std::vector<LinkPose>& links) {
  if (links.empty()) return;
  out << pose_header("links:");
  for (const LinkPose& link : links) out << pose_row(link.link, link.pose);
}

void write_solution_table(std::ostream& out, const RobotModel& model, const RobotSolution& solution) {
  const SolveSummary& s = solution.summary;
  out << "model " << model.name() << ": " << to_string(s.status) << " (" << s.solver << ", " << s.iterations
      << " iterations, residual " << format("%.3g", s.residual_max_abs) << ", "
      << format("%.3g", s.wall_time_seconds * 1e3) << " ms)\n";
  if (!s.converged() && !s.message.empty()) out << "  message: " << s.message << "\n";
  write_stability_line(out, solution.stability_verdict);
  write_contact_lines(out, solution.contacts, solution.contact_gaps);
  if (!model.inputs().empty()) {
    out << "inputs:\n";
    for (size_t i = 0; i < model.inputs().size(); ++i) {
      const ActuationInput& input = model.inputs()[i];
      const auto shown = display_input(model, input, solution.inputs[static_cast<int>(i)]);
      out << format("  %-16s %12.4f %s\n", input.name.c_str(), shown.first, shown.second);
    }
  }
  const std::vector<int>& passive = model.passive_joints();
  if (!passive.empty() && solution.passive_joints.size() == static_cast<int>(passive.size())) {
    // Their limits are not enforced by the solve: a value beyond them is flagged.
    out << "passive joints:\n";
    for (size_t i = 0; i < passive.size(); ++i) {
      const Joint& joint = model.joints()[passive[i]];
      const double value = solution.passive_joints[static_cast<int>(i)];
      const auto shown = display_joint(joint, value);
      out << format("  %-16s %12.4f %s", joint.name.c_str(), tidy(VecX::Constant(1, shown.first), 5e-5)[0],
                    shown.second);
      if (!joint.within_limits(value)) {
        out << format("   (outside its limits [%g, %g] %s)", display_joint(joint, joint.lower).first,
                      display_joint(joint, joint.upper).first, shown.second);
      }
      out << "\n";
    }
  }
  if (!solution.platforms.empty()) {
    out << pose_header("platforms:");
    for (size_t p = 0; p < solution.platforms.size(); ++p)
      out << pose_row(model.platforms()[p].name, solution.platforms[p]);
  }
  out << format("%-16s %12s %15s %15s\n", "rods:", "length [mm]", "axial force [N]", "|n(0)| [N]");
  for (const RodResult& rod : solution.rods)
    out << format("  %-14s %12.4f %15.6f %15.6f\n", rod.name.c_str(), rod.length * kMillimetre,
                  rod.axial_force, rod.base_force.norm());
}

}  // namespace pcr
