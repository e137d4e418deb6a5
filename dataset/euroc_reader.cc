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

EurocCamera ReadCamera(const std::string& folder, int index, bool keep_images) {
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
    ImageListStream stream(list, JoinPath(folder, "data"));
    ImageEntry entry;
    while (stream.Next(&entry)) {
      if (camera.image_count++ == 0) camera.first_image_ns = entry.t_ns;
      if (keep_images) camera.images.push_back(std::move(entry));
    }
    camera.missing_images = stream.missing();
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
  if (data.imu_count > 0) start = data.imu_first_ns;
  for (const EurocCamera& camera : data.cameras) {
    if (camera.image_count > 0) {
      start = std::min(start, camera.first_image_ns);
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
  ImuCsvStream stream(path, report);
  std::vector<ImuSample> samples;
  ImuSample s;
  while (stream.Next(&s)) samples.push_back(s);
  return samples;
}

std::vector<ImageEntry> ReadEurocImageList(const std::string& path,
                                           const std::string& image_folder,
                                           int* missing) {
  ImageListStream stream(path, image_folder);
  std::vector<ImageEntry> images;
  ImageEntry entry;
  while (stream.Next(&entry)) images.push_back(std::move(entry));
  *missing = stream.missing();
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
    data.imu_path = JoinPath(mav0, "imu0/data.csv");
    ImuCsvStream stream(data.imu_path,
                        options.strict ? nullptr : &data.imu_stamps);
    ImuSample s;
    while (stream.Next(&s)) {
      if (data.imu_count++ == 0) data.imu_first_ns = s.t_ns;
      if (options.keep_imu) data.imu.push_back(s);
    }
  }
  for (int n = 0;; ++n) {
    const std::string camera = JoinPath(mav0, "cam" + std::to_string(n));
    if (!IsFolder(camera)) break;
    data.cameras.push_back(ReadCamera(camera, n, options.keep_image_lists));
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
