#include "dataset/fault_injection.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace vio {
namespace {

// Index of the first element whose stamp is at or after first + t_s.
template <typename T>
size_t FirstAtOrAfter(const std::vector<T>& items, double t_s) {
  if (items.empty()) throw std::invalid_argument("fault: no data");
  const int64_t t_ns = items.front().t_ns + std::llround(t_s * 1e9);
  const auto it =
      std::lower_bound(items.begin(), items.end(), t_ns,
                       [](const T& item, int64_t t) { return item.t_ns < t; });
  if (it == items.end()) {
    throw std::invalid_argument("fault at " + std::to_string(t_s) +
                                " s: beyond the data");
  }
  return static_cast<size_t>(it - items.begin());
}

std::string CsvLine(const ImuSample& s) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer),
                "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g",
                static_cast<long long>(s.t_ns), s.gyr.x(), s.gyr.y(), s.gyr.z(),
                s.acc.x(), s.acc.y(), s.acc.z());
  return buffer;
}

bool IsDataLine(const std::string& line) {
  const size_t first = line.find_first_not_of(" \t\r");
  return first != std::string::npos && line[first] != '#';
}

}  // namespace

std::string ImuFault::Describe() const {
  char buffer[160];
  switch (kind) {
    case ImuFaultKind::kDrop:
      std::snprintf(buffer, sizeof(buffer), "%d IMU samples dropped at %.3f s",
                    count, t_s);
      break;
    case ImuFaultKind::kGyroValue:
      std::snprintf(buffer, sizeof(buffer),
                    "gyroscope x = %g rad/s in %d sample(s) at %.3f s", value,
                    count, t_s);
      break;
    case ImuFaultKind::kAccelValue:
      std::snprintf(buffer, sizeof(buffer),
                    "accelerometer x = %g m/s^2 in %d sample(s) at %.3f s",
                    value, count, t_s);
      break;
    case ImuFaultKind::kRepeat:
      std::snprintf(buffer, sizeof(buffer), "IMU line repeated at %.3f s", t_s);
      break;
    case ImuFaultKind::kBackwards:
      std::snprintf(buffer, sizeof(buffer),
                    "IMU sample at %.3f s moved %d places later", t_s, count);
      break;
  }
  return buffer;
}

namespace {

// The first sample the fault touches, after checking that it fits.
size_t FaultStart(const std::vector<ImuSample>& imu, const ImuFault& fault) {
  if (fault.count < 1) throw std::invalid_argument("fault: count < 1");
  const size_t k = FirstAtOrAfter(imu, fault.t_s);
  // Samples the fault needs from k on (kBackwards: the sample and count more).
  size_t needed = static_cast<size_t>(fault.count);
  if (fault.kind == ImuFaultKind::kRepeat) needed = 1;
  if (fault.kind == ImuFaultKind::kBackwards) needed += 1;
  if (k + needed > imu.size()) {
    throw std::invalid_argument("fault: " + fault.Describe() +
                                " runs past the data");
  }
  return k;
}

// Applies the fault to any sequence of per-sample items (samples or lines);
// `set` writes a value fault into item i.
template <typename T, typename Set>
void Apply(const ImuFault& fault, size_t k, std::vector<T>* items, Set set) {
  const size_t n = static_cast<size_t>(fault.count);
  switch (fault.kind) {
    case ImuFaultKind::kDrop:
      items->erase(items->begin() + k, items->begin() + k + n);
      break;
    case ImuFaultKind::kGyroValue:
    case ImuFaultKind::kAccelValue:
      for (size_t i = k; i < k + n; ++i) set(&(*items)[i]);
      break;
    case ImuFaultKind::kRepeat:
      items->insert(items->begin() + k + 1, (*items)[k]);
      break;
    case ImuFaultKind::kBackwards:
      std::rotate(items->begin() + k, items->begin() + k + 1,
                  items->begin() + k + n + 1);
      break;
  }
}

void SetValue(const ImuFault& fault, ImuSample* s) {
  if (fault.kind == ImuFaultKind::kGyroValue) s->gyr.x() = fault.value;
  if (fault.kind == ImuFaultKind::kAccelValue) s->acc.x() = fault.value;
}

}  // namespace

std::vector<ImuSample> WithImuFault(std::vector<ImuSample> imu,
                                    const ImuFault& fault) {
  const size_t k = FaultStart(imu, fault);
  Apply(fault, k, &imu, [&](ImuSample* s) { SetValue(fault, s); });
  return imu;
}

std::string WithImuFaultInCsv(const std::string& csv_text,
                              const ImuFault& fault) {
  // The data lines are faulted as lines, so that every line the fault does
  // not touch keeps its text (as an edit with sed would).
  std::vector<std::string> lines;
  std::istringstream in(csv_text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  struct DataLine {
    ImuSample sample;
    std::string text;
  };
  std::vector<DataLine> data;
  std::vector<std::string> before, after;  // non-data lines around the data
  for (size_t i = 0; i < lines.size(); ++i) {
    if (!IsDataLine(lines[i])) {
      (data.empty() ? before : after).push_back(lines[i]);
      continue;
    }
    ImuSample& s = data.emplace_back().sample;
    data.back().text = lines[i];
    long long t = 0;
    if (std::sscanf(lines[i].c_str(), "%lld,%lf,%lf,%lf,%lf,%lf,%lf", &t,
                    &s.gyr.x(), &s.gyr.y(), &s.gyr.z(), &s.acc.x(), &s.acc.y(),
                    &s.acc.z()) != 7) {
      throw std::invalid_argument("fault: line " + std::to_string(i + 1) +
                                  " is not an IMU sample");
    }
    s.t_ns = t;
  }
  std::vector<ImuSample> samples;
  for (const DataLine& d : data) samples.push_back(d.sample);
  const size_t k = FaultStart(samples, fault);
  Apply(fault, k, &data, [&](DataLine* d) {
    SetValue(fault, &d->sample);
    d->text = CsvLine(d->sample);
  });
  std::string out;
  for (const std::string& l : before) out += l + "\n";
  for (const DataLine& d : data) out += d.text + "\n";
  for (const std::string& l : after) out += l + "\n";
  return out;
}

void SetObservationPixels(std::vector<FeatureFrame>* frames, double t_s,
                          int count, const Eigen::Vector2d& uv) {
  const size_t k = FirstAtOrAfter(*frames, t_s);
  std::vector<FeatureObservation>& obs = (*frames)[k].observations;
  const size_t n =
      std::min(obs.size(), static_cast<size_t>(std::max(0, count)));
  for (size_t i = 0; i < n; ++i) obs[i].uv = uv;
}

}  // namespace vio
