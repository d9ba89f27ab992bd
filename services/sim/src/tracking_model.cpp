#include "mmh/sim/tracking_model.hpp"

#include <algorithm>
#include <cmath>

namespace mmh::sim {

KinematicState referenceAt(const SetpointSample& setpoint, int64_t utime,
                           const TrackingParams& params) {
  const double late_s = std::max(0.0, static_cast<double>(utime - setpoint.utime) * 1e-6);
  const double t = std::min(late_s, params.setpoint_timeout_s);
  const KinematicState& s = setpoint.state;
  KinematicState r;
  r.position = s.position + s.velocity * t + s.acceleration * (t * t / 2.0) +
               setpoint.jerk * (t * t * t / 6.0);
  if (late_s > params.setpoint_timeout_s) return r;  // the stream stopped: hold there
  r.velocity = s.velocity + s.acceleration * t + setpoint.jerk * (t * t / 2.0);
  r.acceleration = s.acceleration + setpoint.jerk * t;
  return r;
}

KinematicState trackingStep(const KinematicState& vehicle, const KinematicState& reference,
                            double dt, const TrackingParams& params) {
  const double w = 2.0 * M_PI * params.bandwidth_hz;
  Eigen::Vector3d a = reference.acceleration + w * w * (reference.position - vehicle.position) +
                      2.0 * params.damping_ratio * w * (reference.velocity - vehicle.velocity);
  const double norm = a.norm();
  if (norm > params.max_acc_mps2) a *= params.max_acc_mps2 / norm;
  KinematicState next;
  next.position = vehicle.position + vehicle.velocity * dt + a * (dt * dt / 2.0);
  next.velocity = vehicle.velocity + a * dt;
  next.acceleration = a;
  return next;
}

}  // namespace mmh::sim
