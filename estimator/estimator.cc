#include "estimator/estimator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "estimator/image_velocity.h"
#include "estimator/state_check.h"
#include "estimator/state_prior.h"
#include "estimator/window_problem.h"
#include "preintegration/imu_preintegration.h"

namespace vio {
namespace {

void Require(bool ok, const std::string& what, const std::string& message) {
  if (!ok) throw std::invalid_argument("Estimator: " + what + message);
}

bool Finite(const EstimatorOutput& o) {
  return o.p_w_b.allFinite() && o.q_w_b.coeffs().allFinite() &&
         o.v_w.allFinite() && o.b_a.allFinite() && o.b_g.allFinite();
}

// The cameras' extrinsics for the initialisers (an identity when there is
// none: the constructor then throws before using them).
std::vector<Eigen::Isometry3d> Extrinsics(
    const std::vector<EstimatorCamera>& cameras) {
  std::vector<Eigen::Isometry3d> T;
  for (const EstimatorCamera& c : cameras) T.push_back(c.T_b_c);
  if (T.empty()) T.push_back(Eigen::Isometry3d::Identity());
  return T;
}

double FirstFocal(const std::vector<EstimatorCamera>& cameras) {
  return cameras.empty() ? 460.0 : cameras[0].focal_px;
}

// The state a pre-solve restart starts from: the last output carried to the
// frame's stamp, since that output is one frame step old. The IMU prediction
// of the step is what exploded, so its position and velocity are useless
// (an accelerometer spike of 1e6 m/s^2 puts it 40-50 m off: the trajectory's
// ATE, docs/initialisation.md); the position moves on at the last velocity,
//   p = p_last + v_last dt   (error a dt^2 / 2, ~1 mm at 1 m/s^2 and 50 ms),
// and the attitude takes the prediction's, the gyroscope's alone, when finite.
// Held at the last output, as before, the restart lagged one frame step
// (0.054 m and the rotation over that step at the test's reset), an offset
// that the new window, gauge-free in position and yaw, never removes.
EstimatorOutput CarriedToFrame(const EstimatorOutput& last,
                               const EstimatorOutput& predicted,
                               int64_t t_ns) {
  EstimatorOutput carried = last;
  carried.t_ns = t_ns;
  const double dt = 1e-9 * static_cast<double>(t_ns - last.t_ns);
  carried.p_w_b = last.p_w_b + last.v_w * dt;
  if (predicted.q_w_b.coeffs().allFinite()) {
    carried.q_w_b = predicted.q_w_b.normalized();
  }
  return carried;
}

}  // namespace

Estimator::Estimator(const EstimatorOptions& options,
                     const VisualFactorOptions& visual, const ImuNoise& noise,
                     const PreintegrationOptions& preintegration,
                     const std::vector<EstimatorCamera>& cameras)
    : options_(options),
      visual_(visual),
      noise_(noise),
      noise_adaptation_(options.imu_stream.noise_adaptation),
      preintegration_(preintegration),
      cameras_(cameras),
      init_(options, Extrinsics(cameras), FirstFocal(cameras), noise,
            preintegration),
      zero_velocity_(options.zero_velocity, FirstFocal(cameras)),
      realign_(options,
               cameras.empty() ? Eigen::Isometry3d::Identity()
                               : cameras.front().T_b_c,
               FirstFocal(cameras), noise, preintegration),
      features_(options.use_stereo ? 2 : 1),
      imu_filter_(options.imu_stream.range, preintegration.max_sample_gap) {
  std::string message;
  Require(options.Validate(&message), "options.", message);
  Require(visual.Validate(&message), "visual.", message);
  Require(noise.Validate(&message), "imu noise: ", message);
  Require(preintegration.Validate(&message), "preintegration: ", message);
  Require(!cameras.empty() && cameras.size() <= kMaxCameras, "",
          "needs 1 or 2 cameras");
  Require(!options.use_stereo || cameras.size() == 2, "",
          "use_stereo needs 2 cameras");
  window_.num_cameras = options.use_stereo ? 2 : 1;
  window_.t_d = options.initial_time_offset_s;
  for (int c = 0; c < window_.num_cameras; ++c) {
    Require(cameras[c].focal_px > 0.0 && std::isfinite(cameras[c].focal_px), "",
            "camera focal length must be > 0");
    window_.extrinsics[c] = PoseArray(cameras[c].T_b_c);
  }
}

Estimator::~Estimator() = default;

void Estimator::AddImu(const ImuSample& sample) {
  if (!sample.acc.allFinite() || !sample.gyr.allFinite()) {
    ++summary_.imu_non_finite;
    return;
  }
  if (!imu_.empty() && sample.t_ns <= imu_.back().t_ns) {
    ++summary_.imu_out_of_order;
    return;
  }
  const size_t before = imu_.size();
  const ImuScreening screening = imu_filter_.Add(sample, &imu_);
  // The samples the filter let through (it may hold some back).
  for (size_t i = before; i < imu_.size(); ++i) realign_.AddImu(imu_[i]);
  if (screening != ImuScreening::kAccepted &&
      summary_.imu_first_glitch_t_ns < 0) {
    summary_.imu_first_glitch_t_ns = sample.t_ns;
  }
  switch (screening) {
    case ImuScreening::kDropped:
      ++summary_.imu_dropped;
      return;
    case ImuScreening::kReplaced:
      ++summary_.imu_replaced;
      break;
    case ImuScreening::kAccepted:
      break;
  }
  NoteImuStep();
  ++summary_.imu_samples;
  zero_velocity_.AddImu(imu_.back());
  if (!initialized_) init_.AddImu(imu_.back());
}

CameraPoseFn Estimator::PoseFn() const {
  return [this](int64_t id, int camera) { return window_.T_w_c(id, camera); };
}

EstimatorOutput Estimator::OutputOf(const WindowFrame& f, int64_t t_ns) const {
  EstimatorOutput o;
  o.t_ns = t_ns;
  o.processed = true;
  o.initialized = true;
  o.keyframe = f.keyframe;
  o.zero_velocity = f.still_link;
  o.p_w_b = Eigen::Vector3d(f.pose.data() + kPoseP);
  o.q_w_b = Eigen::Quaterniond(f.pose.data() + kPoseQ).normalized();
  o.v_w = Eigen::Vector3d(f.speed_bias.data() + kSbV);
  o.b_a = Eigen::Vector3d(f.speed_bias.data() + kSbBa);
  o.b_g = Eigen::Vector3d(f.speed_bias.data() + kSbBg);
  return o;
}

EstimatorOutput Estimator::AddFrame(const FeatureFrame& frame) {
  const EstimatorOutput out = Step(frame);
  std::vector<int64_t> ids;
  ids.reserve(frame.observations.size());
  for (const FeatureObservation& o : frame.observations) {
    ids.push_back(o.feature_id);
  }
  std::sort(ids.begin(), ids.end());
  landmark_map_.Retire(features_, ids);
  return out;
}

EstimatorOutput Estimator::Step(const FeatureFrame& frame) {
  ++summary_.frames;
  EstimatorOutput skipped = last_output_;
  skipped.t_ns = frame.t_ns;
  skipped.processed = false;
  if (have_frame_ && frame.t_ns <= last_frame_t_ns_) {
    ++summary_.frames_out_of_order;
    return skipped;
  }
  const int64_t t_imu_ns = frame.t_ns + std::llround(window_.t_d * 1e9);
  // Not covered yet: wait for the IMU, unless it has gone silent (a gap,
  // tracked on vision alone once initialised).
  const bool covered = !imu_.empty() && imu_.back().t_ns >= t_imu_ns;
  if (!covered && !(initialized_ && ImuHasGap(t_imu_ns, t_imu_ns))) {
    ++summary_.frames_without_imu;
    return skipped;
  }
  have_frame_ = true;
  last_frame_t_ns_ = frame.t_ns;
  zero_velocity_.AddFrame(frame.t_ns, frame.observations);
  if (!initialized_) {
    if (!TryInitialize(frame, t_imu_ns)) {
      ++summary_.frames_before_init;
      EstimatorOutput o;
      o.t_ns = frame.t_ns;
      o.processed = true;
      return last_output_ = o;
    }
    ++summary_.frames_processed;
    return last_output_ = OutputOf(*window_.frames.back(), frame.t_ns);
  }
  EstimatorOutput out;
  if (!ProcessFrame(frame, t_imu_ns, &out)) return skipped;
  ++summary_.frames_processed;
  if (reinit_pending_) TryReinitialize(frame, t_imu_ns, &out);
  TrimImu();
  return last_output_ = out;
}

bool Estimator::TryInitialize(const FeatureFrame& frame, int64_t t_imu_ns) {
  init_.AddFrame(frame, t_imu_ns);
  InitialWindow start;
  if (!init_.TryStart(imu_, zero_velocity_.Check(), &summary_.init_attempts,
                      &start) ||
      !StartFromInitialWindow(start, /*restart=*/false)) {
    return false;
  }
  initialized_ = true;
  init_.Clear();
  return true;
}

void Estimator::StartWindow(const FeatureFrame& frame, int64_t t_imu_ns,
                            const EstimatorOutput& state,
                            double velocity_sigma) {
  window_.frames.clear();
  features_.Clear();
  features_ = FeatureManager(window_.num_cameras);
  auto f = std::make_unique<WindowFrame>();
  f->id = next_frame_id_++;
  f->t_ns = frame.t_ns;
  f->t_imu_ns = t_imu_ns;
  f->t_d_at_stamp = window_.t_d;
  f->gyr_b = GyroscopeAt(imu_, t_imu_ns);
  f->keyframe = true;
  f->p_w_b() = state.p_w_b;
  f->q_w_b() = state.q_w_b.normalized();
  f->v_w() = state.v_w;
  f->b_a() = state.b_a;
  f->b_g() = state.b_g;
  summary_.observations_skipped +=
      features_.AddFrame(f->id, frame.observations).skipped;
  last_keyframe_id_ = f->id;
  ++summary_.keyframes;
  window_.frames.push_back(std::move(f));
  // With stereo the pair gives depths at once.
  summary_.landmarks_triangulated +=
      features_.TriangulateNew(PoseFn(), options_.triangulation);
  SetPriorOnOldest(velocity_sigma);
}

void Estimator::SetPriorOnOldest(double velocity_sigma) {
  WindowFrame& f = *window_.frames.front();
  prior_ = MakeStatePrior(f.pose.data(), f.speed_bias.data(),
                          options_.state_prior, velocity_sigma);
  prior_blocks_ = {f.pose.data(), f.speed_bias.data()};
  SetExtrinsicPrior();
  DropWorldPoints();
}

void Estimator::SetExtrinsicPrior() {
  extrinsic_prior_.reset();
  extrinsic_prior_blocks_.clear();
  if (!options_.estimate_extrinsics) return;
  std::vector<const double*> values;
  for (int c = 0; c < window_.num_cameras; ++c) {
    extrinsic_prior_blocks_.push_back(window_.extrinsics[c].data());
    values.push_back(window_.extrinsics[c].data());
  }
  extrinsic_prior_ = MakeExtrinsicPrior(values, options_.state_prior);
}

void Estimator::TrimImu() {
  // Intervals keep their own samples; the buffer only needs to reach back to
  // the newest frame (one sample before it for interpolation).
  const int64_t t_keep = window_.frames.back()->t_imu_ns;
  size_t first = 0;
  while (first + 1 < imu_.size() && imu_[first + 1].t_ns <= t_keep) ++first;
  if (first > 1000) imu_.erase(imu_.begin(), imu_.begin() + first);
}

void Estimator::DropSecondNewest() {
  auto& frames = window_.frames;
  const size_t k = frames.size() - 2;
  WindowFrame& dropped = *frames[k];
  WindowFrame& newest = *frames[k + 1];
  // Across an IMU gap there is no preintegration to merge (a visual link).
  if (dropped.imu && newest.imu) {
    newest.imu = std::make_unique<ImuPreintegration>(
        ImuPreintegration::Merge(*dropped.imu, *newest.imu));
  } else {
    newest.imu.reset();
  }
  newest.still_link = dropped.still_link && newest.still_link;
  features_.RemoveFrame(dropped.id, PoseFn());
  frames.erase(frames.begin() + k);
  ReleaseOrphanPoints();
}

void Estimator::Reset(int64_t t_ns, Failure reason) {
  ++summary_.resets;
  summary_.reset_log.push_back({t_ns, reason});
  realign_.Stop();
  prior_.reset();
  prior_blocks_.clear();
  DropWorldPoints();
  extrinsic_prior_.reset();
  extrinsic_prior_blocks_.clear();
  gap_bias_prior_.reset();
  gap_bias_prior_blocks_.clear();
}

void Estimator::Restart(const FeatureFrame& frame, int64_t t_imu_ns,
                        Failure reason, const EstimatorOutput& state) {
  Reset(frame.t_ns, reason);
  StartWindow(frame, t_imu_ns, state, options_.state_prior.velocity_moving);
  newest_still_ = StillNow(state.v_w.norm());
  // The in-motion initialiser starts over from this frame on.
  if (options_.init.reinitialize_after_reset &&
      options_.init.method != InitMethod::kStatic) {
    reinit_pending_ = true;
    init_.Clear();
  }
}

bool Estimator::AppendFrame(const FeatureFrame& frame, int64_t t_imu_ns,
                            EstimatorOutput* predicted) {
  const WindowFrame& prev = *window_.frames.back();
  auto f = std::make_unique<WindowFrame>();
  try {
    f->imu = std::make_unique<ImuPreintegration>(
        prev.t_imu_ns, t_imu_ns, imu_,
        Eigen::Vector3d(prev.speed_bias.data() + kSbBa),
        Eigen::Vector3d(prev.speed_bias.data() + kSbBg),
        noise_adaptation_.Scaled(noise_), preintegration_);
  } catch (const std::invalid_argument&) {
    ++summary_.frames_without_imu;  // a gap or a hole in the IMU stream
    return false;
  }
  f->id = next_frame_id_++;
  f->t_ns = frame.t_ns;
  f->t_imu_ns = t_imu_ns;
  f->t_d_at_stamp = window_.t_d;
  f->gyr_b = GyroscopeAt(imu_, t_imu_ns);
  // Prediction: p_j = p_i + v_i T + g T^2 / 2 + R_i dp,
  //             v_j = v_i + g T + R_i dv,  q_j = q_i dq.
  const Eigen::Isometry3d T_w_i = prev.T_w_b();
  const Eigen::Vector3d v_i(prev.speed_bias.data() + kSbV);
  const Eigen::Vector3d g_w(0.0, 0.0, -options_.gravity_magnitude);
  const double T = f->imu->sum_dt();
  const ImuDelta& d = f->imu->delta();
  f->p_w_b() =
      T_w_i.translation() + v_i * T + 0.5 * g_w * T * T + T_w_i.linear() * d.p;
  f->v_w() = v_i + g_w * T + T_w_i.linear() * d.v;
  f->q_w_b() =
      (Eigen::Quaterniond(prev.pose.data() + kPoseQ) * d.q).normalized();
  for (int k = kSbBa; k < 9; ++k) f->speed_bias[k] = prev.speed_bias[k];
  *predicted = OutputOf(*f, frame.t_ns);
  PushFrame(std::move(f), frame);
  return true;
}

void Estimator::PushFrame(std::unique_ptr<WindowFrame> f,
                          const FeatureFrame& frame) {
  const FrameAddStats stats = features_.AddFrame(f->id, frame.observations);
  summary_.observations_skipped += stats.skipped;
  if (stats.added == 0) ++summary_.frames_without_observations;
  const KeyframeDecision decision =
      DecideKeyframe(features_, last_keyframe_id_, f->id, cameras_[0].focal_px,
                     options_.keyframe);
  // A frame without observations adds nothing to keep.
  f->keyframe = stats.added > 0 && decision.is_keyframe;
  window_.frames.push_back(std::move(f));
}

bool Estimator::ProcessFrame(const FeatureFrame& frame, int64_t t_imu_ns,
                             EstimatorOutput* out) {
  EstimatorOutput predicted;
  if (ImuHasGap(window_.frames.back()->t_imu_ns, t_imu_ns)) {
    if (!AppendVisualFrame(frame, t_imu_ns, &predicted)) {
      return RestartAfterGap(frame, t_imu_ns, out);
    }
  } else {
    ResumeImuAfterGap();
    if (!AppendFrame(frame, t_imu_ns, &predicted)) return false;
  }
  MarkStillness(window_.frames.back().get());
  // A frame starting the IMU chain after a gap stays: its interval cannot
  // be merged with the visual link before it.
  const size_t n = window_.frames.size();
  if (n >= 3 && !window_.frames[n - 2]->keyframe &&
      (window_.frames[n - 2]->imu || !window_.frames[n - 1]->imu)) {
    DropSecondNewest();
  }
  Realign(frame, t_imu_ns);
  summary_.landmarks_triangulated +=
      features_.TriangulateNew(PoseFn(), options_.triangulation);
  // Ceres stops the program on a non-finite block: never hand it one.
  if (CheckWindowState(window_, features_, options_.failure.max_speed_m_s) !=
      StateDefect::kNone) {
    Restart(frame, t_imu_ns, Failure::kUnsafeState,
            CarriedToFrame(last_output_, predicted, frame.t_ns));
    *out = OutputOf(*window_.frames.back(), frame.t_ns);
    return true;
  }

  WindowProblem problem(&window_, &features_, ProblemSettings());
  if (prior_) problem.AddPrior(prior_.get(), prior_blocks_);
  if (extrinsic_prior_) {
    problem.AddPrior(extrinsic_prior_.get(), extrinsic_prior_blocks_);
  }
  if (gap_bias_prior_) {
    problem.AddPrior(gap_bias_prior_.get(), gap_bias_prior_blocks_);
  }
  const bool imu_ok = problem.AddImuFactors();
  const int landmarks = problem.AddVisualFactors();
  AddZeroVelocityFactors(&problem);
  Solve(&problem);

  Failure failure = CheckStep(predicted, landmarks, frame.t_ns);
  if (failure == Failure::kNone && !imu_ok) failure = Failure::kNonFinite;
  if (failure != Failure::kNone) {
    // Restart from the prediction, or from the last good output when even
    // the prediction is not finite.
    Restart(frame, t_imu_ns, failure,
            Finite(predicted) ? predicted : last_output_);
  } else {
    AdaptImuNoise();
    Slide(problem);
    RefreshVisualVelocity(window_.frames.back().get());
  }
  *out = OutputOf(*window_.frames.back(), frame.t_ns);
  if (out->zero_velocity) ++summary_.zero_velocity_frames;
  return true;
}

}  // namespace vio
