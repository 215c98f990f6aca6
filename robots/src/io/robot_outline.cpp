#include "pcr/robots/io/robot_outline.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "pcr/core/error.hpp"

namespace pcr {
namespace {

/// Orders points by angle around their centroid in the plane normal to the covariance's weakest
/// direction (smallest eigenvalue of sum (p - c)(p - c)^T); collinear points are ordered along their
/// line. Returns whether the points form a polygon.
bool order_around_centroid(std::vector<Vec3>& points) {
  if (points.size() < 2) return false;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Mat3 covariance = Mat3::Zero();
  for (const Vec3& p : points) covariance += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(covariance);  // eigenvalues ascending
  const Vec3 u = eigen.eigenvectors().col(2), v = eigen.eigenvectors().col(1);
  // Collinear when the spread across the line is below 1e-6 of the spread along it (variance ratio
  // 1e-12, well above the eigensolver's round-off of ~1e-16 relative to the largest eigenvalue).
  const bool polygon = points.size() >= 3 && eigen.eigenvalues()[1] > 1e-12 * eigen.eigenvalues()[2];
  std::vector<std::pair<double, Vec3>> keyed;
  for (const Vec3& p : points) {
    const Vec3 d = p - centroid;
    keyed.emplace_back(polygon ? std::atan2(d.dot(v), d.dot(u)) : d.dot(u), p);
  }
  std::stable_sort(
      keyed.begin(), keyed.end(),
      [](const std::pair<double, Vec3>& a, const std::pair<double, Vec3>& b) { return a.first < b.first; });
  for (size_t k = 0; k < points.size(); ++k) points[k] = keyed[k].second;
  return polygon;
}

}  // namespace

VecX joint_values_of_inputs(const RobotModel& model, const VecX& inputs) {
  require(inputs.size() == static_cast<int>(model.inputs().size()), "joint_values_of_inputs: ", inputs.size(),
          " values for ", model.inputs().size(), " inputs of model '", model.name(), "'");
  VecX q = model.default_joint_values();
  for (size_t i = 0; i < model.inputs().size(); ++i) {
    const ActuationInput& input = model.inputs()[i];
    if (input.kind == ActuationInput::Kind::JointValue)
      q[model.joints()[input.index].value_index] = inputs[static_cast<int>(i)];
  }
  return q;
}

std::vector<Outline> robot_outlines(const RobotModel& model, const RobotSolution& solution) {
  require(solution.platforms.size() == model.platforms().size(),
          "robot_outlines: ", solution.platforms.size(), " platform poses for ", model.platforms().size(),
          " platforms");
  VecX q = joint_values_of_inputs(model, solution.inputs);
  const std::vector<int>& passive = model.passive_joints();
  if (solution.passive_joints.size() == static_cast<int>(passive.size()))
    for (size_t i = 0; i < passive.size(); ++i)
      q[model.joints()[passive[i]].value_index] = solution.passive_joints[static_cast<int>(i)];
  std::vector<Outline> outlines(model.platforms().size() + 1);
  outlines[0].name = "base";
  for (size_t p = 0; p < model.platforms().size(); ++p) {
    outlines[p + 1].name = model.platforms()[p].name;
    outlines[p + 1].platform = static_cast<int>(p);
  }
  for (const RodElement& rod : model.rods()) {
    for (const RodAttachment* end : {&rod.start, &rod.end}) {
      if (end->link < 0) continue;  // free end
      Outline& outline = outlines[model.carrying_platform(end->link) + 1];
      const Vec3 point = model.attachment_pose(*end, q, solution.platforms).position;
      const bool seen = std::any_of(outline.points.begin(), outline.points.end(),
                                    [&](const Vec3& p) { return (p - point).norm() < 1e-9; });
      if (!seen) outline.points.push_back(point);
    }
  }
  std::vector<Outline> out;
  for (Outline& outline : outlines) {
    if (outline.points.empty()) continue;
    outline.closed = order_around_centroid(outline.points);
    out.push_back(std::move(outline));
  }
  return out;
}

}  // namespace pcr
