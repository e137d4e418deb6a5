#include "dataset/sim_folder.h"

#include <charconv>
#include <filesystem>
#include <fstream>

#include "dataset/csv.h"
#include "dataset/euroc_reader.h"
#include "dataset/features_csv.h"
#include "dataset/trajectory_io.h"

namespace vio {
namespace {

namespace fs = std::filesystem;

std::ofstream Create(const std::string& path) {
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  std::ofstream out(path);
  if (!out) throw DatasetError(path + ": cannot open the file for writing");
  return out;
}

void Close(std::ofstream& out, const std::string& path) {
  out.close();
  if (!out) throw DatasetError(path + ": write failed");
}

// The shortest text that reads back as the same double (std::to_chars): exact
// and deterministic.
std::string Numbers(const double* values, int n, const char* separator) {
  std::string text;
  char buffer[32];
  for (int i = 0; i < n; ++i) {
    const std::to_chars_result r =
        std::to_chars(buffer, buffer + sizeof(buffer), values[i]);
    if (i > 0) text += separator;
    text.append(buffer, r.ptr);
  }
  return text;
}

void WriteImu(const Simulation& sim, const std::string& mav0) {
  const std::string path = JoinPath(mav0, "imu0/data.csv");
  std::ofstream out = Create(path);
  out << "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],"
         "w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],"
         "a_RS_S_z [m s^-2]\n";
  for (const ImuSample& s : sim.imu) {
    const double values[6] = {s.gyr.x(), s.gyr.y(), s.gyr.z(),
                              s.acc.x(), s.acc.y(), s.acc.z()};
    out << s.t_ns << ',' << Numbers(values, 6, ",") << '\n';
  }
  Close(out, path);

  const std::string yaml = JoinPath(mav0, "imu0/sensor.yaml");
  std::ofstream y = Create(yaml);
  const ImuNoise& n = sim.options.imu.noise;
  y << "%YAML:1.0\n"
       "sensor_type: imu\n"
       "comment: tcvio simulated IMU (vio_sim)\n"
       "T_BS:\n  cols: 4\n  rows: 4\n"
       "  data: [1.0, 0.0, 0.0, 0.0,\n"
       "         0.0, 1.0, 0.0, 0.0,\n"
       "         0.0, 0.0, 1.0, 0.0,\n"
       "         0.0, 0.0, 0.0, 1.0]\n";
  y << "rate_hz: " << Numbers(&sim.options.imu.rate_hz, 1, "") << "\n";
  y << "gyroscope_noise_density: " << Numbers(&n.gyroscope_noise_density, 1, "")
    << "  # [rad/s/sqrt(Hz)]\n"
    << "gyroscope_random_walk: " << Numbers(&n.gyroscope_random_walk, 1, "")
    << "  # [rad/s^2/sqrt(Hz)]\n"
    << "accelerometer_noise_density: "
    << Numbers(&n.accelerometer_noise_density, 1, "")
    << "  # [m/s^2/sqrt(Hz)]\n"
    << "accelerometer_random_walk: "
    << Numbers(&n.accelerometer_random_walk, 1, "") << "  # [m/s^3/sqrt(Hz)]\n";
  Close(y, yaml);
}

void WriteCameraYaml(const CameraCalibration& c, int index, bool features,
                     const std::string& path) {
  std::ofstream y = Create(path);
  Eigen::Matrix4d T_b_c = Eigen::Matrix4d::Identity();
  T_b_c.topLeftCorner<3, 3>() = c.q_b_c.toRotationMatrix();
  T_b_c.topRightCorner<3, 1>() = c.t_b_c;
  y << "%YAML:1.0\n"
       "sensor_type: camera\n"
       "comment: tcvio simulated cam"
    << index
    << (features ? " (vio_sim; observations in features.csv, no images)\n"
                 : " (vio_sim --render; rendered images in data/)\n");
  y << "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  for (int r = 0; r < 4; ++r) {
    const double row[4] = {T_b_c(r, 0), T_b_c(r, 1), T_b_c(r, 2), T_b_c(r, 3)};
    y << (r == 0 ? "" : ",\n         ") << Numbers(row, 4, ", ");
  }
  y << "]\n";
  const double rate = c.rate_hz;
  const double intrinsics[4] = {c.fx, c.fy, c.cx, c.cy};
  const Eigen::Vector4d& d = c.distortion_coefficients;
  y << "rate_hz: " << Numbers(&rate, 1, "") << "\n"
    << "resolution: [" << c.width << ", " << c.height << "]\n"
    << "camera_model: pinhole\n"
    << "intrinsics: [" << Numbers(intrinsics, 4, ", ")
    << "]  # fu, fv, cu, cv\n"
    << "distortion_model: " << DistortionModelName(c.distortion) << "\n"
    << "distortion_coefficients: [" << Numbers(d.data(), 4, ", ") << "]\n";
  Close(y, path);
}

}  // namespace

void WriteSimulationFolder(const Simulation& sim, const std::string& folder,
                           const SimulationFolderOptions& options) {
  const std::string mav0 = JoinPath(folder, "mav0");
  std::error_code ec;
  if (fs::exists(mav0, ec)) {
    throw DatasetError(mav0 +
                       ": already exists; remove it or choose another folder");
  }
  WriteImu(sim, mav0);
  const int cameras = sim.options.camera.stereo ? 2 : 1;
  for (int i = 0; i < cameras; ++i) {
    const std::string cam = JoinPath(mav0, "cam" + std::to_string(i));
    fs::create_directories(cam, ec);
    if (options.write_features) {
      WriteFeaturesCsv(JoinPath(cam, "features.csv"), sim.frames, i);
    }
    WriteCameraYaml(i == 0 ? sim.options.camera.cam0 : sim.options.camera.cam1,
                    i, options.write_features, JoinPath(cam, "sensor.yaml"));
  }
  const std::string gt = JoinPath(mav0, "state_groundtruth_estimate0");
  fs::create_directories(gt, ec);
  WriteStateCsv(JoinPath(gt, "data.csv"), sim.ground_truth);
}

Simulation SimulateToFolder(const SimulatorOptions& options,
                            const std::string& folder) {
  Simulation sim = Simulate(options);
  WriteSimulationFolder(sim, folder);
  return sim;
}

}  // namespace vio
