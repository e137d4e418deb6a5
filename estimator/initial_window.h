#ifndef VIO_ESTIMATOR_INITIAL_WINDOW_H_
#define VIO_ESTIMATOR_INITIAL_WINDOW_H_

// What an initialiser hands the estimator: the states of the frames it used
// (they become the first window) in a gravity-aligned world, and the
// landmarks it triangulated, all metric. Also the frames the in-motion
// initialisers take as input.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <vector>

#include "estimator/initialization_options.h"
#include "geometry/feature_observation.h"

namespace vio {

// A frame as the initialisers keep it until a start succeeds.
struct BufferedFrame {
  int64_t t_ns = 0;                              // camera stamp [ns]
  int64_t t_imu_ns = 0;                          // t_ns + t_d [ns]
  std::vector<FeatureObservation> observations;  // xy, velocity set
};

struct InitialFrame {
  int64_t t_ns = 0;                                 // camera stamp [ns]
  int64_t t_imu_ns = 0;                             // [ns]
  Eigen::Vector3d p_w_b = Eigen::Vector3d::Zero();  // [m]
  Eigen::Quaterniond q_w_b = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_w = Eigen::Vector3d::Zero();  // [m/s]
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero();  // [rad/s]
  std::vector<FeatureObservation> observations;
};

// Figures of the start, for the summary and the benchmarks.
struct InitDiagnostics {
  double parallax_px = 0.0;          // mono: reference pair, compensated
  int inliers = 0;                   // mono: essential matrix; stereo: points
  double reprojection_rms_px = 0.0;  // mono: after its bundle adjustment
  double scale = 0.0;                // mono: metres per visual unit
  double scale_uncertainty = 0.0;    // mono: relative std of the scale
  double gravity_error = 0.0;        // | |g_free| - g | [m/s^2]
  double imu_excitation = 0.0;       // std of dv / T [m/s^2]
  // Of the joint adjustment: its change of the window's path length [-];
  // meaningful only where ScaleChangeDefined says so.
  double refine_scale_change = 0.0;
  double refined_path_m = 0.0;  // the adjusted window's path length [m]
  // stereo: sightings (landmarks counted once) its outlier rounds removed.
  int refine_outliers_removed = 0;
  // stereo: of those, the ones removed before its first solve (at the
  // alignment's state, refine_prescreen_threshold_px).
  int refine_prescreen_removed = 0;
  // mono: sightings the structure from motion's outlier rounds removed.
  int sfm_outliers_removed = 0;
  // Relative std of the adjusted window's scale, from the joint
  // adjustment's covariance (estimator/scale_uncertainty.h); < 0: unknown.
  double refined_scale_sigma = -1.0;
  // mono: from the long window (init.mono.long_window_s), whose start waits
  // for max_refined_scale_uncertainty; false: the fallback window.
  bool long_window = false;
  // gyro-aided: its costly fit on the reprojection errors ran (false when
  // a cheaper check refused the attempt first).
  bool full_fit = false;
  // The initialiser's biases at the newest frame, before the joint
  // adjustment (what it handed on) [m/s^2, rad/s].
  Eigen::Vector3d initial_b_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d initial_b_g = Eigen::Vector3d::Zero();
};

struct InitialWindow {
  InitMethod method = InitMethod::kStatic;
  std::vector<InitialFrame> frames;  // oldest first; the newest started
  // Triangulated landmarks in the world, by feature id [m].
  std::map<int64_t, Eigen::Vector3d> points_w;
  InitDiagnostics diagnostics;
};

// An accepted start, for the summary: the first window's states right after
// the joint adjustment (observations left out).
struct StartRecord {
  int64_t t_ns = 0;  // the frame it happened at [ns]
  InitMethod method = InitMethod::kStatic;
  bool restart = false;  // a re-initialisation after a failure reset
  InitDiagnostics diagnostics;
  std::vector<InitialFrame> window;
};

// Whether InitDiagnostics::refine_scale_change means anything: not when the
// adjusted window's path is shorter than kMinScalePathM, nor when its spread
// (the scale's measure, estimator/scale_uncertainty.h) is not known to
// within kMaxDefinedScaleSigma of itself or not at all (refined_scale_sigma
// < 0). A window at rest has a path made of position noise, which the
// adjustment shrinks: the simulated still stereo start's 134 mm of path
// became 14 mm ("moved the scale -89 %"), EuRoC V1_01's still start's
// 1.2 mm became 0.9 mm ("-26 %"). Neither the covariance nor the zero-
// velocity detector tells that rest alone: the spread is a norm, positive on
// noise (5.6 of its sigmas in the simulated still start, while the mono
// starts in motion claim 8 to 40 %), and the detector has no verdict before
// its 0.5 s of IMU (the stereo start comes at 0.45 s). 2 cm is several times
// the stereo positions' millimetres of noise and under any start in motion
// (0.45 s at the slowest preset's 0.1 m/s: 4.5 cm).
constexpr double kMinScalePathM = 0.02;        // [m]
constexpr double kMaxDefinedScaleSigma = 0.5;  // relative std [-]
bool ScaleChangeDefined(const InitDiagnostics& diagnostics);

// Moves the window rigidly about the world z axis and along it so that its
// newest frame gets position p_w_b and the yaw `yaw_rad` (Yaw(): the heading
// of the body x axis). This fixes the 4-DoF gauge of visual-inertial
// odometry at a first start. Velocities and points follow; roll, pitch,
// biases are unchanged.
void SetGauge(const Eigen::Vector3d& p_w_b, double yaw_rad,
              InitialWindow* window);

// The same move for a re-start, which keeps the running gauge: the newest
// frame gets position p_w_b and, of the attitudes a rotation about world z
// can give it, the one closest to q_w_b (YawBetween).
void SetGauge(const Eigen::Vector3d& p_w_b, const Eigen::Quaterniond& q_w_b,
              InitialWindow* window);

// The angle [rad] of the rotation about world z that brings R_from closest
// to R_to over all three body axes: argmin_theta |Rz(theta) R_from - R_to|_F.
// A difference of Yaw()s is not that when the body x axis points nearly up
// (EuRoC's IMU x does): its heading is then ill-defined, and a tilt
// difference of a degree turns into tens of degrees of yaw.
double YawBetween(const Eigen::Matrix3d& R_from, const Eigen::Matrix3d& R_to);

}  // namespace vio

#endif  // VIO_ESTIMATOR_INITIAL_WINDOW_H_
