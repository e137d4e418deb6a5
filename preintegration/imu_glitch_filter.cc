#include "preintegration/imu_glitch_filter.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace vio {
namespace {

bool Within(const Eigen::Vector3d& v, double range) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() <= range;
}

}  // namespace

bool ImuRange::Validate(std::string* message) const {
  const struct {
    const char* name;
    double value;
  } fields[] = {{"accelerometer_range", accelerometer_range},
                {"gyroscope_range", gyroscope_range}};
  for (const auto& f : fields) {
    if (!(std::isfinite(f.value) && f.value > 0.0)) {
      std::ostringstream out;
      out << f.name << " must be > 0 (got " << f.value << ")";
      *message = out.str();
      return false;
    }
  }
  return true;
}

bool ImuRange::Contains(const ImuSample& sample) const {
  return Within(sample.acc, accelerometer_range) &&
         Within(sample.gyr, gyroscope_range);
}

ImuGlitchFilter::ImuGlitchFilter(const ImuRange& range, double max_replaced_s)
    : range_(range), max_replaced_ns_(std::llround(max_replaced_s * 1e9)) {
  std::string message;
  if (!range.Validate(&message)) {
    throw std::invalid_argument("ImuGlitchFilter: " + message);
  }
  if (!(std::isfinite(max_replaced_s) && max_replaced_s > 0.0)) {
    throw std::invalid_argument("ImuGlitchFilter: max_replaced_s must be > 0");
  }
}

ImuScreening ImuGlitchFilter::Add(const ImuSample& sample,
                                  std::vector<ImuSample>* stream) {
  if (range_.Contains(sample)) {
    // Replaced samples are those after the last good one, at the back.
    for (auto it = stream->rbegin();
         have_good_ && it != stream->rend() && it->t_ns > last_good_.t_ns;
         ++it) {
      const double u = static_cast<double>(it->t_ns - last_good_.t_ns) /
                       static_cast<double>(sample.t_ns - last_good_.t_ns);
      it->acc = (1.0 - u) * last_good_.acc + u * sample.acc;
      it->gyr = (1.0 - u) * last_good_.gyr + u * sample.gyr;
    }
    stream->push_back(sample);
    last_good_ = sample;
    have_good_ = true;
    return ImuScreening::kAccepted;
  }
  if (!have_good_ || sample.t_ns - last_good_.t_ns > max_replaced_ns_) {
    return ImuScreening::kDropped;
  }
  ImuSample held = last_good_;
  held.t_ns = sample.t_ns;
  stream->push_back(held);
  return ImuScreening::kReplaced;
}

}  // namespace vio
