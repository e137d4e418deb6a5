// vio_sim: writes a simulated sequence folder in the EuRoC ASL layout (IMU,
// feature observations or, with --render, rendered images, ground truth),
// prints the effective configuration and a summary.

#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "config/render_config.h"
#include "config/simulator_config.h"
#include "dataset/sim_folder.h"
#include "tools/command_line.h"
#include "tools/sim_images.h"

namespace {

struct Args {
  std::string config;  // empty: built-in defaults (= config/sim_default.yaml)
  std::string out = "sim_sequence";
  bool has_seed = false;
  int64_t seed = 0;
  bool render = false;  // images instead of features.csv
  bool help = false;
};

constexpr char kUsage[] =
    "usage: vio_sim [--config FILE] [--out DIR] [--seed N] [--render] "
    "[--help]\n"
    "\n"
    "Simulates a visual-inertial sequence and writes it to DIR in the EuRoC\n"
    "ASL layout: mav0/imu0/data.csv, mav0/camN/features.csv (tracked feature\n"
    "pixels instead of images), sensor.yaml files and\n"
    "mav0/state_groundtruth_estimate0/data.csv. Prints the effective\n"
    "configuration (YAML, loadable with --config) and a summary.\n"
    "\n"
    "  --config FILE  a preset, e.g. config/sim_stereo.yaml (default: the\n"
    "                 built-in defaults, identical to "
    "config/sim_default.yaml)\n"
    "  --out DIR      output folder (default sim_sequence); DIR/mav0 must not\n"
    "                 exist yet\n"
    "  --seed N       overrides the preset's seed (0 <= N < 2^32); the same\n"
    "                 seed and configuration give the same bytes\n"
    "  --render       render 8-bit images of a textured room instead of\n"
    "                 writing features.csv: mav0/camN/data/*.png + data.csv\n"
    "                 as EuRoC, and the truth in mav0/render/ (the preset's\n"
    "                 render: block sets blur, gain, noise, vignetting)\n";

Args ParseArgs(int argc, char** argv) {
  Args args;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string flag = line.Current();
    if (flag == "--config") {
      args.config = line.Value();
    } else if (flag == "--out") {
      args.out = line.Value();
    } else if (flag == "--seed") {
      const std::string text = line.Value();
      std::istringstream in(text);
      if (!(in >> args.seed) || !in.eof() || args.seed < 0 ||
          args.seed > 0xffffffffLL) {
        throw std::invalid_argument(
            "--seed expects an integer in [0, 2^32) (got '" + text + "')");
      }
      args.has_seed = true;
    } else if (flag == "--render") {
      args.render = true;
    } else if (flag == "--help" || flag == "-h") {
      args.help = true;
    } else {
      throw std::invalid_argument("unknown argument '" + flag + "'\n" + kUsage);
    }
  }
  return args;
}

void PrintSummary(const vio::SimulationSummary& s, const std::string& out) {
  std::printf("duration %.3f s\n", s.duration_s);
  std::printf("imu samples %lld\n", static_cast<long long>(s.imu_samples));
  std::printf("frames %lld\n", static_cast<long long>(s.frames));
  std::printf("observations per frame (cam0) mean %.1f max %d\n",
              s.mean_cam0_observations, s.max_cam0_observations);
  std::printf("observations (all cameras) %lld, outliers %lld\n",
              static_cast<long long>(s.observations),
              static_cast<long long>(s.outliers));
  std::printf("tracks %lld\n", static_cast<long long>(s.tracks));
  std::printf("mean track length %.1f frames\n", s.mean_track_length);
  std::printf("wrote %s\n", out.c_str());
}

// The simulator's body pose at an IMU stamp.
vio::BodyPoseAt SimulatedBodyPose(const vio::SimulatorOptions& options) {
  const vio::SimTrajectory trajectory(options.motion);
  const int64_t start_ns = options.start_time_ns;
  return [trajectory, start_ns](int64_t t_ns) {
    const vio::SimState s =
        trajectory.At(static_cast<double>(t_ns - start_ns) * 1e-9);
    Eigen::Isometry3d T_w_b = Eigen::Isometry3d::Identity();
    T_w_b.linear() = s.q_w_b.toRotationMatrix();
    T_w_b.translation() = s.p_w_b;
    return T_w_b;
  };
}

// Renders the simulation's camera frames into the folder and prints the
// render summary.
void RenderImages(const vio::Simulation& sim, const vio::RenderOptions& render,
                  const std::string& out) {
  const vio::SimulatorOptions& o = sim.options;
  vio::SceneLayout layout;
  layout.half_length_x_m = o.room.half_length_x_m;
  layout.half_width_y_m = o.room.half_width_y_m;
  layout.height_m = o.room.height_m;
  layout.boxes = render.boxes;
  std::vector<vio::CameraCalibration> cameras = {o.camera.cam0};
  if (o.camera.stereo) cameras.push_back(o.camera.cam1);
  std::vector<Eigen::Vector3d> positions;
  for (const vio::StampedState& s : sim.ground_truth) {
    positions.push_back(s.p_w_b);
    for (const vio::CameraCalibration& c : cameras) {
      positions.push_back(s.p_w_b + s.q_w_b * c.t_b_c);
    }
  }
  constexpr double kBoxClearanceM = 0.2;
  vio::CheckClearOfBoxes(layout, positions, kBoxClearanceM);
  std::vector<int64_t> stamps;
  for (const vio::FeatureFrame& f : sim.frames) stamps.push_back(f.t_ns);
  const vio::SimImagesSummary s = vio::RenderSequenceImages(
      stamps, cameras, layout, render, o.camera.time_offset_s, o.seed,
      SimulatedBodyPose(o), out);
  const double images = static_cast<double>(s.render.images);
  const double ms = images > 0 ? 1e3 * s.render.cpu_seconds / images : 0.0;
  std::printf(
      "render: %lld frames x %zu camera(s), %.2f ms CPU per image (%.1f "
      "images/s on one core), blur %.2f renders per frame on average (max "
      "%d); textures %.2f s; PNG writing %.2f ms per image\n",
      static_cast<long long>(s.render.frames), cameras.size(), ms,
      ms > 0 ? 1e3 / ms : 0.0,
      s.render.frames > 0
          ? static_cast<double>(s.render.blur_samples) / s.render.frames
          : 0.0,
      s.render.max_blur_samples, s.texture_seconds,
      images > 0 ? 1e3 * s.write_seconds / images : 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = ParseArgs(argc, argv);
    if (args.help) {
      std::cout << kUsage;
      return 0;
    }
    vio::SimulatorOptions options;
    if (!args.config.empty()) options = vio::LoadSimulatorOptions(args.config);
    if (args.has_seed) options.seed = static_cast<uint32_t>(args.seed);
    std::string message;
    if (!options.Validate(&message)) {
      throw std::invalid_argument("simulator options: " + message);
    }
    vio::RenderOptions render;
    if (args.render && !args.config.empty()) {
      render = vio::LoadRenderOptions(args.config);
    }
    std::cout << "# effective configuration"
              << (args.config.empty() ? " (built-in defaults)"
                                      : " (" + args.config + ")")
              << "\n"
              << vio::SimulatorOptionsToYaml(options)
              << (args.render ? vio::RenderOptionsToYaml(render) : "")
              << std::flush;
    const vio::Simulation sim = vio::Simulate(options);
    vio::SimulationFolderOptions folder;
    folder.write_features = !args.render;
    vio::WriteSimulationFolder(sim, args.out, folder);
    if (args.render) RenderImages(sim, render, args.out);
    PrintSummary(sim.summary, args.out);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
