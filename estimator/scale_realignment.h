#ifndef VIO_ESTIMATOR_SCALE_REALIGNMENT_H_
#define VIO_ESTIMATOR_SCALE_REALIGNMENT_H_

// A second look at the scale some seconds after a monocular start in motion
// (the idea of ORB-SLAM3's repeated inertial-only scale refinement after its
// initialisation: Campos et al., T-RO 2021, sec. V-B; here the start's own
// machinery over a longer span). The start took its scale from ~2 s of
// motion, which determines it to ~18 % (docs/initialisation.md); the running
// window then converges to the right one over 4-8 s, held back by the
// marginalised prior linearised at the start's scale. So the frames and IMU
// since the start are kept, and once `realign_after_s` have passed the
// monocular start (structure from motion and the linear visual-inertial
// alignment, estimator/mono_initializer.h) runs again over the last
// `realign_window_s`, and its frames are adjusted jointly with the IMU as a
// start's are (Estimator::AdjustSpan). When that adjustment determines the
// span's scale well (relative std at most `realign_max_scale_uncertainty`,
// estimator/scale_uncertainty.h) the running window's positions, compared
// with the span's over the frames both hold, give the factor by which the
// window's scale is off; the estimator applies it, with the span's tilt and
// accelerometer bias, to the window and its prior (window_rescale.h).
// Measured in docs/initialisation.md (off by default: it helps the worst
// motion_mono runs and hurts the hand-held ones).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/initial_window.h"
#include "estimator/mono_initializer.h"
#include "estimator/window.h"
#include "preintegration/imu_types.h"

namespace vio {

// The outcome of one try.
struct RealignmentResult {
  bool done = false;   // a scale was found (its figures below)
  double scale = 1.0;  // the factor the window's scale is to be multiplied by
  double scale_sigma = 0.0;  // relative std of the new span's scale [-]
  int common_frames = 0;     // frames of the new span inside the window
};

// For the summary: one realignment that found a scale.
struct RealignmentRecord {
  int64_t t_ns = 0;  // the frame it happened at [ns]
  RealignmentResult result;
  bool applied = false;  // |scale - 1| reached realign_min_change
};

// The RMS distance of positions from their centroid (0 for none): the
// spread a scale is compared by, blind to position and yaw.
double PositionSpread(const std::vector<Eigen::Vector3d>& p);

// The spread (PositionSpread; its uncertainty: estimator/scale_uncertainty.h)
// of `reference`'s positions over its frames within the window's time span,
// divided by that of the window's positions interpolated linearly in time at
// the same stamps (t_imu_ns). 0 when fewer than `min_frames` such frames or
// a spread is not positive. It ignores the gauge (position, yaw) the two
// trajectories differ by.
double SpreadRatio(const std::vector<InitialFrame>& reference,
                   const Window& window, int min_frames, int* common);

class ScaleRealignment {
 public:
  ScaleRealignment(const EstimatorOptions& options,
                   const Eigen::Isometry3d& T_b_c, double focal_px,
                   const ImuNoise& noise,
                   const PreintegrationOptions& preintegration);

  // Off, or not after a start in motion: nothing is kept.
  bool active() const { return active_; }
  // Begins after a monocular (or gyroscope-aided) start at t_ns whose window
  // is `start` (its frames' observations are kept as the span's first).
  void Begin(const std::vector<BufferedFrame>& start_frames, int64_t t_ns);
  void Stop();
  void AddImu(const ImuSample& sample);
  void AddFrame(const FeatureFrame& frame, int64_t t_imu_ns);
  // When due (after realign_after_s, every few frames until
  // realign_after_s + realign_window_s, then given up): the monocular start
  // over the span; true when it succeeded with its scale's relative std at
  // most realign_max_scale_uncertainty.
  bool TrySpan(int64_t t_ns, InitialWindow* span);
  // The span (after its joint adjustment) against the running window: the
  // factor by which the window's scale is off (SpreadRatio); stops after a
  // factor is found. False when they share too few frames.
  bool Compare(const InitialWindow& span, const Window& window,
               RealignmentResult* r);
  // The IMU kept for the span [oldest first].
  const std::vector<ImuSample>& imu() const { return imu_; }

 private:
  MonoInitOptions options_;
  std::unique_ptr<MonoInitializer> mono_;
  bool active_ = false;
  int64_t start_ns_ = 0;
  int frames_since_try_ = 0;
  std::vector<BufferedFrame> frames_;
  std::vector<ImuSample> imu_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_SCALE_REALIGNMENT_H_
