#include "dataset/euroc_reader.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <utility>

#include "dataset/csv.h"
#include "dataset/features_csv.h"
#include "dataset/trajectory_io.h"

namespace vio {
namespace {

namespace fs = std::filesystem;

bool IsFile(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

bool IsFolder(const std::string& path) {
  std::error_code ec;
  return fs::is_directory(path, ec);
}

void RequireFile(const std::string& path) {
  if (!IsFile(path)) throw DatasetError(path + ": no such file");
}

void RequireIncreasing(const CsvReader& csv, bool first, int64_t previous,
                       int64_t t_ns) {
  if (first) return;
  if (t_ns == previous) {
    csv.Fail("timestamp " + std::to_string(t_ns) + " is repeated");
  }
  if (t_ns < previous) {
    csv.Fail("timestamp " + std::to_string(t_ns) +
             " is before the previous one (" + std::to_string(previous) + ")");
  }
}

void RequireFieldCount(const CsvReader& csv, size_t n, const char* what) {
  csv.ExpectAtLeast(n);
  if (csv.size() != n) {
    csv.Fail("expected " + std::to_string(n) + " fields (" + what + "), got " +
             std::to_string(csv.size()));
  }
}

EurocCamera ReadCamera(const std::string& folder, int index) {
  EurocCamera camera;
  camera.index = index;
  camera.folder = folder;
  const std::string list = JoinPath(folder, "data.csv");
  const std::string features = JoinPath(folder, "features.csv");
  camera.has_images = IsFile(list);
  camera.has_features = IsFile(features);
  if (!camera.has_images && !camera.has_features) {
    throw DatasetError(folder +
                       ": holds neither data.csv (images) nor features.csv");
  }
  if (camera.has_images) {
    camera.images = ReadEurocImageList(list, JoinPath(folder, "data"),
                                       &camera.missing_images);
  }
  if (camera.has_features) {
    camera.feature_frames = ReadFeaturesCsv(features, index);
  }
  return camera;
}

// gt_first_ns: the ground truth's first stamp when it is not kept (the
// largest int64_t otherwise).
int64_t EarliestStamp(const EurocData& data, int64_t gt_first_ns) {
  int64_t start = gt_first_ns;
  if (!data.imu.empty()) start = data.imu.front().t_ns;
  for (const EurocCamera& camera : data.cameras) {
    if (!camera.images.empty()) {
      start = std::min(start, camera.images.front().t_ns);
    }
    if (!camera.feature_frames.empty()) {
      start = std::min(start, camera.feature_frames.front().t_ns);
    }
  }
  if (!data.ground_truth.empty()) {
    start = std::min(start, data.ground_truth.front().t_ns);
  }
  return start == std::numeric_limits<int64_t>::max() ? 0 : start;
}

}  // namespace

std::string JoinPath(const std::string& folder, const std::string& name) {
  return (fs::path(folder) / name).string();
}

std::vector<ImuSample> ReadEurocImu(const std::string& path,
                                    ImuStampReport* report) {
  RequireFile(path);
  CsvReader csv(path);
  std::vector<ImuLine> lines;
  while (csv.Next()) {
    RequireFieldCount(csv, 7, "timestamp, 3 angular rates, 3 accelerations");
    ImuSample s;
    s.t_ns = csv.Int64(0);
    if (report == nullptr) {
      RequireIncreasing(csv, lines.empty(),
                        lines.empty() ? 0 : lines.back().sample.t_ns, s.t_ns);
    }
    s.gyr = {csv.Double(1), csv.Double(2), csv.Double(3)};
    s.acc = {csv.Double(4), csv.Double(5), csv.Double(6)};
    lines.push_back({s, csv.line()});
  }
  if (lines.empty()) throw DatasetError(path + ": holds no IMU sample");
  if (report != nullptr) return FilterImuStamps(lines, report);
  std::vector<ImuSample> samples;
  samples.reserve(lines.size());
  for (const ImuLine& l : lines) samples.push_back(l.sample);
  return samples;
}

std::vector<ImageEntry> ReadEurocImageList(const std::string& path,
                                           const std::string& image_folder,
                                           int* missing) {
  RequireFile(path);
  CsvReader csv(path);
  std::vector<ImageEntry> images;
  *missing = 0;
  bool first = true;
  int64_t previous = 0;
  while (csv.Next()) {
    RequireFieldCount(csv, 2, "timestamp, filename");
    const int64_t t_ns = csv.Int64(0);
    RequireIncreasing(csv, first, previous, t_ns);
    first = false;
    previous = t_ns;
    const std::string& name = csv.String(1);
    if (name.empty()) csv.Fail("the filename is empty");
    const std::string image = JoinPath(image_folder, name);
    if (IsFile(image)) {
      images.push_back(ImageEntry{t_ns, image});
    } else {
      ++*missing;
    }
  }
  return images;
}

std::vector<FeatureFrame> MergedFeatureFrames(const EurocData& data) {
  std::map<int64_t, FeatureFrame> by_stamp;
  for (const EurocCamera& camera : data.cameras) {
    for (const FeatureFrame& frame : camera.feature_frames) {
      FeatureFrame& merged = by_stamp[frame.t_ns];
      merged.t_ns = frame.t_ns;
      merged.observations.insert(merged.observations.end(),
                                 frame.observations.begin(),
                                 frame.observations.end());
    }
  }
  std::vector<FeatureFrame> frames;
  frames.reserve(by_stamp.size());
  for (auto& [t_ns, frame] : by_stamp) frames.push_back(std::move(frame));
  return frames;
}

EurocData ReadEurocFolder(const std::string& folder,
                          const EurocReadOptions& options) {
  if (!IsFolder(folder)) throw DatasetError(folder + ": no such folder");
  const std::string mav0 = JoinPath(folder, "mav0");
  if (!IsFolder(mav0)) {
    throw DatasetError(folder +
                       ": not a EuRoC sequence folder (no mav0/ inside)");
  }
  EurocData data;
  data.folder = folder;
  // Without imu0/ at all the caller may accept the folder; an imu0/ without
  // data.csv is always an error.
  data.has_imu = options.require_imu || IsFolder(JoinPath(mav0, "imu0"));
  if (data.has_imu) {
    data.imu = ReadEurocImu(JoinPath(mav0, "imu0/data.csv"),
                            options.strict ? nullptr : &data.imu_stamps);
  }
  for (int n = 0;; ++n) {
    const std::string camera = JoinPath(mav0, "cam" + std::to_string(n));
    if (!IsFolder(camera)) break;
    data.cameras.push_back(ReadCamera(camera, n));
  }
  const std::string gt = JoinPath(mav0, "state_groundtruth_estimate0/data.csv");
  int64_t gt_first_ns = std::numeric_limits<int64_t>::max();
  if (IsFile(gt)) {
    data.ground_truth_path = gt;
    if (options.keep_ground_truth) {
      data.ground_truth = ReadEurocGroundTruth(gt);
    } else {
      ForEachEurocGroundTruth(gt, [&](const StampedState& s) {
        gt_first_ns = std::min(gt_first_ns, s.t_ns);
      });
    }
  }
  data.start_ns = EarliestStamp(data, gt_first_ns);
  return data;
}

}  // namespace vio
