#ifndef VIO_TEST_TESTING_EUROC_V1_01_H_
#define VIO_TEST_TESTING_EUROC_V1_01_H_

// Access to the real EuRoC excerpt ../shared/data/euroc_V1_01_first5s for the
// frontend tests: its two camera calibrations (read from its sensor.yaml
// files through config/) and its images.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>
#include <vector>

#include "config/euroc_sensor.h"
#include "geometry/camera_model.h"

namespace vio {
namespace testing {

inline std::string V101Dir() {
  return std::string(VIO_SHARED_DIR) + "/data/euroc_V1_01_first5s/mav0";
}

inline CameraCalibration V101Cam0() {
  return ReadEurocCameraYaml(V101Dir() + "/cam0/sensor.yaml");
}

inline CameraCalibration V101Cam1() {
  return ReadEurocCameraYaml(V101Dir() + "/cam1/sensor.yaml");
}

// The (stamp, file) rows of mav0/cam<camera>/data.csv, header skipped.
inline std::vector<std::pair<int64_t, std::string>> V101ImageList(int camera) {
  std::vector<std::pair<int64_t, std::string>> rows;
  std::ifstream in(V101Dir() + "/cam" + std::to_string(camera) + "/data.csv");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t comma = line.find(',');
    std::string file = line.substr(comma + 1);
    while (!file.empty() && (file.back() == '\r' || file.back() == ' ')) {
      file.pop_back();
    }
    rows.emplace_back(std::stoll(line.substr(0, comma)), file);
  }
  return rows;
}

// Frame `index` of cam<camera> as 8-bit grey; empty when it does not exist.
inline cv::Mat V101Image(int camera, size_t index) {
  const auto rows = V101ImageList(camera);
  if (index >= rows.size()) return cv::Mat();
  return cv::imread(V101Dir() + "/cam" + std::to_string(camera) + "/data/" +
                        rows[index].second,
                    cv::IMREAD_GRAYSCALE);
}

// A sequence folder at `folder` that is the excerpt with cam0's list cut to
// its first `cam0_images` rows (cam1, the IMU and the ground truth whole): a
// shorter replay of real data. Everything but cam0/data.csv is a symbolic
// link to the excerpt's own files.
inline void WriteV101Excerpt(const std::string& folder, int cam0_images) {
  namespace fs = std::filesystem;
  const fs::path src(V101Dir());
  const fs::path mav0 = fs::path(folder) / "mav0";
  fs::create_directories(mav0 / "cam0");
  for (const char* entry : {"imu0", "cam1", "state_groundtruth_estimate0"}) {
    fs::create_directory_symlink(src / entry, mav0 / entry);
  }
  fs::create_directory_symlink(src / "cam0/data", mav0 / "cam0/data");
  fs::create_symlink(src / "cam0/sensor.yaml", mav0 / "cam0/sensor.yaml");
  std::ofstream csv(mav0 / "cam0/data.csv");
  csv << "#timestamp [ns],filename\n";
  const auto rows = V101ImageList(0);
  for (int k = 0; k < cam0_images && k < static_cast<int>(rows.size()); ++k) {
    csv << rows[k].first << "," << rows[k].second << "\n";
  }
}

}  // namespace testing
}  // namespace vio

#endif  // VIO_TEST_TESTING_EUROC_V1_01_H_
