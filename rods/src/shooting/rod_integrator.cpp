#include "pcr/rods/shooting/rod_integrator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "pcr/core/error.hpp"

namespace pcr {
namespace {

// Dormand-Prince 5(4) tableau (Hairer, Norsett & Wanner, Solving ODEs I, Table 5.2).
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
// 5th-order weights (also row 7 of the tableau: first same as last).
constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
// Error weights e = b - b_hat (b_hat: the embedded 4th-order solution).
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                 e6 = 22.0 / 525, e7 = -1.0 / 40;

// Renormalise q after a step. For the tangents: d(q/|q|) = (dq - qhat (qhat . dq)) / |q|.
void normalise(RodStateVector& y) {
  y.segment<4>(RodStateIndex::q).normalize();
}
void normalise(RodStateWithTangents& Y) {
  const double norm = Y.col(0).segment<4>(RodStateIndex::q).norm();
  const Quat q_hat = Y.col(0).segment<4>(RodStateIndex::q) / norm;
  Y.col(0).segment<4>(RodStateIndex::q) = q_hat;
  for (int j = 1; j < Y.cols(); ++j) {
    const Quat dq = Y.col(j).segment<4>(RodStateIndex::q);
    Y.col(j).segment<4>(RodStateIndex::q) = (dq - q_hat * q_hat.dot(dq)) / norm;
  }
}

template <typename State>
void rk4_step(const RodOde& ode, double s, double h, State& y, State& k1, State& k2, State& k3, State& k4,
              State& tmp) {
  ode.derivative(s, y, k1);
  tmp = y + (0.5 * h) * k1;
  ode.derivative(s + 0.5 * h, tmp, k2);
  tmp = y + (0.5 * h) * k2;
  ode.derivative(s + 0.5 * h, tmp, k3);
  tmp = y + h * k3;
  ode.derivative(s + h, tmp, k4);
  y += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

struct DormandPrinceStages {
  template <typename State>
  static void step(const RodOde& ode, double s, double h, const State& y, const State& k1, State& k2,
                   State& k3, State& k4, State& k5, State& k6, State& k7, State& tmp, State& y_new,
                   bool last_stage = true) {
    tmp = y + h * (a21 * k1);
    ode.derivative(s + c2 * h, tmp, k2);
    tmp = y + h * (a31 * k1 + a32 * k2);
    ode.derivative(s + c3 * h, tmp, k3);
    tmp = y + h * (a41 * k1 + a42 * k2 + a43 * k3);
    ode.derivative(s + c4 * h, tmp, k4);
    tmp = y + h * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4);
    ode.derivative(s + c5 * h, tmp, k5);
    tmp = y + h * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5);
    ode.derivative(s + h, tmp, k6);
    y_new = y + h * (b1 * k1 + b3 * k3 + b4 * k4 + b5 * k5 + b6 * k6);
    if (last_stage) ode.derivative(s + h, y_new, k7);  // for the error estimate and FSAL
  }
};

void record(RodTrajectory* trajectory, double s, const RodStateVector& y) {
  if (!trajectory) return;
  trajectory->s.push_back(s);
  trajectory->y.push_back(y);
}
void record(RodTrajectory* trajectory, double s, const RodStateWithTangents& Y) {
  if (!trajectory) return;
  trajectory->s.push_back(s);
  trajectory->y.push_back(Y.col(0));
}

RodStateVector state_of(const RodStateVector& y) {
  return y;
}
RodStateVector state_of(const RodStateWithTangents& Y) {
  return Y.col(0);
}

std::string failure(const char* what, double s) {
  std::ostringstream out;
  out << what << " at s = " << s;
  return out.str();
}

void check_interval(double s0, double s1) {
  require(std::isfinite(s0) && std::isfinite(s1) && s1 >= s0,
          "integrate_rod: need finite s0 <= s1, got s0 = ", s0, ", s1 = ", s1);
}

}  // namespace

void check_integrator_options(const IntegratorOptions& o) {
  if (o.method == IntegratorMethod::RK4) {
    require(o.rk4_steps >= 1, "integrate_rod: rk4_steps must be >= 1, got ", o.rk4_steps);
  } else {
    require(std::isfinite(o.relative_tolerance) && o.relative_tolerance > 0.0,
            "integrate_rod: relative_tolerance must be positive, got ", o.relative_tolerance);
    require(std::isfinite(o.absolute_tolerance) && o.absolute_tolerance > 0.0,
            "integrate_rod: absolute_tolerance must be positive, got ", o.absolute_tolerance);
    require(o.min_step_fraction > 0.0 && o.min_step_fraction < 1.0,
            "integrate_rod: min_step_fraction must lie in (0, 1), got ", o.min_step_fraction);
    require(o.max_steps >= 1, "integrate_rod: max_steps must be >= 1, got ", o.max_steps);
  }
}

namespace {

template <typename State>
IntegrationReport integrate_rk4(const RodOde& ode, double s0, double s1, State& y, const IntegratorOptions& o,
                                RodTrajectory* trajectory) {
  IntegrationReport report;
  record(trajectory, s0, y);
  if (s1 == s0) return report;
  // The step count is defined over the whole rod length, so that a partial interval (dense output)
  // uses the same step size.
  const double h_nominal = ode.length() / o.rk4_steps;
  const int steps = std::max(1, static_cast<int>(std::ceil((s1 - s0) / h_nominal - 1e-9)));
  const double h = (s1 - s0) / steps;
  State k1, k2, k3, k4, tmp;
  for (int i = 0; i < steps; ++i) {
    const double s = s0 + i * h;
    rk4_step(ode, s, h, y, k1, k2, k3, k4, tmp);
    normalise(y);
    if (!y.allFinite()) {
      report.success = false;
      report.message = failure("non-finite state", s + h);
      return report;
    }
    ++report.steps;
    record(trajectory, i + 1 == steps ? s1 : s + h, y);
  }
  return report;
}

// RMS of e weighted by absolute_tolerance * scale_i + relative_tolerance * max(|y_a,i|, |y_b,i|), the
// norm of the step-size control (Hairer, Norsett & Wanner II.4).
struct WeightedRms {
  const IntegratorOptions& o;
  const RodStateVector& scale;
  double operator()(const RodStateVector& e, const RodStateVector& y_a, const RodStateVector& y_b) const {
    double sum = 0.0;
    for (int i = 0; i < kRodStateSize; ++i) {
      const double sc = o.absolute_tolerance * scale[i] +
                        o.relative_tolerance * std::max(std::abs(y_a[i]), std::abs(y_b[i]));
      sum += (e[i] / sc) * (e[i] / sc);
    }
    return std::sqrt(sum / kRodStateSize);
  }
};

// Initial step: h = 0.01 |y| / |y'| in the weighted norm (Hairer, Norsett & Wanner II.4, simplified),
// within [10 h_min, span]; then the controller adapts it.
double initial_step(const WeightedRms& weighted_rms, const RodStateVector& y0, const RodStateVector& f0,
                    double span, double h_min) {
  const double d0 = weighted_rms(y0, y0, y0), d1 = weighted_rms(f0, y0, y0);
  const double h = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 * span : 0.01 * d0 / d1;
  return std::min(std::max(h, 10.0 * h_min), span);
}

// k1 = f(s, y) at the start of the next step, y the renormalised y_new. First same as last: k7 =
// f(y_new); renormalising q scales f's q part by 1/|q| (degree-1 homogeneous in q, the rest is
// independent of |q|), except for the tangents: recompute then.
template <typename State>
void next_first_stage(const RodOde& ode, double s, const State& y, const State& y_new, const State& k7,
                      State& k1) {
  if (std::is_same<State, RodStateVector>::value) {
    k1 = k7;
    const double norm = state_of(y_new).template segment<4>(RodStateIndex::q).norm();
    k1.col(0).template segment<4>(RodStateIndex::q) /= norm;
  } else {
    ode.derivative(s, y, k1);
  }
}

IntegrationReport failed(IntegrationReport report, const char* what, double s) {
  report.success = false;
  report.message = failure(what, s);
  return report;
}

template <typename State>
IntegrationReport integrate_dormand_prince(const RodOde& ode, double s0, double s1, State& y,
                                           const IntegratorOptions& o, RodTrajectory* trajectory) {
  IntegrationReport report;
  record(trajectory, s0, y);
  if (s1 == s0) return report;
  const double span = s1 - s0;
  const double h_min = o.min_step_fraction * span;
  const WeightedRms weighted_rms{o, ode.state_scale()};
  State k1, k2, k3, k4, k5, k6, k7, tmp, y_new;
  ode.derivative(s0, y, k1);
  double h = initial_step(weighted_rms, state_of(y), state_of(k1), span, h_min);
  double s = s0;
  bool last_rejected = false;
  while (s < s1) {
    if (report.steps + report.rejected_steps >= o.max_steps)
      return failed(report, "too many steps (max_steps reached)", s);
    const bool last = s + h >= s1 - 1e-14 * span;
    if (last) h = s1 - s;
    DormandPrinceStages::step(ode, s, h, y, k1, k2, k3, k4, k5, k6, k7, tmp, y_new);
    // Error estimate on the state only (column 0).
    const RodStateVector err = h * (e1 * k1.col(0) + e3 * k3.col(0) + e4 * k4.col(0) + e5 * k5.col(0) +
                                    e6 * k6.col(0) + e7 * k7.col(0));
    const double error = weighted_rms(err, state_of(y), state_of(y_new));
    if (!std::isfinite(error)) {
      // Non-finite trial: shrink the step hard; fail if that is impossible.
      if (h <= h_min) return failed(report, "non-finite state", s);
      h = std::max(0.1 * h, h_min);
      ++report.rejected_steps;
      last_rejected = true;
      continue;
    }
    // Step-size controller: h_new = h * clamp(0.9 err^(-1/5), 0.2, 5), no growth right after a rejection.
    double factor = error == 0.0 ? 5.0 : 0.9 * std::pow(error, -0.2);
    if (error <= 1.0) {
      s = last ? s1 : s + h;
      y = y_new;
      normalise(y);
      next_first_stage(ode, s, y, y_new, k7, k1);
      ++report.steps;
      record(trajectory, s, y);
      factor = std::min(last_rejected ? 1.0 : 5.0, std::max(0.2, factor));
      last_rejected = false;
      h *= factor;
    } else {
      ++report.rejected_steps;
      last_rejected = true;
      h *= std::max(0.2, factor);
      if (h < h_min) return failed(report, "step size underflow (min_step_fraction reached)", s);
    }
  }
  return report;
}

template <typename State>
IntegrationReport integrate(const RodOde& ode, double s0, double s1, State& y, const IntegratorOptions& o,
                            RodTrajectory* trajectory) {
  check_interval(s0, s1);
  check_integrator_options(o);
  if (o.method == IntegratorMethod::RK4) return integrate_rk4(ode, s0, s1, y, o, trajectory);
  return integrate_dormand_prince(ode, s0, s1, y, o, trajectory);
}

template <typename State>
IntegrationReport integrate_mesh(const RodOde& ode, const std::vector<double>& mesh, State& y,
                                 IntegratorMethod method, RodTrajectory* trajectory) {
  require(!mesh.empty(), "integrate_rod_on_mesh: empty mesh");
  for (size_t i = 0; i < mesh.size(); ++i)
    require(std::isfinite(mesh[i]) && (i == 0 || mesh[i] > mesh[i - 1]),
            "integrate_rod_on_mesh: mesh must be finite and strictly increasing, got s[", i, "] = ", mesh[i]);
  IntegrationReport report;
  record(trajectory, mesh[0], y);
  State k1, k2, k3, k4, k5, k6, k7, tmp, y_new;
  for (size_t i = 0; i + 1 < mesh.size(); ++i) {
    const double s = mesh[i], h = mesh[i + 1] - mesh[i];
    if (method == IntegratorMethod::RK4) {
      rk4_step(ode, s, h, y, k1, k2, k3, k4, tmp);
    } else {
      ode.derivative(s, y, k1);
      DormandPrinceStages::step(ode, s, h, y, k1, k2, k3, k4, k5, k6, k7, tmp, y_new, false);
      y = y_new;
    }
    normalise(y);
    if (!y.allFinite()) {
      report.success = false;
      report.message = failure("non-finite state", mesh[i + 1]);
      return report;
    }
    ++report.steps;
    record(trajectory, mesh[i + 1], y);
  }
  return report;
}

}  // namespace

IntegrationReport integrate_rod_on_mesh(const RodOde& ode, const std::vector<double>& mesh, RodStateVector& y,
                                        IntegratorMethod method, RodTrajectory* trajectory) {
  return integrate_mesh(ode, mesh, y, method, trajectory);
}

IntegrationReport integrate_rod_on_mesh(const RodOde& ode, const std::vector<double>& mesh,
                                        RodStateWithTangents& Y, IntegratorMethod method,
                                        RodTrajectory* trajectory) {
  return integrate_mesh(ode, mesh, Y, method, trajectory);
}

const char* to_string(IntegratorMethod method) {
  return method == IntegratorMethod::RK4 ? "rk4" : "dormand_prince";
}

IntegrationReport integrate_rod(const RodOde& ode, double s0, double s1, RodStateVector& y,
                                const IntegratorOptions& options, RodTrajectory* trajectory) {
  return integrate(ode, s0, s1, y, options, trajectory);
}

IntegrationReport integrate_rod(const RodOde& ode, double s0, double s1, RodStateWithTangents& Y,
                                const IntegratorOptions& options, RodTrajectory* trajectory) {
  return integrate(ode, s0, s1, Y, options, trajectory);
}

RodStateVector rod_single_step(const RodOde& ode, double s0, double h, const RodStateVector& y,
                               IntegratorMethod method) {
  RodStateVector x = y, k1, k2, k3, k4, k5, k6, k7, tmp, y_new;
  if (method == IntegratorMethod::RK4) {
    rk4_step(ode, s0, h, x, k1, k2, k3, k4, tmp);
    normalise(x);
    return x;
  }
  ode.derivative(s0, x, k1);
  DormandPrinceStages::step(ode, s0, h, x, k1, k2, k3, k4, k5, k6, k7, tmp, y_new, false);
  normalise(y_new);
  return y_new;
}

}  // namespace pcr
