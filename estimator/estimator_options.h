#ifndef VIO_ESTIMATOR_ESTIMATOR_OPTIONS_H_
#define VIO_ESTIMATOR_ESTIMATOR_OPTIONS_H_

// The options of the sliding-window estimator: plain structs with in-class
// defaults, a unit on every field and a Validate() that can be tested without
// YAML (config/estimator_config maps the `estimator:` block onto them).
//
// Pixel thresholds are converted to the normalised image plane by the focal
// length [px] the estimator is given with the cameras: x [-] = px / focal.

#include <ceres/types.h>

#include <string>

#include "estimator/imu_noise_adaptation.h"
#include "estimator/initialization_options.h"
#include "preintegration/imu_glitch_filter.h"

namespace vio {

// When a new frame becomes a keyframe (the newest frame against the last
// keyframe, over the features seen in both).
struct KeyframeOptions {
  double min_parallax_px = 20.0;  // median parallax making a keyframe [px]
  int min_tracked_features = 50;  // fewer tracked features: keyframe [-]
};

// When a landmark may enter the problem.
struct TriangulationOptions {
  // Largest angle between two of its viewing rays, at least [deg]. A stereo
  // pair with a 0.11 m baseline sees 1 deg at about 6 m.
  double min_parallax_deg = 0.5;
  double min_depth_m = 0.1;   // in every observing camera, at least [m]
  double max_depth_m = 40.0;  // in the anchor camera, at most [m]
  int min_observations = 2;   // sightings (frames x cameras) needed [-]
};

// Which landmarks enter the problem and which leave it after the solve. (The
// pixel noise and the robust kernel are the visual factors' own options,
// factors/visual_factor_options.h.)
// The landmarks anchored in the keyframe that leaves the window
// (docs/recorded_flights.md, "Consistency").
enum class ReanchoredTracks {
  // All their factors go into the prior and their inverse depths are
  // eliminated; re-anchored on their next sighting (depth carried over),
  // every remaining sighting enters the problem again, although it already
  // shaped the prior (VINS-Mono's way): a sighting is folded into the prior
  // about five times.
  kReuse,
  // A track still alive becomes a point in the world (3 coordinates) that the
  // prior keeps: only the leaving frame's sightings are folded (each sighting
  // once, the anchor's with a residual of its own), its other sightings stay
  // in the problem as world-point factors, and the point is marginalised out
  // of the prior when its track ends or it is removed
  // (factors/world_point_factor.h; with estimate_time_offset,
  // factors/timed_world_point_factor.h).
  kKeepPoint,
  // keep_point with the world-point factors' Jacobians taken at the point's
  // first estimate (where the prior first held it).
  kKeepPointFirstEstimate,
};
const char* ReanchoredTracksName(ReanchoredTracks r);
// false when name is none of reuse, keep_point, keep_point_fej.
bool ParseReanchoredTracks(const std::string& name, ReanchoredTracks* r);

struct LandmarkOptions {
  // After the solve, a sighting whose reprojection error exceeds this is
  // removed; a landmark with most of its sightings beyond it is removed
  // whole [px]. With 1 px feature noise a good sighting passes 5 px almost
  // surely; a tracker slip lands far beyond it.
  double outlier_threshold_px = 5.0;
  // Landmarks per step at most, those with the most sightings first [-].
  int max_landmarks = 120;
  // What happens to the landmarks anchored in a keyframe that is
  // marginalised. keep_point_fej by default (config/default.yaml): reuse
  // counts a sighting once per keyframe its track spans and is overconfident
  // (NEES 3.72 per dimension on sim_default against 1.13;
  // docs/recorded_flights.md, "The mono configurations switched").
  ReanchoredTracks reanchored_tracks =
      ReanchoredTracks::kKeepPointFirstEstimate;
  // keep_point: whether the world points take places of max_landmarks.
  // They are always in the problem (the prior holds them), so when they
  // count, long old tracks crowd out new landmarks (with stereo's 60, most
  // places); false puts them on top of max_landmarks inverse-depth
  // landmarks (docs/recorded_flights.md, "A keep_point variant").
  bool world_points_in_max_landmarks = false;
  // keep_point: at most this many world points stay after a
  // marginalisation (0: no bound). The excess, those whose last sighting is
  // oldest first (the points that would leave the window soonest: tracks the
  // tracker lost before tracks still seen), are marginalised with every
  // sighting they have in the window and forgotten; a track still seen goes
  // on as a new landmark. Each sighting still enters the prior once; what is
  // bounded is the dense part of the solver's system and of the prior
  // (docs/recorded_flights.md, "A bound on the world points").
  int max_world_points = 50;
  // keep_point*: for this many seconds after a start in motion (any start
  // but the static one) the leaving keyframe's landmarks are handled as
  // reuse, keep_point after it (0: keep_point from the start). A start in
  // motion's scale and biases are still being corrected then; a world point
  // made in that time is held by the prior where the wrong scale put it
  // (docs/recorded_flights.md, "Starts in motion and keep_point").
  double reuse_after_moving_start_s = 4.0;
};

// Static start: the IMU tells when the vehicle stands still.
struct StaticInitOptions {
  double window_s = 1.0;  // IMU span averaged [s]
  // Stillness: per-axis standard deviation of the means of blocks of block_s
  // over the span, at most [m/s^2] / [rad/s]. Block means ignore rotor
  // vibration: EuRoC V1_01 standing gives <= 0.10 m/s^2 and 0.006 rad/s,
  // flying 0.1-1.1 m/s^2 and 0.07-0.13 rad/s (0.1 s blocks over 1 s).
  double block_s = 0.1;
  double max_acc_std = 0.15;
  double max_gyr_std = 0.02;
  // The part of the mean specific force along gravity beyond g becomes the
  // accelerometer bias; otherwise the bias starts at zero.
  bool estimate_accel_bias = false;
};

// The prior that fixes the gauge (position, yaw) and the first speed-bias
// estimate of a window that starts afresh: after the static initialisation,
// after a reset, or when a marginalisation fails. Standard deviations.
struct StatePriorOptions {
  double position_m = 1e-3;      // [m]
  double yaw_rad = 1e-3;         // about world z [rad]
  double tilt_rad = 0.02;        // roll and pitch [rad]
  double velocity_still = 0.02;  // after the static start [m/s]
  double velocity_moving = 0.3;  // after a reset or failure [m/s]
  double accel_bias = 0.2;       // [m/s^2]
  double gyro_bias = 0.005;      // [rad/s]
  // The camera extrinsic's calibration, when it is estimated: without a
  // prior its translation is unobservable until the body rotates, and it
  // wanders during the still start (docs/estimator.md, "Online calibration").
  double extrinsic_rotation_rad = 0.02;   // about the camera axes [rad]
  double extrinsic_translation_m = 0.01;  // [m]
};

// When the estimator gives up and starts again.
struct FailureOptions {
  int min_tracked_landmarks = 8;        // landmarks in the problem [-]
  double max_accel_bias = 2.0;          // |b_a| [m/s^2]
  double max_gyro_bias = 0.5;           // |b_g| [rad/s]
  double max_position_jump_m = 1.0;     // newest position, step to step [m]
  double max_rotation_jump_deg = 30.0;  // newest attitude, step to step [deg]
  // |v| of any window state, checked before every solve (an exploding
  // prediction never reaches Ceres) and after it [m/s].
  double max_speed_m_s = 50.0;
};

// The IMU stream as the configuration's imu: block describes it; the tools
// copy it from there (config/imu_config.h, ApplyImuConfig), as they copy
// gravity_magnitude.
struct ImuStreamOptions {
  // Nominal sample rate [Hz]: a step longer than 1.5 periods (and up to the
  // preintegration's max_sample_gap) is a short gap, integrated across and
  // counted.
  double rate_hz = 200.0;
  // A sample outside the measuring range is a glitch: replaced from its
  // neighbours and counted (preintegration/imu_glitch_filter.h).
  ImuRange range;
  // The white-noise densities scaled online from the window's IMU residuals
  // (estimator/imu_noise_adaptation.h; the imu: block's adapt_noise).
  ImuNoiseAdaptationOptions noise_adaptation;
};

// Which code minimises each step's problem.
enum class SolverBackend {
  // tcvio's own solver of the window's structure (estimator/window_solver.h):
  // inverse depths eliminated in closed form, one dense reduced system.
  kWindow,
  // ceres::Solve with linear_solver (the same factors, manifolds, losses).
  kCeres,
};

// Options of the per-step solve.
struct SolverOptions {
  SolverBackend backend = SolverBackend::kWindow;
  // Ceres' linear solver; used by the kCeres backend only.
  ceres::LinearSolverType linear_solver = ceres::DENSE_SCHUR;
  // DOGLEG or LEVENBERG_MARQUARDT, with Ceres' meaning in both backends.
  ceres::TrustRegionStrategyType trust_region = ceres::DOGLEG;
  int max_iterations = 4;  // [-]
  // A step ends when an accepted iteration changes the cost by less than
  // this fraction of it [-]. Ceres' default is 1e-6; in a window that is
  // solved again 20 times a second, iterations that move the cost by less
  // than 0.1 % (far below its statistical spread) change the trajectory by
  // nothing measurable (docs/speed.md) and cost a quarter of the time.
  double function_tolerance = 1e-3;
  // Wall-clock budget per step [s]; 0: none, the iteration limit alone ends
  // a step. A budget makes the trajectory depend on the machine's load (a
  // busy machine cuts steps short), so offline replays leave it at 0 and
  // only a real-time system that must keep up should set one.
  double max_time_s = 0.0;
  // 1 makes every run bit-for-bit repeatable (Ceres sums Jacobian blocks in a
  // thread-dependent order with more threads).
  int num_threads = 1;
  // Window backend: true solves every linearisation of a step after the
  // first by conjugate gradients preconditioned with the step's last
  // Cholesky factor (a fresh factor when they do not converge in 8
  // iterations): the same steps to a relative residual of 1e-6 at a
  // fraction of the factor's cost where the reduced system is wide (world
  // points; docs/speed.md). false: a factor per linearisation.
  bool kept_factor_pcg = true;
};

struct EstimatorOptions {
  int window_size = 10;             // keyframes in the window [-]
  double gravity_magnitude = 9.81;  // [m/s^2]
  ImuStreamOptions imu_stream;
  bool estimate_extrinsics = false;
  // Camera-IMU time offset t_d, t_imu = t_cam + t_d [s]: frame poses sit at
  // t_cam + t_d. Estimated online (camera-0 factors, image velocity predicted
  // from the state) when asked, within +-0.02 s (docs/estimator.md, Online
  // calibration).
  bool estimate_time_offset = false;
  double initial_time_offset_s = 0.0;
  // Stereo: use camera 1 too (the sequence must have it).
  bool use_stereo = false;
  KeyframeOptions keyframe;
  TriangulationOptions triangulation;
  LandmarkOptions landmarks;
  StaticInitOptions static_init;
  StatePriorOptions state_prior;
  FailureOptions failure;
  SolverOptions solver;
  InitOptions init;                   // how the estimator starts
  ZeroVelocityOptions zero_velocity;  // holding still when still

  // True when every field is in range; otherwise false with a message that
  // starts with the offending field's name ("window_size must be >= 2 ...").
  bool Validate(std::string* message) const;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_ESTIMATOR_OPTIONS_H_
