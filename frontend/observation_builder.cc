#include "frontend/observation_builder.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace vio {

ObservationBuilder::ObservationBuilder(std::vector<CameraModel> cameras)
    : cameras_(std::move(cameras)), previous_(cameras_.size()) {}

void ObservationBuilder::Process(FeatureFrame* frame) {
  if (started_ && frame->t_ns <= last_t_ns_) {
    throw std::invalid_argument(
        "ObservationBuilder: frame stamp " + std::to_string(frame->t_ns) +
        " is not after the previous one (" + std::to_string(last_t_ns_) + ")");
  }
  started_ = true;
  last_t_ns_ = frame->t_ns;
  ++summary_.frames;

  std::vector<PreviousFrame> current(cameras_.size());
  std::vector<FeatureObservation> kept;
  kept.reserve(frame->observations.size());
  for (FeatureObservation& obs : frame->observations) {
    if (obs.camera < 0 || obs.camera >= static_cast<int>(cameras_.size())) {
      ++summary_.unknown_camera;
      continue;
    }
    // No camera sees there: a corrupted line, which undistortion would
    // otherwise turn into a plausible-looking bearing.
    if (!cameras_[obs.camera].InImage(obs.uv)) {
      ++summary_.outside_image;
      continue;
    }
    if (!cameras_[obs.camera].PixelToNormalized(obs.uv, &obs.xy)) {
      ++summary_.failed_undistortion;
      continue;
    }
    obs.velocity.setZero();
    const PreviousFrame& previous = previous_[obs.camera];
    if (previous.valid) {
      const auto it = previous.xy_by_id.find(obs.feature_id);
      if (it != previous.xy_by_id.end()) {
        // Stamps are differenced as integers first, so no precision is lost.
        const double dt =
            static_cast<double>(frame->t_ns - previous.t_ns) * 1e-9;
        obs.velocity = (obs.xy - it->second) / dt;
      }
    }
    PreviousFrame& next = current[obs.camera];
    next.valid = true;
    next.t_ns = frame->t_ns;
    next.xy_by_id[obs.feature_id] = obs.xy;
    kept.push_back(obs);
  }
  // A camera absent from this frame has no observation in it: its next frame
  // starts every track afresh, as a tracker that lost the frame would.
  for (size_t i = 0; i < current.size(); ++i) {
    current[i].valid = true;
    current[i].t_ns = frame->t_ns;
  }
  previous_ = std::move(current);
  summary_.observations += static_cast<int64_t>(kept.size());
  frame->observations = std::move(kept);
}

}  // namespace vio
