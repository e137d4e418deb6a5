#include "estimator/initialization.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace vio {

Initialization::Initialization(const EstimatorOptions& options,
                               const std::vector<Eigen::Isometry3d>& T_b_c,
                               double focal_px, const ImuNoise& noise,
                               const PreintegrationOptions& preintegration)
    : options_(options),
      static_(options.static_init, options.gravity_magnitude) {
  // auto takes the stereo start when the configuration is stereo; a forced
  // mono start uses camera 0 of a stereo configuration alone.
  const bool stereo =
      options.init.method == InitMethod::kStereo ||
      (options.init.method == InitMethod::kAuto && options.use_stereo);
  if (stereo && T_b_c.size() >= 2) {
    stereo_ = std::make_unique<StereoInitializer>(
        options, T_b_c[0], T_b_c[1], focal_px, noise, preintegration);
  } else {
    mono_ = std::make_unique<MonoInitializer>(options, T_b_c[0], focal_px,
                                              noise, preintegration);
    if (options.init.mono.gyro_aided) {
      gyro_aided_ = std::make_unique<GyroAidedInitializer>(
          options, T_b_c[0], focal_px, noise, preintegration);
    }
  }
}

void Initialization::AddImu(const ImuSample& sample) {
  static_.AddSample(sample);
}

void Initialization::AddFrame(const FeatureFrame& frame, int64_t t_imu_ns) {
  frames_.push_back({frame.t_ns, t_imu_ns, frame.observations});
  // Keep what the larger window needs, with one frame of margin.
  const double keep_s =
      std::max(options_.init.mono.long_window_s, options_.init.stereo.window_s);
  const int64_t keep_ns = std::llround(keep_s * 1e9);
  size_t drop = 0;
  while (drop + 2 < frames_.size() &&
         frame.t_ns - frames_[drop + 1].t_ns > keep_ns) {
    ++drop;
  }
  frames_.erase(frames_.begin(), frames_.begin() + drop);
}

InitAttempt Initialization::TryStatic(const StillnessReport& still,
                                      InitialWindow* window) {
  InitAttempt a;
  a.t_ns = frames_.empty() ? 0 : frames_.back().t_ns;
  a.method = InitMethod::kStatic;
  StaticInitState s;
  if (!static_.TryInitialize(&s)) {
    const ImuStatistics stats = static_.Statistics();
    const double acc = stats.acc_block_std.maxCoeff();
    const bool acc_bad = acc > options_.static_init.max_acc_std;
    a.reason = InitFailure::kNotStill;
    a.value = acc_bad ? acc : stats.gyr_block_std.maxCoeff();
    a.limit = acc_bad ? options_.static_init.max_acc_std
                      : options_.static_init.max_gyr_std;
    // A span still too short reads as "not still" with the std so far.
    if (stats.duration_s < 0.95 * options_.static_init.window_s) {
      a.reason = InitFailure::kTooFewFrames;
      a.value = stats.duration_s;
      a.limit = options_.static_init.window_s;
    }
    return a;
  }
  // The IMU cannot tell rest from slow motion: the features must agree.
  if (still.newest_has_features && !still.image_verdict) {
    a.reason = InitFailure::kNoImageVerdict;
    a.value = still.common_features;
    a.limit = options_.zero_velocity.min_common_features;
    return a;
  }
  if (still.image_verdict && !still.image_still) {
    a.reason = InitFailure::kImageMoving;
    a.value = still.disparity_px;
    a.limit = options_.zero_velocity.max_disparity_px;
    return a;
  }
  InitialFrame f;
  f.t_ns = frames_.back().t_ns;
  f.t_imu_ns = frames_.back().t_imu_ns;
  f.q_w_b = s.q_w_b;
  f.b_a = s.b_a;
  f.b_g = s.b_g;
  f.observations = frames_.back().observations;
  window->method = InitMethod::kStatic;
  window->frames = {f};
  window->points_w.clear();
  window->diagnostics = InitDiagnostics();
  return a;
}

bool Initialization::TryStart(const std::vector<ImuSample>& imu,
                              const StillnessReport& still,
                              std::vector<InitAttempt>* log,
                              InitialWindow* window) {
  if (frames_.empty()) return false;
  const InitMethod m = options_.init.method;
  if (m == InitMethod::kAuto || m == InitMethod::kStatic) {
    const InitAttempt a = TryStatic(still, window);
    if (a.reason == InitFailure::kNone) return true;
    log->push_back(a);
    if (m == InitMethod::kStatic) return false;
  }
  return TryInMotion(imu, log, window);
}

bool Initialization::TryInMotion(const std::vector<ImuSample>& imu,
                                 std::vector<InitAttempt>* log,
                                 InitialWindow* window) {
  if (frames_.empty() || options_.init.method == InitMethod::kStatic) {
    return false;
  }
  const InitAttempt a = stereo_ ? stereo_->TryInitialize(frames_, imu, window)
                                : mono_->TryInitialize(frames_, imu, window);
  if (a.reason == InitFailure::kNone) return true;
  log->push_back(a);
  if (!gyro_aided_) return false;
  const int64_t t_ns = frames_.back().t_ns;
  if (t_ns < gyro_aided_next_ns_) return false;
  // With one mono window (long_window_s = window_s, the default) both
  // starts select the same frames and measure the same excitation: the
  // mono refusal is the gyroscope-aided one's too, without preintegrating
  // the window again (a constant-velocity sequence paid that at every
  // frame, 1.7 times the run's time with the key off).
  const MonoInitOptions& mono = options_.init.mono;
  if (a.reason == InitFailure::kLowImuExcitation &&
      mono.long_window_s <= mono.window_s) {
    InitAttempt b = a;
    b.method = InitMethod::kGyroAided;
    log->push_back(b);
    return false;
  }
  const InitAttempt b = gyro_aided_->TryInitialize(frames_, imu, window);
  if (b.reason == InitFailure::kNone) return true;
  log->push_back(b);
  // A window whose frames showed no translation (refused by the cheap
  // precheck, ~0.1 s of work) is judged again once a part of it is new,
  // not at every frame: a camera turning on the spot for a whole sequence
  // paid that precheck 270 times in 15 s (docs/initialisation.md). Each
  // further such refusal doubles the wait, up to the window's length (a
  // window of frames all new); any other outcome resets it.
  if (b.reason == InitFailure::kLowParallax && !window->diagnostics.full_fit) {
    gyro_aided_wait_s_ =
        gyro_aided_wait_s_ > 0.0
            ? std::min(2.0 * gyro_aided_wait_s_, mono.window_s)
            : kGyroAidedRetryAfterNoParallaxS;
    gyro_aided_next_ns_ = t_ns + std::llround(gyro_aided_wait_s_ * 1e9);
  } else {
    gyro_aided_wait_s_ = 0.0;
  }
  return false;
}

void Initialization::Clear() {
  static_.Clear();
  frames_.clear();
  gyro_aided_next_ns_ = INT64_MIN;
  gyro_aided_wait_s_ = 0.0;
}

}  // namespace vio
