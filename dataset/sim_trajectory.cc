#include "dataset/sim_trajectory.h"

#include <cmath>
#include <stdexcept>

namespace vio {
namespace {

// Frequencies of the attitude oscillations relative to the lap frequency.
constexpr double kRollRate = 1.7;
constexpr double kPitchRate = 2.3;
constexpr double kYawRate = 1.3;

// tau = s(t) and its first two derivatives.
struct TimeWarp {
  double s, ds, dds;
};

TimeWarp Warp(const SimMotionOptions& o, double t) {
  const double t_moving = t - o.still_duration_s;
  const double tb = o.blend_duration_s;
  if (tb <= 0.0) return {t_moving, 1.0, 0.0};
  if (t_moving <= 0.0) return {0.0, 0.0, 0.0};
  if (t_moving >= tb) return {0.5 * tb + (t_moving - tb), 1.0, 0.0};
  // s' = 3x^2 - 2x^3 (x = t_moving / tb) integrates to s = tb (x^3 - x^4/2);
  // s'' = (6x - 6x^2) / tb.
  const double x = t_moving / tb;
  return {tb * (x * x * x - 0.5 * x * x * x * x), 3.0 * x * x - 2.0 * x * x * x,
          (6.0 * x - 6.0 * x * x) / tb};
}

// Rotation about one axis by `angle` [rad].
Eigen::Matrix3d AxisRotation(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

constexpr struct {
  SimShape shape;
  const char* name;
} kShapeNames[] = {{SimShape::kEllipse, "ellipse"},
                   {SimShape::kRotation, "rotation"},
                   {SimShape::kLine, "line"},
                   {SimShape::kCircle, "circle"}};

}  // namespace

const char* SimShapeName(SimShape shape) {
  for (const auto& n : kShapeNames) {
    if (n.shape == shape) return n.name;
  }
  return "?";
}

bool ParseSimShape(const std::string& name, SimShape* shape) {
  for (const auto& n : kShapeNames) {
    if (name == n.name) {
      *shape = n.shape;
      return true;
    }
  }
  return false;
}

bool SimMotionOptions::Validate(std::string* message) const {
  const struct {
    const char* name;
    double value;
  } non_negative[] = {{"still_duration_s", still_duration_s},
                      {"blend_duration_s", blend_duration_s},
                      {"radius_x_m", radius_x_m},
                      {"radius_y_m", radius_y_m},
                      {"height_m", height_m},
                      {"height_amplitude_m", height_amplitude_m},
                      {"roll_amplitude_rad", roll_amplitude_rad},
                      {"pitch_amplitude_rad", pitch_amplitude_rad},
                      {"yaw_amplitude_rad", yaw_amplitude_rad},
                      {"start_phase_s", start_phase_s}};
  for (const auto& f : non_negative) {
    if (!(std::isfinite(f.value) && f.value >= 0.0)) {
      *message = std::string(f.name) + " must be >= 0 (got " +
                 std::to_string(f.value) + ")";
      return false;
    }
  }
  if (!(std::isfinite(lap_period_s) && lap_period_s > 0.0)) {
    *message =
        "lap_period_s must be > 0 (got " + std::to_string(lap_period_s) + ")";
    return false;
  }
  if (!(std::isfinite(attitude_rate_factor) && attitude_rate_factor > 0.0)) {
    *message = "attitude_rate_factor must be > 0 (got " +
               std::to_string(attitude_rate_factor) + ")";
    return false;
  }
  if (roll_amplitude_rad >= 1.0 || pitch_amplitude_rad >= 1.0) {
    *message = "roll_amplitude_rad and pitch_amplitude_rad must be < 1";
    return false;
  }
  if (still_duration_s > 0.0 && blend_duration_s <= 0.0) {
    *message = "blend_duration_s must be > 0 after a still start";
    return false;
  }
  return true;
}

SimTrajectory::SimTrajectory(const SimMotionOptions& options)
    : options_(options), w_(2.0 * M_PI / options.lap_period_s) {
  std::string message;
  if (!options_.Validate(&message)) {
    throw std::invalid_argument("SimMotionOptions: " + message);
  }
}

void SimTrajectory::Path(double tau, Eigen::Vector3d* P, Eigen::Vector3d* dP,
                         Eigen::Vector3d* ddP) const {
  const SimMotionOptions& o = options_;
  const double c = std::cos(w_ * tau), s = std::sin(w_ * tau);
  switch (o.shape) {
    case SimShape::kRotation:
      tau = o.start_phase_s;
      [[fallthrough]];
    case SimShape::kEllipse: {
      const double cr = std::cos(w_ * tau), sr = std::sin(w_ * tau);
      const double c2 = std::cos(2.0 * w_ * tau), s2 = std::sin(2.0 * w_ * tau);
      const double h = o.height_amplitude_m;
      *P = Eigen::Vector3d(o.radius_x_m * cr, o.radius_y_m * sr,
                           o.height_m + h * s2);
      *dP = Eigen::Vector3d(-o.radius_x_m * w_ * sr, o.radius_y_m * w_ * cr,
                            2.0 * w_ * h * c2);
      *ddP = Eigen::Vector3d(-o.radius_x_m * w_ * w_ * cr,
                             -o.radius_y_m * w_ * w_ * sr,
                             -4.0 * w_ * w_ * h * s2);
      if (o.shape == SimShape::kRotation) {
        dP->setZero();
        ddP->setZero();
      }
      return;
    }
    case SimShape::kLine: {
      const double speed = 2.0 * o.radius_x_m / o.lap_period_s;
      *P = Eigen::Vector3d(-o.radius_x_m + speed * tau, 0.0, o.height_m);
      *dP = Eigen::Vector3d(speed, 0.0, 0.0);
      *ddP = Eigen::Vector3d::Zero();
      return;
    }
    case SimShape::kCircle: {
      const double r = o.radius_y_m;
      *P = Eigen::Vector3d(r * c, r * s, o.height_m);
      *dP = Eigen::Vector3d(-r * w_ * s, r * w_ * c, 0.0);
      *ddP = Eigen::Vector3d(-r * w_ * w_ * c, -r * w_ * w_ * s, 0.0);
      return;
    }
  }
}

void SimTrajectory::Attitude(double tau, double ds, Eigen::Matrix3d* R_w_v,
                             Eigen::Vector3d* w_v) const {
  const SimMotionOptions& o = options_;
  // Euler angles and their rates (d/dt = d/dtau * s').
  double roll = 0.0, pitch = 0.0, yaw = 0.0;
  double droll = 0.0, dpitch = 0.0, dyaw = 0.0;
  if (o.shape == SimShape::kEllipse || o.shape == SimShape::kRotation) {
    const double f = o.attitude_rate_factor * w_;
    roll = o.roll_amplitude_rad * std::sin(kRollRate * f * tau);
    pitch = o.pitch_amplitude_rad * std::sin(kPitchRate * f * tau);
    yaw = w_ * tau + 0.5 * M_PI +
          o.yaw_amplitude_rad * std::sin(kYawRate * f * tau);
    droll = o.roll_amplitude_rad * kRollRate * f *
            std::cos(kRollRate * f * tau) * ds;
    dpitch = o.pitch_amplitude_rad * kPitchRate * f *
             std::cos(kPitchRate * f * tau) * ds;
    dyaw = (w_ +
            o.yaw_amplitude_rad * kYawRate * f * std::cos(kYawRate * f * tau)) *
           ds;
  } else if (o.shape == SimShape::kCircle) {
    yaw = w_ * tau + 0.5 * M_PI;  // heading along the path
    dyaw = w_ * ds;
  }
  // R_w_v = Rz(yaw) Ry(pitch) Rx(roll); its body rate in V is the standard
  // Z-Y-X kinematics: w_v = (droll - dyaw sin(pitch),
  //   dpitch cos(roll) + dyaw cos(pitch) sin(roll),
  //   -dpitch sin(roll) + dyaw cos(pitch) cos(roll)).
  *R_w_v = AxisRotation(Eigen::Vector3d::UnitZ(), yaw) *
           AxisRotation(Eigen::Vector3d::UnitY(), pitch) *
           AxisRotation(Eigen::Vector3d::UnitX(), roll);
  const double sr = std::sin(roll), cr = std::cos(roll);
  const double sp = std::sin(pitch), cp = std::cos(pitch);
  *w_v = Eigen::Vector3d(droll - dyaw * sp, dpitch * cr + dyaw * cp * sr,
                         -dpitch * sr + dyaw * cp * cr);
}

SimState SimTrajectory::At(double t) const {
  const TimeWarp tw = Warp(options_, t);
  const double tau = options_.start_phase_s + tw.s;
  // Path P(tau) and its tau-derivatives; then the chain rule through s(t):
  // v = P' s',  a = P'' s'^2 + P' s''.
  Eigen::Vector3d P, dP, ddP;
  Path(tau, &P, &dP, &ddP);
  SimState state;
  state.p_w_b = P;
  state.v_w = dP * tw.ds;
  state.a_w = ddP * tw.ds * tw.ds + dP * tw.dds;
  Eigen::Matrix3d R_w_v;
  Eigen::Vector3d w_v;
  Attitude(tau, tw.ds, &R_w_v, &w_v);
  Eigen::Matrix3d R_v_b;
  R_v_b << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  state.q_w_b = Eigen::Quaterniond(R_w_v * R_v_b).normalized();
  state.w_b = R_v_b.transpose() * w_v;
  return state;
}

}  // namespace vio
