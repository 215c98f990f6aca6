#include "targets.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <Eigen/QR>

#include "pcr/core/error.hpp"
#include "pcr/math/so3.hpp"
#include "pcr/robots/io/solution_writers.hpp"

namespace pcr_app {
namespace {

const char* const kComponentNames[6] = {"x", "y", "z", "rx", "ry", "rz"};

bool mode_has(const pcr::LinkTarget& target, int component) {
  return component < 3 ? target.mode != pcr::LinkTarget::Mode::Orientation
                       : target.mode != pcr::LinkTarget::Mode::Position;
}

bool selected(const pcr::LinkTarget& target, int component) {
  return target.components[component] && mode_has(target, component);
}

/// The scaled rows d(selected target components)/d(inputs) at the FK solution `fk` holds: position rows
/// [m] of the link origin x_p + R_p o (dx = dx_p - (R_p o) x dtheta_p), rotation rows in the target frame
/// (R_t^T dtheta_p, the linearisation of the target residual 2 vec(Q_t* Q)); divided by the length scale
/// for positions, inputs of length multiplied by it, so that all entries are dimensionless. Row names
/// in `names`.
pcr::MatX target_jacobian(const pcr::ForwardKinematics& fk, const pcr::RobotSolution& solution,
                          const std::vector<pcr::LinkTarget>& targets, std::vector<std::string>& names) {
  const pcr::RobotAssembly& assembly = fk.assembly();
  const pcr::RobotModel& model = assembly.model();
  const double length = assembly.length_scale();
  const pcr::MatX J = fk.input_jacobian();
  const std::vector<pcr::LinkPose> links = pcr::link_poses(model, solution, [&] {
    std::vector<std::string> n;
    for (const pcr::LinkTarget& t : targets) n.push_back(t.link);
    return n;
  }());
  std::vector<pcr::VecX> rows;
  for (size_t k = 0; k < targets.size(); ++k) {
    const pcr::LinkTarget& t = targets[k];
    const int p = model.carrying_platform(model.link_index(t.link));
    const pcr::MatX Jx = J.middleRows(6 * p, 3), Jr = J.middleRows(6 * p + 3, 3);
    const pcr::Vec3 arm = links[k].pose.position - solution.platforms[p].position;
    pcr::MatX position = Jx;
    for (int c = 0; c < Jx.cols(); ++c) position.col(c) -= arm.cross(pcr::Vec3(Jr.col(c)));
    const pcr::MatX rotation = t.pose.rotation().transpose() * Jr;
    for (int i = 0; i < 6; ++i) {
      if (!selected(t, i)) continue;
      rows.push_back(i < 3 ? pcr::VecX(position.row(i).transpose() / length)
                           : pcr::VecX(rotation.row(i - 3).transpose()));
      names.push_back(t.link + "." + kComponentNames[i]);
    }
  }
  pcr::MatX A(static_cast<int>(rows.size()), J.cols());
  for (size_t r = 0; r < rows.size(); ++r) A.row(static_cast<int>(r)) = rows[r].transpose();
  for (int c = 0; c < A.cols(); ++c) {
    const pcr::ActuationInput& in = model.inputs()[c];
    const bool angle = in.kind == pcr::ActuationInput::Kind::JointValue &&
                       model.joints()[in.index].type != pcr::JointType::Prismatic;
    if (!angle) A.col(c) *= length;
  }
  return A;
}

/// Target rows split by a column-pivoted QR of A^T: its pivots are the rows of A in order of
/// independence; the first min(rank, inputs) are those the inputs can meet together.
struct RowAdvice {
  std::vector<int> kept, dropped;  // row indices
};

RowAdvice split_rows(const pcr::MatX& A, int inputs) {
  Eigen::ColPivHouseholderQR<pcr::MatX> qr(A.transpose());
  qr.setThreshold(1e-8);  // relative to the largest pivot: rows below it are not moved by the inputs
  const int keep = std::min<int>(static_cast<int>(qr.rank()), inputs);
  RowAdvice advice;
  for (int k = 0; k < A.rows(); ++k)
    (k < keep ? advice.kept : advice.dropped).push_back(qr.colsPermutation().indices()[k]);
  std::sort(advice.kept.begin(), advice.kept.end());
  std::sort(advice.dropped.begin(), advice.dropped.end());
  return advice;
}

std::string join(const std::vector<int>& rows, const std::vector<std::string>& names) {
  std::string out;
  for (int r : rows) out += (out.empty() ? "" : ", ") + names[static_cast<size_t>(r)];
  return out;
}

/// " --components LINK=LIST" per target, with the kept rows (names LINK.component, in target order).
std::string components_example(const std::vector<pcr::LinkTarget>& targets, const std::vector<int>& kept,
                               const std::vector<std::string>& names) {
  std::string out;
  for (const pcr::LinkTarget& t : targets) {
    std::string list;
    for (int r : kept) {
      const std::string& name = names[static_cast<size_t>(r)];
      if (name.compare(0, t.link.size() + 1, t.link + ".") == 0)
        list += (list.empty() ? "" : ",") + name.substr(t.link.size() + 1);
    }
    if (!list.empty()) out += " --components " + t.link + "=" + list;
  }
  return out;
}

}  // namespace

pcr::LinkTarget parse_target(const NamedArgument& arg) {
  const std::vector<double> v = parse_numbers(arg.value, arg.text());
  pcr::LinkTarget target;
  target.link = arg.name;
  size_t q = 0;  // index of the quaternion's w, if any
  if (arg.option == "--orientation-only") {
    if (v.size() != 4) throw UsageError(arg.text() + ": expected 4 numbers qw,qx,qy,qz");
    target.mode = pcr::LinkTarget::Mode::Orientation;
  } else if (v.size() == 3) {
    target.mode = pcr::LinkTarget::Mode::Position;
  } else if (v.size() == 7) {
    target.mode = pcr::LinkTarget::Mode::Pose;
    q = 3;
  } else {
    throw UsageError(arg.text() + ": expected 3 numbers x,y,z or 7 numbers x,y,z,qw,qx,qy,qz, got " +
                     std::to_string(v.size()));
  }
  if (target.mode != pcr::LinkTarget::Mode::Orientation) target.pose.position = pcr::Vec3(v[0], v[1], v[2]);
  if (target.mode != pcr::LinkTarget::Mode::Position) {
    const pcr::Quat quaternion(v[q], v[q + 1], v[q + 2], v[q + 3]);
    if (!(quaternion.norm() > 1e-12)) throw UsageError(arg.text() + ": the quaternion is zero");
    target.pose.orientation = quaternion.normalized();
  }
  return target;
}

int component_index(const std::string& name) {
  for (int i = 0; i < 6; ++i)
    if (name == kComponentNames[i]) return i;
  return -1;
}

std::string selected_components(const pcr::LinkTarget& target) {
  std::string out;
  for (int i = 0; i < 6; ++i)
    if (selected(target, i)) out += (out.empty() ? "" : ", ") + std::string(kComponentNames[i]);
  return out;
}

int target_rows(const pcr::LinkTarget& target) {
  int rows = 0;
  for (int i = 0; i < 6; ++i) rows += selected(target, i) ? 1 : 0;
  return rows;
}

void apply_components(std::vector<pcr::LinkTarget>& targets, const std::vector<NamedArgument>& components) {
  for (const NamedArgument& arg : components) {
    auto target = std::find_if(targets.begin(), targets.end(),
                               [&](const pcr::LinkTarget& t) { return t.link == arg.name; });
    if (target == targets.end()) throw UsageError(arg.text() + ": no target on link '" + arg.name + "'");
    std::array<bool, 6> mask{};
    std::istringstream list(arg.value);
    std::string name;
    while (std::getline(list, name, ',')) {
      const int i = component_index(name);
      if (i < 0) throw UsageError(arg.text() + ": unknown component '" + name + "' (x, y, z, rx, ry, rz)");
      if (!mode_has(*target, i))
        throw UsageError(arg.text() + ": the target on '" + arg.name + "' has no " +
                         (i < 3 ? "position" : "orientation") + " (component '" + name + "')");
      mask[i] = true;
    }
    target->components = mask;
    if (target_rows(*target) == 0) throw UsageError(arg.text() + ": no component selected");
  }
}

void check_target_rows(const std::shared_ptr<const pcr::RobotAssembly>& assembly,
                       const std::vector<pcr::LinkTarget>& targets, const pcr::VecX& reference,
                       const pcr::KinematicsOptions& options) {
  const pcr::RobotModel& model = assembly->model();
  const int inputs = static_cast<int>(model.inputs().size());
  int rows = 0;
  std::string listed;
  for (const pcr::LinkTarget& t : targets) {
    rows += target_rows(t);
    listed += (listed.empty() ? "" : "; ") + t.link + ": " + selected_components(t);
  }
  if (rows <= inputs) return;
  std::ostringstream message;
  message << "the targets have " << rows << " rows (" << listed << ") but model '" << model.name() << "' has "
          << inputs << " input" << (inputs == 1 ? "" : "s") << ": at most " << inputs
          << " target rows can be met in general; select them with --components";
  for (const pcr::LinkTarget& t : targets)
    if (model.carrying_platform(model.link_index(t.link)) < 0) throw UsageError(message.str());
  try {
    pcr::KinematicsOptions fk_options = options;
    fk_options.solver = pcr::SolverKind::Newton;
    pcr::ForwardKinematics fk(assembly, fk_options);
    const pcr::RobotSolution solution = fk.solve(reference);
    if (solution.summary.converged()) {
      std::vector<std::string> names;
      const pcr::MatX A = target_jacobian(fk, solution, targets, names);
      const RowAdvice advice = split_rows(A, inputs);
      message << ";\n  at the reference inputs the inputs move " << join(advice.kept, names)
              << " independently and " << join(advice.dropped, names) << " least: drop those, e.g."
              << components_example(targets, advice.kept, names);
    }
  } catch (const pcr::InputError&) {
    // no advice where the Jacobian is singular: the counts above stand alone
  }
  throw UsageError(message.str());
}

void print_target_errors(std::ostream& out, const pcr::RobotModel& model, const pcr::RobotSolution& solution,
                         const std::vector<pcr::LinkTarget>& targets) {
  const pcr::VecX q = pcr::joint_values_of_solution(model, solution);
  for (const pcr::LinkTarget& target : targets) {
    const pcr::Pose reached = model.link_pose(model.link_index(target.link), q, solution.platforms);
    const double position_error_mm = (reached.position - target.pose.position).norm() * 1e3;
    const double angle_error_deg =
        pcr::rotation_angle_between(reached.rotation(), target.pose.rotation()) * 57.295779513082321;
    const std::string name = target_rows(target) == (target.mode == pcr::LinkTarget::Mode::Pose ? 6 : 3)
                                 ? target.link
                                 : target.link + " (" + selected_components(target) + " selected)";
    char line[300];
    if (target.mode == pcr::LinkTarget::Mode::Position)
      std::snprintf(line, sizeof line, "target %s: position error %.3g mm\n", name.c_str(),
                    position_error_mm);
    else if (target.mode == pcr::LinkTarget::Mode::Orientation)
      std::snprintf(line, sizeof line, "target %s: orientation error %.3g deg\n", name.c_str(),
                    angle_error_deg);
    else
      std::snprintf(line, sizeof line, "target %s: position error %.3g mm, orientation error %.3g deg\n",
                    name.c_str(), position_error_mm, angle_error_deg);
    out << line;
  }
}

std::vector<std::string> reported_links(const pcr::RobotModel& model,
                                        const std::vector<pcr::LinkTarget>& targets,
                                        const std::vector<std::string>& extra) {
  std::vector<std::string> out;
  auto add = [&](const std::string& link) {
    model.link_index(link);  // throws InputError naming an unknown link
    if (std::find(out.begin(), out.end(), link) == out.end()) out.push_back(link);
  };
  for (const pcr::LinkTarget& t : targets)
    if (model.platform_of_link(model.link_index(t.link)) < 0) add(t.link);
  for (const std::string& link : extra) add(link);
  return out;
}

}  // namespace pcr_app
