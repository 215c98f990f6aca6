// The kinematic part of the rod end couplings (energy_terms.hpp CouplingRows).
#include <utility>

#include "energy_kinematics.hpp"
#include "energy_terms.hpp"

namespace pcr::kinematics {

namespace {

/// Local quantities: the rod end [p (3), q (4)], the platform [x (3), Q (4)], and a displacement
/// delta (3) and rotation vector theta (3) of the attachment frame (links moved by passive joints).
constexpr int kLocal = 20;
using D = Dual<kLocal>;

/// The rows of a coupling of `kind` between the rod end (p, R) and the attachment frame (X, Ra).
template <class T>
void coupling_rows(const RodAttachment& a, const V3<T>& p, const M3<T>& R, const V3<T>& X, const M3<T>& Ra,
                   double length_scale, T* rows) {
  const V3<T> gap = (p - X) / length_scale;
  for (int i = 0; i < 3; ++i) rows[i] = gap[i];
  const Vec3 axis = a.axis.normalized();
  switch (a.coupling) {
    case RodEndKind::Clamped: {
      // The skew part of Ra^T R - I: zero when R = Ra (and at half turns, far from any start used here).
      const M3<T> S = Ra.transpose() * R;
      rows[3] = 0.5 * (S(2, 1) - S(1, 2));
      rows[4] = 0.5 * (S(0, 2) - S(2, 0));
      rows[5] = 0.5 * (S(1, 0) - S(0, 1));
      break;
    }
    case RodEndKind::Collar:  // d3 = R e3 normal to Ra e1 and Ra e2
      rows[3] = Ra.col(0).dot(R.col(2));
      rows[4] = Ra.col(1).dot(R.col(2));
      break;
    case RodEndKind::Revolute: {  // R a = Ra a: R a normal to Ra b1, Ra b2 (b1, b2 normal to a)
      const Vec3 b1 = axis.unitOrthogonal(), b2 = axis.cross(b1);
      const V3<T> Rax = R * axis.cast<T>();
      rows[3] = (Ra * b1.cast<T>()).dot(Rax);
      rows[4] = (Ra * b2.cast<T>()).dot(Rax);
      break;
    }
    case RodEndKind::Universal: {  // Ra a normal to R b, b = e3 x a / |e3 x a| in the rod's body frame
      const Vec3 b = Vec3::UnitZ().cross(axis).normalized();
      rows[3] = (Ra * axis.cast<T>()).dot(R * b.cast<T>());
      break;
    }
    default: break;  // spherical: the position only
  }
}

}  // namespace

int CouplingRows::rows_of(RodEndKind kind) {
  switch (kind) {
    case RodEndKind::Clamped: return 6;
    case RodEndKind::Collar:
    case RodEndKind::Revolute: return 5;
    case RodEndKind::Universal: return 4;
    case RodEndKind::Spherical: return 3;
    default: return 0;
  }
}

CouplingRows::CouplingRows(const RobotModel& model, const RodAttachment& attachment, VecX joint_values,
                           const Pose& platform_from_attachment, std::vector<VariableId> variables,
                           int platform_count, std::vector<int> passive_joints, double length_scale)
    : ResidualBlock("energy.coupling", "", rows_of(attachment.coupling), std::move(variables)),
      model_(model),
      attachment_(attachment),
      joint_values_(std::move(joint_values)),
      platform_from_attachment_(platform_from_attachment),
      on_platform_(platform_count > 0),
      passive_joints_(std::move(passive_joints)),
      length_scale_(length_scale) {
  sizes_.assign(this->variables().size(), 1);
  sizes_[0] = 7;
  if (on_platform_) sizes_[1] = 7;
}

void CouplingRows::evaluate(const double* const* values, double* residual, double* const* jacobians) const {
  V3<D> p, X;
  V4<D> q;
  M3<D> Ra;
  for (int i = 0; i < 3; ++i) p[i] = D::variable(values[0][i], i);
  for (int i = 0; i < 4; ++i) q[i] = D::variable(values[0][3 + i], 3 + i);
  const int first_passive = on_platform_ ? 2 : 1;
  std::vector<Vec3> dX(passive_joints_.size()), dtheta(passive_joints_.size());  // per passive joint
  if (on_platform_) {
    V3<D> x;
    V4<D> Q;
    for (int i = 0; i < 3; ++i) x[i] = D::variable(values[1][i], 7 + i);
    for (int i = 0; i < 4; ++i) Q[i] = D::variable(values[1][3 + i], 10 + i);
    const M3<D> RQ = collocation::rotation(Q);
    X = x + RQ * platform_from_attachment_.position.cast<D>();
    Ra = RQ * platform_from_attachment_.rotation().cast<D>();
  } else {
    VecX jv = joint_values_;
    for (std::size_t j = 0; j < passive_joints_.size(); ++j)
      jv[model_.joints()[passive_joints_[j]].value_index] = values[first_passive + j][0];
    const std::vector<Pose> platforms = model_.initial_platform_poses();  // unused: no platform link
    const Pose at = model_.attachment_pose(attachment_, jv, platforms);
    V3<D> delta, theta;
    for (int i = 0; i < 3; ++i) delta[i] = D::variable(0.0, 14 + i), theta[i] = D::variable(0.0, 17 + i);
    X = at.position.cast<D>() + delta;
    // Ra = (I + hat(theta)) R0: the first-order rotation, exact in value and derivative at theta = 0.
    Ra = at.rotation().cast<D>();
    for (int c = 0; c < 3; ++c) Ra.col(c) += theta.cross(at.rotation().col(c).cast<D>());
    for (std::size_t j = 0; j < passive_joints_.size(); ++j) {
      // The attachment moves with the joint: omega x (X - o) and omega (revolute), the axis (prismatic).
      const Joint& joint = model_.joints()[passive_joints_[j]];
      const Pose frame = model_.link_pose(joint.parent_link, jv, platforms) * joint.origin;
      const Vec3 axis = frame.rotation() * joint.axis.normalized();
      const bool prismatic = joint.type == JointType::Prismatic;
      dX[j] = prismatic ? axis : Vec3(axis.cross(at.position - frame.position));
      dtheta[j] = prismatic ? Vec3::Zero() : axis;
    }
  }
  D rows[6];
  coupling_rows(attachment_, p, collocation::rotation(q), X, Ra, length_scale_, rows);
  for (int r = 0; r < num_rows(); ++r) residual[r] = rows[r].a;
  if (!jacobians) return;
  for (int r = 0; r < num_rows(); ++r) {
    const D::Grad& g = rows[r].v;
    if (jacobians[0])
      for (int c = 0; c < 7; ++c) jacobians[0][r * 7 + c] = g[c];
    if (on_platform_ && jacobians[1])
      for (int c = 0; c < 7; ++c) jacobians[1][r * 7 + c] = g[7 + c];
    for (std::size_t j = 0; j < passive_joints_.size(); ++j)
      if (jacobians[first_passive + j])
        jacobians[first_passive + j][r] = g.segment<3>(14).dot(dX[j]) + g.segment<3>(17).dot(dtheta[j]);
  }
}

}  // namespace pcr::kinematics
