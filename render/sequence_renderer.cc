#include "render/sequence_renderer.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <stdexcept>

namespace vio {
namespace {

Eigen::Isometry3d Extrinsic(const CameraCalibration& c) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = c.q_b_c.normalized().toRotationMatrix();
  T.translation() = c.t_b_c;
  return T;
}

uint64_t NoiseSeed(uint32_t seed, int64_t frame, int camera) {
  std::seed_seq sequence{seed, static_cast<uint32_t>(frame),
                         static_cast<uint32_t>(frame >> 32),
                         static_cast<uint32_t>(camera), 0x6e6f6973u};
  uint32_t out[2];
  sequence.generate(out, out + 2);
  return (static_cast<uint64_t>(out[0]) << 32) | out[1];
}

}  // namespace

SequenceRenderer::SequenceRenderer(
    const std::vector<CameraCalibration>& cameras, const TexturedScene* scene,
    const RenderOptions& options, double time_offset_s, uint32_t seed)
    : options_(options),
      scene_(scene),
      time_offset_ns_(std::llround(time_offset_s * 1e9)),
      seed_(seed),
      gain_rng_(seed) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("render options: " + message);
  }
  if (cameras.empty()) throw std::invalid_argument("no camera to render");
  for (const CameraCalibration& c : cameras) {
    cameras_.emplace_back(c, scene, options.view_scale, options.mip_bias);
    sensors_.emplace_back(c, options);
    T_b_c_.push_back(Extrinsic(c));
  }
}

double SequenceRenderer::NextGain() {
  if (stats_.frames > 0 && options_.gain_change_per_frame > 0.0) {
    std::normal_distribution<double> step(0.0, options_.gain_change_per_frame);
    const double lo = std::log(options_.min_gain);
    const double hi = std::log(options_.max_gain);
    log_gain_ += step(gain_rng_);
    // Reflect at the bounds (a step is far smaller than the range).
    for (int i = 0; i < 4 && (log_gain_ < lo || log_gain_ > hi); ++i) {
      log_gain_ = log_gain_ < lo ? 2 * lo - log_gain_ : 2 * hi - log_gain_;
    }
    log_gain_ = std::clamp(log_gain_, lo, hi);
  }
  return std::exp(log_gain_);
}

int SequenceRenderer::BlurSamples(const Eigen::Isometry3d& T_w_b0,
                                  const Eigen::Isometry3d& T_w_b1) const {
  double motion_px = 0.0;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    const CameraModel& model = cameras_[c].camera();
    const CameraCalibration& k = model.calibration();
    const Eigen::Isometry3d T_w_c0 = T_w_b0 * T_b_c_[c];
    const Eigen::Isometry3d T_c1_w = (T_w_b1 * T_b_c_[c]).inverse();
    for (double fu : {0.1, 0.5, 0.9}) {
      for (double fv : {0.1, 0.5, 0.9}) {
        const Eigen::Vector2d uv(fu * (k.width - 1), fv * (k.height - 1));
        Eigen::Vector2d xy, uv1;
        SceneHit hit;
        if (!model.PixelToNormalized(uv, &xy)) continue;
        const Eigen::Vector3d ray_w = T_w_c0.linear() * xy.homogeneous();
        if (!scene_->geometry.Intersect(T_w_c0.translation(), ray_w, &hit)) {
          continue;
        }
        const Eigen::Vector3d X_w =
            T_w_c0.translation() + hit.distance * ray_w.normalized();
        if (!model.Project(T_c1_w * X_w, &uv1)) continue;
        motion_px = std::max(motion_px, (uv1 - uv).norm());
      }
    }
  }
  const int n = static_cast<int>(std::ceil(motion_px / options_.blur_step_px));
  return std::clamp(n, 1, options_.max_blur_samples);
}

void SequenceRenderer::Render(int64_t t_ns, const BodyPoseAt& body_pose,
                              RenderedFrame* frame) {
  const std::clock_t cpu_start = std::clock();
  frame->t_ns = t_ns;
  const int64_t centre_ns = t_ns + time_offset_ns_;
  frame->T_w_b = body_pose(centre_ns);
  const int64_t exposure_ns = std::llround(options_.exposure_time_s * 1e9);
  std::vector<int64_t> times = {centre_ns};
  if (exposure_ns > 0) {
    const int64_t start_ns = centre_ns - exposure_ns / 2;
    const int n =
        BlurSamples(body_pose(start_ns), body_pose(start_ns + exposure_ns));
    times.clear();
    for (int i = 0; i < n; ++i) {
      times.push_back(start_ns + std::llround((i + 0.5) * exposure_ns / n));
    }
  }
  frame->blur_samples = static_cast<int>(times.size());
  std::vector<Eigen::Isometry3d> T_w_b;
  for (int64_t t : times) T_w_b.push_back(body_pose(t));
  frame->gain = NextGain();
  frame->images.resize(cameras_.size());
  for (size_t c = 0; c < cameras_.size(); ++c) {
    std::vector<Eigen::Isometry3d> T_w_c;
    for (const Eigen::Isometry3d& T : T_w_b) T_w_c.push_back(T * T_b_c_[c]);
    const double gain = frame->gain * (c == 1 ? options_.cam1_gain_ratio : 1.0);
    cameras_[c].RenderRadiance(T_w_c, &radiance_);
    sensors_[c].Expose(radiance_, gain,
                       NoiseSeed(seed_, stats_.frames, static_cast<int>(c)),
                       &frame->images[c]);
  }
  ++stats_.frames;
  stats_.images += static_cast<int64_t>(cameras_.size());
  stats_.blur_samples += frame->blur_samples;
  stats_.max_blur_samples =
      std::max(stats_.max_blur_samples, frame->blur_samples);
  stats_.cpu_seconds +=
      static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
}

}  // namespace vio
