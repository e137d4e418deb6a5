#ifndef VIO_DATASET_TRAJECTORY_CURVE_H_
#define VIO_DATASET_TRAJECTORY_CURVE_H_

// A smooth curve through a recorded trajectory (EuRoC ground truth, a TUM
// file): the uniform cubic B-spline of geometry/pose_spline.h fitted by least
// squares to the stamped poses, so that its analytic derivatives give a
// consistent IMU (the simulator's TrajectorySource for a recorded flight).
//
// The fit minimises, over the control points,
//   sum_k |p(t_k) - p_k|^2 / sp^2 + sum_k |Log(R_k^T R(t_k))|^2 / sr^2
//   + sum_i |c_{i+1} - 2 c_i + c_{i-1}|^2 / (sa dt^2)^2
//   + sum_i |d_{i+1} - d_i|^2 / (sw dt^2)^2,     d_i = Log(R_i^T R_{i+1}),
// with sp, sr the ground truth's noise and sa, sw weak priors on the
// acceleration and angular acceleration that only matter where samples are
// sparse (gaps, the curve's ends). Positions are linear in the control points
// (one sparse solve); rotations are solved by Gauss-Newton from control
// rotations interpolated (slerp) from the samples. Eigen only (sparse LDLT).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dataset/trajectory.h"
#include "dataset/trajectory_source.h"
#include "geometry/pose_spline.h"

namespace vio {

struct CurveFitOptions {
  // Knot spacing [s]: the curve cannot follow motion faster than about
  // 1 / (2 knot_spacing_s) Hz. 0.05 s keeps a MAV's manoeuvres (EuRoC's
  // ground truth has no content above a few Hz).
  double knot_spacing_s = 0.05;
  // Knot spacing of the rotations [s]; 0: knot_spacing_s. The rotations and
  // the positions are fitted apart (two splines evaluated together), so the
  // attitude can follow faster motion than the positions: a ground truth
  // whose attitude has content the gyroscope felt (EuRoC MH's, estimated
  // with the IMU) and whose positions are noisy beyond a few Hz (twice
  // differentiated, position noise becomes acceleration error).
  double rotation_knot_spacing_s = 0.0;
  double position_sigma_m = 1e-3;    // ground-truth position noise [m]
  double rotation_sigma_rad = 1e-3;  // ground-truth attitude noise [rad]
  double acceleration_sigma = 50.0;  // smoothness prior [m/s^2]
  double angular_acceleration_sigma = 50.0;  // smoothness prior [rad/s^2]
  int max_iterations = 20;  // Gauss-Newton on the rotations [-]

  // True when every value is finite and > 0 (rotation_knot_spacing_s >= 0,
  // max_iterations >= 1); otherwise false with a message naming the field.
  bool Validate(std::string* message) const;
};

// How well the curve passes through the samples it was fitted to.
struct CurveFitReport {
  int samples = 0;
  int control_points = 0;
  int iterations = 0;           // Gauss-Newton steps taken
  double position_rms_m = 0.0;  // |p(t_k) - p_k| [m]
  double position_max_m = 0.0;
  double rotation_rms_rad = 0.0;  // |Log(R_k^T R(t_k))| [rad]
  double rotation_max_rad = 0.0;
};

class TrajectoryCurve : public TrajectorySource {
 public:
  // poses: strictly increasing stamps, at least 2, spanning at least one
  // knot spacing; options valid. Throws std::invalid_argument otherwise.
  TrajectoryCurve(const std::vector<StampedPose>& poses,
                  const CurveFitOptions& options);
  // A curve fitted elsewhere (dataset/imu_curve_fit.h): `spline` starts at
  // t = 0 (start_ns) and spans at least end_ns - start_ns.
  TrajectoryCurve(int64_t start_ns, int64_t end_ns, PoseSpline spline,
                  const CurveFitReport& report);

  // The state at t seconds after start_ns(), t in [0, duration_s()]; throws
  // std::out_of_range outside.
  SimState At(double t) const override;

  int64_t start_ns() const { return start_ns_; }  // the first sample's stamp
  int64_t end_ns() const { return end_ns_; }      // the last sample's stamp
  double duration_s() const {
    return static_cast<double>(end_ns_ - start_ns_) * 1e-9;
  }
  const CurveFitReport& report() const { return report_; }
  // The positions' spline (and the rotations', unless rotation_spline() is
  // set).
  const PoseSpline& spline() const { return spline_; }
  // The rotations' spline when their knot spacing differs, else null.
  const PoseSpline* rotation_spline() const {
    return rotation_spline_.has_value() ? &*rotation_spline_ : nullptr;
  }

 private:
  int64_t start_ns_;
  int64_t end_ns_;
  CurveFitReport report_;  // before spline_: the fit fills it
  PoseSpline spline_;
  std::optional<PoseSpline> rotation_spline_;
};

}  // namespace vio

#endif  // VIO_DATASET_TRAJECTORY_CURVE_H_
