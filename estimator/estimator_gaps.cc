// The estimator across gaps in the IMU stream (estimator/imu_gaps.h): gap
// accounting, the visual-only step, and the restart after a gap that vision
// could not bridge.

#include <algorithm>
#include <cmath>

#include "estimator/estimator.h"
#include "estimator/state_prior.h"
#include "estimator/visual_tracker.h"
#include "geometry/so3.h"

namespace vio {
namespace {

int64_t SecondsToNs(double s) { return std::llround(s * 1e9); }

}  // namespace

void Estimator::NoteImuStep() {
  if (imu_.size() < 2) return;
  const int64_t t0 = imu_[imu_.size() - 2].t_ns;
  const int64_t t1 = imu_.back().t_ns;
  if (t1 - t0 > SecondsToNs(preintegration_.max_sample_gap)) {
    // Opened already when a frame found the IMU silent: close it.
    ImuGap* open = GapBefore(t1);
    if (open != nullptr && open->open() && open->t_start_ns == t0) {
      open->t_end_ns = t1;
    } else {
      ImuGap gap;
      gap.t_start_ns = t0;
      gap.t_end_ns = t1;
      summary_.imu_gaps.push_back(gap);
    }
  } else if (static_cast<double>(t1 - t0) >
             1.5e9 / options_.imu_stream.rate_hz) {
    ++summary_.imu_short_gaps;
  }
}

ImuGap* Estimator::GapBefore(int64_t t_ns) {
  for (auto it = summary_.imu_gaps.rbegin(); it != summary_.imu_gaps.rend();
       ++it) {
    if (it->t_start_ns < t_ns) return &*it;
  }
  return nullptr;
}

ImuGap* Estimator::GapFor(int64_t t_imu_ns) {
  // Silent since its last sample and still not back: an open gap, logged
  // now (NoteImuStep closes it when a sample comes).
  const int64_t max_gap_ns = SecondsToNs(preintegration_.max_sample_gap);
  if (!imu_.empty() && t_imu_ns - imu_.back().t_ns > max_gap_ns) {
    std::vector<ImuGap>& gaps = summary_.imu_gaps;
    if (gaps.empty() || gaps.back().t_start_ns != imu_.back().t_ns) {
      ImuGap gap;
      gap.t_start_ns = imu_.back().t_ns;
      gaps.push_back(gap);
    }
    return &gaps.back();
  }
  return GapBefore(t_imu_ns);
}

bool Estimator::ImuHasGap(int64_t t0_ns, int64_t t1_ns) const {
  return LongestImuHoleNs(imu_, t0_ns, t1_ns) >
         SecondsToNs(preintegration_.max_sample_gap);
}

void Estimator::RefreshVisualVelocity(WindowFrame* newest) const {
  // A frame placed by vision alone has no velocity estimate of its own: the
  // difference of the two newest (solved) positions.
  const auto& frames = window_.frames;
  if (frames.size() < 2 || newest->imu) return;
  const WindowFrame& before = *frames[frames.size() - 2];
  const double dt =
      1e-9 * static_cast<double>(newest->t_imu_ns - before.t_imu_ns);
  if (dt <= 0.0) return;
  newest->v_w() =
      (newest->T_w_b().translation() - before.T_w_b().translation()) / dt;
}

void Estimator::ResumeImuAfterGap() {
  auto& frames = window_.frames;
  WindowFrame& newest = *frames.back();
  if (frames.size() < 2 || newest.imu) return;
  // The IMU covers the next interval again. It starts at a frame placed by
  // vision: its velocity comes from the poses; its biases were held through
  // the gap, and with no IMU factor tying them to the biases before it, one
  // short interval would let them jump. Tie them with the random walk the
  // IMU factors would have carried, to the last frame before the gap.
  RefreshVisualVelocity(&newest);
  if (!gap_bias_prior_blocks_.empty() &&
      gap_bias_prior_blocks_.back() == newest.speed_bias.data()) {
    return;
  }
  size_t k = frames.size() - 1;
  while (k > 0 && !frames[k]->imu) --k;
  if (k > 0) {
    // frames[k] has an IMU interval: it is the last frame before the gap.
    const WindowFrame& before = *frames[k];
    const double dt =
        1e-9 * static_cast<double>(newest.t_imu_ns - before.t_imu_ns);
    gap_bias_prior_ =
        MakeBiasLink(before.speed_bias.data(), newest.speed_bias.data(),
                     noise_.accelerometer_random_walk * std::sqrt(dt),
                     noise_.gyroscope_random_walk * std::sqrt(dt));
    gap_bias_prior_blocks_ = {frames[k]->speed_bias.data(),
                              newest.speed_bias.data()};
    return;
  }
  // The frames before the gap have left the window: hold the biases as a
  // fresh window does.
  gap_bias_prior_ =
      MakeBiasPrior(newest.speed_bias.data(), options_.state_prior.accel_bias,
                    options_.state_prior.gyro_bias);
  gap_bias_prior_blocks_ = {newest.speed_bias.data()};
}

bool Estimator::AppendVisualFrame(const FeatureFrame& frame, int64_t t_imu_ns,
                                  EstimatorOutput* predicted) {
  RefreshVisualVelocity(window_.frames.back().get());
  const WindowFrame& prev = *window_.frames.back();
  const double dt = 1e-9 * static_cast<double>(t_imu_ns - prev.t_imu_ns);
  // Guess: the newest frame's velocity and angular rate, held.
  const Eigen::Vector3d w_b = prev.gyr_b - prev.b_g_value();
  Eigen::Isometry3d guess = prev.T_w_b();
  guess.translation() += prev.v_w_value() * dt;
  guess.linear() = guess.linear() * ExpQuaternion(w_b * dt).toRotationMatrix();
  VisualTrackerSettings settings;
  for (int c = 0; c < window_.num_cameras; ++c) {
    settings.focal_px[c] = cameras_[c].focal_px;
  }
  settings.visual = visual_;
  settings.min_landmarks = std::max(options_.failure.min_tracked_landmarks, 6);
  settings.inlier_threshold_px = options_.landmarks.outlier_threshold_px;
  const VisualPose pose = TrackPoseOnLandmarks(
      window_, features_, frame.observations, guess, settings);
  if (!pose.ok || !(dt > 0.0)) return false;

  auto f = std::make_unique<WindowFrame>();  // imu null: a visual link
  f->id = next_frame_id_++;
  f->t_ns = frame.t_ns;
  f->t_imu_ns = t_imu_ns;
  f->t_d_at_stamp = window_.t_d;
  f->pose = PoseArray(pose.T_w_b);
  f->speed_bias = prev.speed_bias;  // the biases held through the gap
  f->v_w() = (pose.T_w_b.translation() - prev.T_w_b().translation()) / dt;
  // The raw gyroscope reading that rotation implies (bias added back).
  const Eigen::Quaterniond dq(prev.T_w_b().linear().transpose() *
                              pose.T_w_b.linear());
  f->gyr_b = Log(dq) / dt + prev.b_g_value();
  *predicted = OutputOf(*f, frame.t_ns);
  PushFrame(std::move(f), frame);
  ++summary_.frames_visual_only;
  if (ImuGap* gap = GapFor(t_imu_ns)) ++gap->frames_visual;
  return true;
}

bool Estimator::RestartAfterGap(const FeatureFrame& frame, int64_t t_imu_ns,
                                EstimatorOutput* out) {
  // Vision could not place the frame. While the IMU is still silent there is
  // nothing to start from: no pose. Once it flows again, start afresh here,
  // from the last pose, so the trajectory continues where it was.
  ImuGap* gap = GapFor(t_imu_ns);
  const bool covered = !imu_.empty() && imu_.back().t_ns >= t_imu_ns;
  if (!covered || ImuHasGap(t_imu_ns, t_imu_ns)) {
    ++summary_.frames_without_imu;
    if (gap != nullptr) ++gap->frames_lost;
    return false;
  }
  if (gap != nullptr) gap->reset = true;
  Restart(frame, t_imu_ns, Failure::kImuGap, last_output_);
  *out = OutputOf(*window_.frames.back(), frame.t_ns);
  return true;
}

}  // namespace vio
