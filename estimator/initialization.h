#ifndef VIO_ESTIMATOR_INITIALIZATION_H_
#define VIO_ESTIMATOR_INITIALIZATION_H_

// The choice of start (init.method):
//   static  the static start (static_initializer.h) once the IMU has been
//           still for static_init.window_s and the features do not move
//           (zero_velocity.h's image test; without features, the IMU alone);
//   mono    the monocular start in motion (mono_initializer.h);
//   stereo  the stereo start in motion (stereo_initializer.h);
//   auto    at every frame the static start first (exact at rest, where the
//           in-motion starts cannot work), then the in-motion one of the
//           configuration (stereo with use_stereo, else mono): whichever is
//           ready first and passes its checks.
// With init.mono.gyro_aided, a failed mono attempt is followed at the same
// frame by the gyroscope-aided one (gyro_aided_initializer.h), except for
// kGyroAidedRetryAfterNoParallaxS after it refused a window for showing no
// translation at its cheap precheck (the frames then are mostly the same),
// twice that after a second such refusal in a row, and so on up to
// init.mono.window_s.
// Every failed attempt is appended to the log as data (init_attempt.h): at
// most one per method and frame.

#include <Eigen/Geometry>
#include <climits>
#include <cstdint>
#include <memory>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/gyro_aided_initializer.h"
#include "estimator/init_attempt.h"
#include "estimator/initial_window.h"
#include "estimator/mono_initializer.h"
#include "estimator/static_initializer.h"
#include "estimator/stereo_initializer.h"
#include "estimator/zero_velocity.h"

namespace vio {

// How long the gyroscope-aided start waits after its precheck found no
// translation in the window before it tries again: at 20 Hz five frames, an
// eighth of its 2 s window new; doubled at each such refusal in a row, up to
// the window's length [s].
constexpr double kGyroAidedRetryAfterNoParallaxS = 0.25;

class Initialization {
 public:
  // T_b_c: one extrinsic per camera used (two with use_stereo); focal_px:
  // camera 0's.
  Initialization(const EstimatorOptions& options,
                 const std::vector<Eigen::Isometry3d>& T_b_c, double focal_px,
                 const ImuNoise& noise,
                 const PreintegrationOptions& preintegration);

  // Feeds the static start (finite samples only).
  void AddImu(const ImuSample& sample);
  // Buffers a frame for the in-motion starts (older frames than their
  // windows need are dropped).
  void AddFrame(const FeatureFrame& frame, int64_t t_imu_ns);

  // Tries the starts init.method allows at the newest frame. `still` is the
  // zero-velocity detector's verdict at it; imu the estimator's buffer.
  // True with *window on success; failures are appended to *log.
  bool TryStart(const std::vector<ImuSample>& imu, const StillnessReport& still,
                std::vector<InitAttempt>* log, InitialWindow* window);

  // Only the in-motion start (for re-initialisation after a reset);
  // false without logging when the method is static.
  bool TryInMotion(const std::vector<ImuSample>& imu,
                   std::vector<InitAttempt>* log, InitialWindow* window);

  // Forgets the buffered frames and IMU.
  void Clear();

 private:
  InitAttempt TryStatic(const StillnessReport& still, InitialWindow* window);

  EstimatorOptions options_;
  StaticInitializer static_;
  std::unique_ptr<MonoInitializer> mono_;
  std::unique_ptr<StereoInitializer> stereo_;
  std::unique_ptr<GyroAidedInitializer> gyro_aided_;  // mono's fallback
  std::vector<BufferedFrame> frames_;
  // No gyroscope-aided attempt before this frame stamp [ns].
  int64_t gyro_aided_next_ns_ = INT64_MIN;
  double gyro_aided_wait_s_ = 0.0;  // the last wait set, 0: none [s]
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_INITIALIZATION_H_
