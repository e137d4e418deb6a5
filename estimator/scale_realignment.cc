#include "estimator/scale_realignment.h"

#include <algorithm>
#include <cmath>

namespace vio {
namespace {

// Frames tried between two attempts once the realignment is due.
constexpr int kRetryFrames = 5;

}  // namespace

double PositionSpread(const std::vector<Eigen::Vector3d>& p) {
  if (p.empty()) return 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& x : p) c += x;
  c /= static_cast<double>(p.size());
  double s = 0.0;
  for (const Eigen::Vector3d& x : p) s += (x - c).squaredNorm();
  return std::sqrt(s / static_cast<double>(p.size()));
}

double SpreadRatio(const std::vector<InitialFrame>& reference,
                   const Window& window, int min_frames, int* common) {
  *common = 0;
  const auto& frames = window.frames;
  if (frames.size() < 2) return 0.0;
  std::vector<Eigen::Vector3d> ref, win;
  size_t k = 1;  // window interval [k-1, k] holding the stamp
  for (const InitialFrame& f : reference) {
    const int64_t t = f.t_imu_ns;
    if (t < frames.front()->t_imu_ns || t > frames.back()->t_imu_ns) continue;
    while (k + 1 < frames.size() && frames[k]->t_imu_ns < t) ++k;
    const WindowFrame& a = *frames[k - 1];
    const WindowFrame& b = *frames[k];
    const double span = static_cast<double>(b.t_imu_ns - a.t_imu_ns);
    const double u =
        span > 0.0 ? static_cast<double>(t - a.t_imu_ns) / span : 0.0;
    win.push_back((1.0 - u) * a.p_w_b_value() + u * b.p_w_b_value());
    ref.push_back(f.p_w_b);
  }
  *common = static_cast<int>(ref.size());
  if (*common < min_frames) return 0.0;
  const double s_ref = PositionSpread(ref), s_win = PositionSpread(win);
  if (!(s_ref > 0.0 && s_win > 0.0)) return 0.0;
  return s_ref / s_win;
}

ScaleRealignment::ScaleRealignment(const EstimatorOptions& options,
                                   const Eigen::Isometry3d& T_b_c,
                                   double focal_px, const ImuNoise& noise,
                                   const PreintegrationOptions& preintegration)
    : options_(options.init.mono) {
  if (options_.realign_after_s <= 0.0) return;
  // The start's monocular initialiser over the longer span alone (no
  // fallback window, no wait: only its scale and that scale's std are used).
  EstimatorOptions o = options;
  o.init.mono.long_window_s = options_.realign_window_s;
  o.init.mono.window_s = options_.realign_window_s;
  o.init.mono.min_span_s = 0.75 * options_.realign_window_s;
  o.init.mono.max_frames = 2 * options.init.mono.max_frames - 1;
  mono_ = std::make_unique<MonoInitializer>(o, T_b_c, focal_px, noise,
                                            preintegration);
}

void ScaleRealignment::Begin(const std::vector<BufferedFrame>& start_frames,
                             int64_t t_ns) {
  if (!mono_) return;
  active_ = true;
  start_ns_ = t_ns;
  frames_since_try_ = kRetryFrames;
  frames_ = start_frames;
}

void ScaleRealignment::Stop() {
  active_ = false;
  frames_.clear();  // the IMU stays: a later start needs what precedes it
}

void ScaleRealignment::AddImu(const ImuSample& sample) {
  if (!mono_ || (!imu_.empty() && sample.t_ns <= imu_.back().t_ns)) return;
  imu_.push_back(sample);
  // Kept: the span and a second before it (the start's oldest frames).
  const int64_t keep_ns =
      std::llround((options_.realign_window_s + options_.realign_after_s +
                    options_.window_s + 1.0) *
                   1e9);
  if (imu_.size() > 4096 && sample.t_ns - imu_.front().t_ns > keep_ns) {
    size_t drop = 0;
    while (drop + 1 < imu_.size() && sample.t_ns - imu_[drop].t_ns > keep_ns) {
      ++drop;
    }
    imu_.erase(imu_.begin(), imu_.begin() + drop);
  }
}

void ScaleRealignment::AddFrame(const FeatureFrame& frame, int64_t t_imu_ns) {
  if (!active_) return;
  if (!frames_.empty() && frame.t_ns <= frames_.back().t_ns) return;
  frames_.push_back({frame.t_ns, t_imu_ns, frame.observations});
  const int64_t keep_ns = std::llround(options_.realign_window_s * 1e9);
  size_t drop = 0;
  while (drop + 2 < frames_.size() &&
         frame.t_ns - frames_[drop + 1].t_ns > keep_ns) {
    ++drop;
  }
  frames_.erase(frames_.begin(), frames_.begin() + drop);
}

bool ScaleRealignment::TrySpan(int64_t t_ns, InitialWindow* span) {
  if (!active_) return false;
  const double age_s = 1e-9 * static_cast<double>(t_ns - start_ns_);
  if (age_s < options_.realign_after_s) return false;
  if (age_s > options_.realign_after_s + options_.realign_window_s) {
    Stop();  // given up
    return false;
  }
  if (++frames_since_try_ < kRetryFrames) return false;
  frames_since_try_ = 0;
  const InitAttempt a = mono_->TryInitialize(frames_, imu_, span);
  return a.reason == InitFailure::kNone;
}

bool ScaleRealignment::Compare(const InitialWindow& span, const Window& window,
                               RealignmentResult* r) {
  // The joint adjustment's own figure for the span (AdjustSpan in
  // estimator_realign.cc; scale_uncertainty.h): not determined well enough,
  // the span is not used, and the next try comes a few frames later.
  const double sigma = span.diagnostics.refined_scale_sigma;
  if (!(sigma >= 0.0 && sigma <= options_.realign_max_scale_uncertainty)) {
    return false;
  }
  int common = 0;
  const double ratio = SpreadRatio(span.frames, window, 4, &common);
  if (!(ratio > 0.0) || !std::isfinite(ratio)) return false;
  r->done = true;
  r->scale = ratio;
  r->scale_sigma = sigma;
  r->common_frames = common;
  Stop();
  return true;
}

}  // namespace vio
