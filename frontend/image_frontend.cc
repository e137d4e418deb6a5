#include "frontend/image_frontend.h"

#include <stdexcept>
#include <string>

namespace vio {
namespace {

const FrontendOptions& Validated(const FrontendOptions& options) {
  std::string message;
  if (!options.Validate(&message)) {
    throw std::invalid_argument("FrontendOptions: " + message);
  }
  return options;
}

}  // namespace

ImageFrontend::ImageFrontend(const CameraModel& cam0, const CameraModel* cam1,
                             const FrontendOptions& options)
    : tracker_(cam0, Validated(options).tracker, 0) {
  if (options.stereo) {
    if (cam1 == nullptr) {
      throw std::invalid_argument(
          "ImageFrontend: stereo needs the cam1 calibration");
    }
    matcher_ =
        std::make_unique<StereoMatcher>(cam0, *cam1, options.stereo_matcher);
  }
}

FeatureFrame ImageFrontend::Process(int64_t t_ns, const cv::Mat& left,
                                    const cv::Mat& right) {
  FeatureFrame frame;
  frame.t_ns = t_ns;
  frame.observations = tracker_.Track(left);
  stats_ = FrontendStats();
  stats_.tracker = tracker_.stats();
  if (matcher_ && !right.empty()) {
    // The right image must look like the left one did to the tracker.
    const std::vector<FeatureObservation> matches =
        matcher_->Match(tracker_.image(), tracker_.Preprocess(right),
                        frame.observations, &stats_.stereo);
    frame.observations.insert(frame.observations.end(), matches.begin(),
                              matches.end());
    stats_.stereo_matched = true;
  }
  return frame;
}

}  // namespace vio
