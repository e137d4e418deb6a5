#include "config/recorded_flight.h"

#include <filesystem>

#include "config/euroc_sensor.h"
#include "dataset/csv.h"
#include "dataset/euroc_reader.h"
#include "dataset/trajectory_io.h"

namespace vio {
namespace {

namespace fs = std::filesystem;

bool IsFile(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

// The ground truth as states; a TUM file gives poses (zero v and biases).
std::vector<StampedState> ReadGroundTruth(const std::string& path,
                                          bool* has_biases) {
  CsvReader probe(path);
  if (!probe.Next()) throw DatasetError(path + ": holds no data line");
  *has_biases = probe.size() >= 17;
  if (*has_biases) return ReadEurocGroundTruth(path);
  std::vector<StampedState> states;
  for (const StampedPose& p : ReadTrajectory(path)) {
    StampedState s;
    s.t_ns = p.t_ns;
    s.p_w_b = p.p_w_b;
    s.q_w_b = p.q_w_b;
    states.push_back(s);
  }
  return states;
}

// The first column (t [ns]) of a camera list; stamps must increase.
std::vector<int64_t> ReadStamps(const std::string& path) {
  CsvReader csv(path);
  std::vector<int64_t> stamps;
  while (csv.Next()) {
    const int64_t t = csv.Int64(0);
    if (!stamps.empty() && t <= stamps.back()) {
      csv.Fail("timestamp " + std::to_string(t) +
               " is not after the previous one (" +
               std::to_string(stamps.back()) + ")");
    }
    stamps.push_back(t);
  }
  return stamps;
}

}  // namespace

RecordedFlight LoadRecordedFlight(const std::string& folder,
                                  const std::string& ground_truth_path) {
  RecordedFlight flight;
  flight.folder = folder;
  const std::string mav0 = JoinPath(folder, "mav0");
  std::error_code ec;
  if (!fs::is_directory(mav0, ec)) {
    throw DatasetError(mav0 + ": no such folder");
  }
  flight.ground_truth_path = ground_truth_path;
  if (flight.ground_truth_path.empty()) {
    for (const char* name :
         {"state_groundtruth_estimate0/data.csv", "ground_truth.tum"}) {
      if (IsFile(JoinPath(mav0, name))) {
        flight.ground_truth_path = JoinPath(mav0, name);
        break;
      }
    }
    if (flight.ground_truth_path.empty()) {
      throw DatasetError(mav0 +
                         ": no ground truth (state_groundtruth_estimate0/"
                         "data.csv or ground_truth.tum); give one");
    }
  }
  flight.ground_truth =
      ReadGroundTruth(flight.ground_truth_path, &flight.has_biases);
  const std::string imu = JoinPath(mav0, "imu0/data.csv");
  if (IsFile(imu)) flight.imu = ReadEurocImu(imu);
  const std::string imu_yaml = JoinPath(mav0, "imu0/sensor.yaml");
  if (IsFile(imu_yaml)) {
    flight.imu_noise = ReadEurocImuYaml(imu_yaml).noise;
    flight.has_imu_noise = true;
  }
  for (int c = 0; c < 2; ++c) {
    const std::string yaml =
        JoinPath(mav0, "cam" + std::to_string(c) + "/sensor.yaml");
    if (!IsFile(yaml)) break;
    flight.cameras.push_back(ReadEurocCameraYaml(yaml));
  }
  for (const char* name : {"cam0/data.csv", "cam0_timestamps_only.csv"}) {
    const std::string path = JoinPath(mav0, name);
    if (IsFile(path)) {
      flight.frame_stamps_ns = ReadStamps(path);
      flight.frame_stamps_path = path;
      break;
    }
  }
  return flight;
}

}  // namespace vio
