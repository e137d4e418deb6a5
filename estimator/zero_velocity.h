#ifndef VIO_ESTIMATOR_ZERO_VELOCITY_H_
#define VIO_ESTIMATOR_ZERO_VELOCITY_H_

// Zero-velocity detection: is the vehicle standing still right now?
//
// Two witnesses, as OpenVINS' zero-velocity update uses them:
//   - the IMU: over the last imu_window_s the means of blocks of block_s
//     barely vary (accelerometer and gyroscope; block means ignore rotor
//     vibration, see static_initializer.h);
//   - the images: the camera-0 features shared by the newest frame and the
//     frame image_span_s before it moved less than max_disparity_px
//     (median, no rotation compensation: turning on the spot is motion too).
// The IMU alone cannot tell rest from slow or constant-velocity motion (no
// acceleration either way); the image test is what keeps the detector quiet
// in slow motion: a camera moving at v for image_span_s shifts a feature at
// depth Z by about focal v T / Z pixels, so with the defaults (3 px over 1 s,
// focal 460 px) any motion faster than ~3 cm/s at 5 m median depth is seen
// as motion. Without an image verdict (too few features shared, or the
// frames do not span image_span_s yet) the estimator also demands an
// estimated speed below max_speed_without_image_m_s.

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "estimator/initialization_options.h"
#include "estimator/static_initializer.h"
#include "geometry/feature_observation.h"
#include "preintegration/imu_types.h"

namespace vio {

struct StillnessReport {
  bool imu_still = false;
  double acc_block_std = 0.0;  // largest axis [m/s^2]
  double gyr_block_std = 0.0;  // largest axis [rad/s]
  // The image verdict exists when enough features are shared with a frame
  // at least image_span_s old.
  bool image_verdict = false;
  bool image_still = false;   // verdict and disparity <= max_disparity_px
  double disparity_px = 0.0;  // median over the shared features [px]
  int common_features = 0;
  bool newest_has_features = false;  // camera-0 observations in the newest

  // Still by both witnesses, or by the IMU with no image evidence against
  // it: the images said still, or there is no image verdict and the caller's
  // estimated speed [m/s] is below `max_speed`.
  bool Still(double estimated_speed, double max_speed) const {
    if (!imu_still) return false;
    if (image_verdict) return image_still;
    return estimated_speed <= max_speed;
  }
};

class ZeroVelocityDetector {
 public:
  ZeroVelocityDetector(const ZeroVelocityOptions& options, double focal_px)
      : options_(options), focal_px_(focal_px) {}

  // Appends a finite IMU sample (the caller filters bad ones); samples older
  // than imu_window_s before it are dropped.
  void AddImu(const ImuSample& sample);

  // Appends a frame's observations (camera-0 xy used); frames older than the
  // one image_span_s before it are dropped.
  void AddFrame(int64_t t_ns,
                const std::vector<FeatureObservation>& observations);

  // The verdict for the newest IMU sample and frame.
  StillnessReport Check() const;

  void Clear();

 private:
  struct Frame {
    int64_t t_ns = 0;
    std::map<int64_t, Eigen::Vector2d> xy;
  };

  ZeroVelocityOptions options_;
  double focal_px_;
  std::deque<ImuSample> imu_;
  std::deque<Frame> frames_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_ZERO_VELOCITY_H_
