#include "config/simulator_config.h"

#include <charconv>
#include <sstream>
#include <vector>

#include "config/imu_config.h"
#include "config/yaml_reader.h"

namespace vio {
namespace {

Eigen::Vector3d Vector3(const YamlNode& node, const std::string& key) {
  const std::vector<double> v = node.GetVector(key, 3);
  return {v[0], v[1], v[2]};
}

void ReadMotion(const YamlNode& m, SimMotionOptions* o) {
  const std::string shape = m.Get<std::string>("shape");
  if (!ParseSimShape(shape, &o->shape)) {
    throw ConfigError(m.Where("shape") +
                      " must be one of ellipse, rotation, line, circle (got '" +
                      shape + "')");
  }
  o->still_duration_s = m.Get<double>("still_duration_s");
  o->blend_duration_s = m.Get<double>("blend_duration_s");
  o->radius_x_m = m.Get<double>("radius_x_m");
  o->radius_y_m = m.Get<double>("radius_y_m");
  o->lap_period_s = m.Get<double>("lap_period_s");
  o->height_m = m.Get<double>("height_m");
  o->height_amplitude_m = m.Get<double>("height_amplitude_m");
  o->roll_amplitude_rad = m.Get<double>("roll_amplitude_rad");
  o->pitch_amplitude_rad = m.Get<double>("pitch_amplitude_rad");
  o->yaw_amplitude_rad = m.Get<double>("yaw_amplitude_rad");
  o->start_phase_s = m.Get<double>("start_phase_s");
  o->attitude_rate_factor = m.Get<double>("attitude_rate_factor");
  ValidateAt(m, *o);
}

void ReadImu(const YamlNode& i, SimImuOptions* o) {
  o->rate_hz = i.Get<double>("rate_hz");
  o->add_noise = i.Get<bool>("add_noise");
  o->noise = ReadImuNoise(i);
  o->initial_accelerometer_bias = Vector3(i, "initial_accelerometer_bias");
  o->initial_gyroscope_bias = Vector3(i, "initial_gyroscope_bias");
  ValidateAt(i, o->noise);
}

void ReadCamera(const YamlNode& c, SimCameraOptions* o) {
  o->stereo = c.Get<bool>("stereo");
  o->pixel_noise_px = c.Get<double>("pixel_noise_px");
  o->max_features_per_frame = c.Get<int>("max_features_per_frame");
  o->min_feature_distance_px = c.Get<double>("min_feature_distance_px");
  o->track_drop_probability = c.Get<double>("track_drop_probability");
  o->outlier_fraction = c.Get<double>("outlier_fraction");
  o->time_offset_s = c.Get<double>("time_offset_s");
}

void ReadRoom(const YamlNode& r, SimRoomOptions* o) {
  o->half_length_x_m = r.Get<double>("half_length_x_m");
  o->half_width_y_m = r.Get<double>("half_width_y_m");
  o->height_m = r.Get<double>("height_m");
  o->landmarks = r.Get<int>("landmarks");
}

// The shortest text that reads back as the same double.
std::string Num(double v) {
  char buffer[32];
  const std::to_chars_result r =
      std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, r.ptr);
}

std::string Vec(const Eigen::Vector3d& v) {
  return "[" + Num(v.x()) + ", " + Num(v.y()) + ", " + Num(v.z()) + "]";
}

}  // namespace

SimulatorOptions LoadSimulatorOptions(const std::string& path) {
  const YamlNode root = YamlNode::LoadFile(path);
  SimulatorOptions o;
  const int64_t seed = root.Get<int64_t>("seed");
  if (seed < 0 || seed > 0xffffffffLL) {
    throw ConfigError(root.Where("seed") + " must be in [0, 2^32) (got " +
                      std::to_string(seed) + ")");
  }
  o.seed = static_cast<uint32_t>(seed);
  o.start_time_ns = root.Get<int64_t>("start_time_ns");
  o.duration_s = root.Get<double>("duration_s");
  o.gravity_m_s2 = root.Get<double>("gravity_m_s2");
  ReadMotion(root.Child("motion"), &o.motion);
  ReadImu(root.Child("imu"), &o.imu);
  ReadCamera(root.Child("camera"), &o.camera);
  ReadRoom(root.Child("room"), &o.room);
  // Validate's messages start with the section ("camera.outlier_fraction").
  ValidateAt(root, o);
  return o;
}

std::string SimulatorOptionsToYaml(const SimulatorOptions& o) {
  std::ostringstream y;
  y << "seed: " << o.seed << "\n"
    << "start_time_ns: " << o.start_time_ns << "  # first IMU stamp [ns]\n"
    << "duration_s: " << Num(o.duration_s) << "\n"
    << "gravity_m_s2: " << Num(o.gravity_m_s2) << "\n";
  const SimMotionOptions& m = o.motion;
  y << "motion:\n"
    << "  shape: " << SimShapeName(m.shape) << "\n"
    << "  still_duration_s: " << Num(m.still_duration_s) << "\n"
    << "  blend_duration_s: " << Num(m.blend_duration_s) << "\n"
    << "  radius_x_m: " << Num(m.radius_x_m) << "\n"
    << "  radius_y_m: " << Num(m.radius_y_m) << "\n"
    << "  lap_period_s: " << Num(m.lap_period_s) << "\n"
    << "  height_m: " << Num(m.height_m) << "\n"
    << "  height_amplitude_m: " << Num(m.height_amplitude_m) << "\n"
    << "  roll_amplitude_rad: " << Num(m.roll_amplitude_rad) << "\n"
    << "  pitch_amplitude_rad: " << Num(m.pitch_amplitude_rad) << "\n"
    << "  yaw_amplitude_rad: " << Num(m.yaw_amplitude_rad) << "\n"
    << "  start_phase_s: " << Num(m.start_phase_s) << "\n"
    << "  attitude_rate_factor: " << Num(m.attitude_rate_factor) << "\n";
  const SimImuOptions& i = o.imu;
  y << "imu:\n"
    << "  rate_hz: " << Num(i.rate_hz) << "\n"
    << "  add_noise: " << (i.add_noise ? "true" : "false") << "\n"
    << "  accelerometer_noise_density: "
    << Num(i.noise.accelerometer_noise_density) << "\n"
    << "  gyroscope_noise_density: " << Num(i.noise.gyroscope_noise_density)
    << "\n"
    << "  accelerometer_random_walk: " << Num(i.noise.accelerometer_random_walk)
    << "\n"
    << "  gyroscope_random_walk: " << Num(i.noise.gyroscope_random_walk) << "\n"
    << "  initial_accelerometer_bias: " << Vec(i.initial_accelerometer_bias)
    << "\n"
    << "  initial_gyroscope_bias: " << Vec(i.initial_gyroscope_bias) << "\n";
  const SimCameraOptions& c = o.camera;
  y << "camera:  # calibrations: EuRoC VI-Sensor cam0 (and cam1), built in\n"
    << "  stereo: " << (c.stereo ? "true" : "false") << "\n"
    << "  pixel_noise_px: " << Num(c.pixel_noise_px) << "\n"
    << "  max_features_per_frame: " << c.max_features_per_frame << "\n"
    << "  min_feature_distance_px: " << Num(c.min_feature_distance_px) << "\n"
    << "  track_drop_probability: " << Num(c.track_drop_probability) << "\n"
    << "  outlier_fraction: " << Num(c.outlier_fraction) << "\n"
    << "  time_offset_s: " << Num(c.time_offset_s) << "\n";
  const SimRoomOptions& r = o.room;
  y << "room:\n"
    << "  half_length_x_m: " << Num(r.half_length_x_m) << "\n"
    << "  half_width_y_m: " << Num(r.half_width_y_m) << "\n"
    << "  height_m: " << Num(r.height_m) << "\n"
    << "  landmarks: " << r.landmarks << "\n";
  return y.str();
}

}  // namespace vio
