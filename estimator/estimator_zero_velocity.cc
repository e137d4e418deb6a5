// The estimator's zero-velocity handling (estimator/zero_velocity.h for the
// detection, factors/zero_motion_factor.h for the constraint).

#include <memory>

#include "estimator/estimator.h"
#include "factors/zero_motion_factor.h"

namespace vio {

bool Estimator::StillNow(double speed_m_s) const {
  // Without an image verdict, the speed of the last estimate decides with
  // the IMU (a constant-velocity flight over a blank wall is not rest).
  const ZeroVelocityOptions& z = options_.zero_velocity;
  return z.enabled &&
         zero_velocity_.Check().Still(speed_m_s, z.max_speed_without_image_m_s);
}

void Estimator::MarkStillness(WindowFrame* newest) {
  // Across an IMU gap (a visual link, no preintegration) the IMU window
  // holds only samples from before the gap: no verdict.
  const bool still = newest->imu && StillNow(last_output_.v_w.norm());
  // Still over the whole interval: at both of its ends. (A longer interval,
  // merged when the frame between leaves, keeps the link only when both of
  // its parts had it: Estimator::DropSecondNewest.)
  newest->still_link = still && newest_still_;
  // The first still frame after motion is kept as a keyframe: the frames
  // after it merge into one interval starting there, and a merged interval
  // is held only when all of it was still, so an interval reaching back
  // into the motion (or to an in-motion start) would never be held.
  if (still && !newest_still_) newest->keyframe = true;
  newest_still_ = still;
}

void Estimator::AddZeroVelocityFactors(WindowProblem* problem) const {
  const ZeroVelocityOptions& z = options_.zero_velocity;
  const auto& frames = window_.frames;
  for (size_t k = 1; k < frames.size(); ++k) {
    WindowFrame& i = *frames[k - 1];
    WindowFrame& j = *frames[k];
    if (!j.still_link) continue;
    problem->AddFrameLink(
        std::make_unique<ZeroMotionFactor>(
            z.sigma_position_m, z.sigma_rotation_rad, z.sigma_velocity_m_s),
        {i.pose.data(), j.pose.data(), j.speed_bias.data()}, i.id);
  }
}

}  // namespace vio
