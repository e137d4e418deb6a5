#ifndef VIO_RENDER_SEQUENCE_RENDERER_H_
#define VIO_RENDER_SEQUENCE_RENDERER_H_

// Renders the images of a sequence, frame after frame, along any body
// trajectory (the simulator's analytic one, or a curve fitted to a recorded
// flight): each camera's image of the textured scene with motion blur over
// the exposure, the auto-exposure gain, vignetting and sensor noise.
//
// Time: the frame stamped t_ns (camera clock) is exposed around IMU time
// t_ns + t_d (t_d = time_offset_s, as the simulator's cameras). With an
// exposure time T > 0 its image is the mean of N renders at the IMU times
//   t_ns + t_d - T/2 + (i + 0.5) T / N,  i = 0..N-1,
// N = ceil(d / blur_step_px) (at most max_blur_samples), d the largest
// motion during the exposure of the scene points seen at nine probe pixels
// of any camera. The pose at the exposure centre is the frame's truth.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "geometry/camera_model.h"
#include "render/camera_renderer.h"
#include "render/render_options.h"
#include "render/sensor_model.h"
#include "render/texture_atlas.h"

namespace vio {

// The pose of the body (IMU) frame in the world at an IMU stamp [ns].
using BodyPoseAt = std::function<Eigen::Isometry3d(int64_t t_ns)>;

struct RenderedFrame {
  int64_t t_ns = 0;             // camera stamp [ns]
  std::vector<cv::Mat> images;  // 8-bit grey, one per camera
  Eigen::Isometry3d T_w_b = Eigen::Isometry3d::Identity();  // exposure centre
  int blur_samples = 1;                                     // renders averaged
  double gain = 1.0;  // cam0's gain (cam1: times cam1_gain_ratio)
};

// Running totals, for a tool's summary.
struct RenderStats {
  int64_t frames = 0;
  int64_t images = 0;        // frames x cameras
  int64_t blur_samples = 0;  // summed over frames
  int max_blur_samples = 0;
  double cpu_seconds = 0.0;  // process CPU time spent rendering [s]
};

class SequenceRenderer {
 public:
  // `scene` must outlive the renderer; cameras are cam0, cam1, ... The
  // seed drives the gain walk and the noise. Throws std::invalid_argument
  // for invalid options or a camera CameraRenderer refuses.
  SequenceRenderer(const std::vector<CameraCalibration>& cameras,
                   const TexturedScene* scene, const RenderOptions& options,
                   double time_offset_s, uint32_t seed);

  // Renders the next frame into *frame (its images are reused when they
  // have the right size: pass the same frame again to avoid allocations).
  // Frames must come in increasing stamp order (the gain walks from one
  // frame to the next).
  void Render(int64_t t_ns, const BodyPoseAt& body_pose, RenderedFrame* frame);

  const RenderStats& stats() const { return stats_; }
  const std::vector<CameraRenderer>& cameras() const { return cameras_; }

 private:
  int BlurSamples(const Eigen::Isometry3d& T_w_b0,
                  const Eigen::Isometry3d& T_w_b1) const;
  double NextGain();

  RenderOptions options_;
  const TexturedScene* scene_;
  std::vector<CameraRenderer> cameras_;
  std::vector<SensorModel> sensors_;
  std::vector<Eigen::Isometry3d> T_b_c_;
  int64_t time_offset_ns_;
  uint32_t seed_;
  std::mt19937 gain_rng_;
  double log_gain_ = 0.0;
  RenderStats stats_;
  cv::Mat radiance_;  // reused from frame to frame
};

}  // namespace vio

#endif  // VIO_RENDER_SEQUENCE_RENDERER_H_
