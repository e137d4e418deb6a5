// vio_sim: writes a simulated sequence folder in the EuRoC ASL layout (IMU,
// feature observations or, with --render, rendered images, ground truth),
// prints the effective configuration and a summary.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/recorded_flight.h"
#include "config/render_config.h"
#include "config/simulator_config.h"
#include "dataset/sim_folder.h"
#include "dataset/sim_trajectory.h"
#include "dataset/trajectory_curve.h"
#include "tools/command_line.h"
#include "tools/curve_flags.h"
#include "tools/sim_images.h"

namespace {

struct Args {
  std::string config;  // empty: built-in defaults (= config/sim_default.yaml)
  std::string out = "sim_sequence";
  bool has_seed = false;
  int64_t seed = 0;
  bool render = false;  // images instead of features.csv
  bool help = false;
  // Flight mode (--flight): a recorded sequence's ground truth as the motion.
  std::string flight;
  std::string ground_truth;  // empty: the folder's own
  vio::FlightImu imu = vio::FlightImu::kSynthetic;
  double knot_spacing_s = vio::CurveFitOptions().knot_spacing_s;
  double rotation_knot_spacing_s =
      vio::CurveFitOptions().rotation_knot_spacing_s;
  vio::FlightCurve fit = vio::FlightCurve::kGroundTruth;
  vio::ImuCurveFitOptions imu_curve;
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
    "                 render: block sets blur, gain, noise, vignetting;\n"
    "                 docs/rendering.md); with --flight too\n"
    "\n"
    "Flight mode: the motion of a recorded sequence instead of the preset's\n"
    "(docs/recorded_flights.md). The preset still gives the seed, the IMU\n"
    "noise of the synthetic IMU and the camera model (noise, tracks, stereo);\n"
    "its motion, room and duration are not used.\n"
    "  --flight FOLDER      a sequence in the EuRoC ASL layout with ground\n"
    "                       truth (state_groundtruth_estimate0/data.csv or\n"
    "                       mav0/ground_truth.tum); its camN/sensor.yaml and\n"
    "                       frame stamps are used when present\n"
    "  --ground-truth FILE  this ground truth instead (EuRoC CSV or TUM)\n"
    "  --imu synthetic|recorded  synthetic: from the fitted curve with the\n"
    "                       preset's noise (default); recorded: the folder's\n"
    "                       mav0/imu0/data.csv passed through unchanged\n"
    "  --knot-spacing S     of the fitted B-spline [s] (default 0.05)\n"
    "  --rotation-knot-spacing S  of its rotations, fitted apart [s]\n"
    "                       (default 0: the same as --knot-spacing)\n"
    "  --curve ground-truth|imu  what the curve is fitted to: the ground\n"
    "                       truth alone (default), or the ground truth and\n"
    "                       the recorded IMU together (--imu recorded only):\n"
    "                       the cameras then move as the recorded IMU says\n"
    "  --fit-noise-scale S  joint fit: the sensor.yaml white-noise densities\n"
    "                       times S (default 1)\n"
    "  --fit-bias-walk-scale S  joint fit: the random walks times S\n"
    "                       (default 1)\n"
    "  --fit-bias-knot-spacing S  joint fit: of the bias splines [s]\n"
    "                       (default 1)\n"
    "  --fit-position-sigma M, --fit-rotation-sigma RAD  joint fit: the\n"
    "                       ground truth's noise (default 0.003 m, 0.003 rad)\n"
    "  --fit-knot-spacing S joint fit: of the spline [s] (default 0.005)\n";

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
    } else if (flag == "--flight") {
      args.flight = line.Value();
    } else if (flag == "--ground-truth") {
      args.ground_truth = line.Value();
    } else if (flag == "--imu") {
      const std::string mode = line.Value();
      if (mode == "synthetic") {
        args.imu = vio::FlightImu::kSynthetic;
      } else if (mode == "recorded") {
        args.imu = vio::FlightImu::kRecorded;
      } else {
        throw std::invalid_argument(
            "--imu expects synthetic or recorded (got '" + mode + "')");
      }
    } else if (flag == "--knot-spacing") {
      const std::string text = line.Value();
      std::istringstream in(text);
      if (!(in >> args.knot_spacing_s) || !in.eof() ||
          !(args.knot_spacing_s > 0.0)) {
        throw std::invalid_argument(
            "--knot-spacing expects seconds > 0 (got '" + text + "')");
      }
    } else if (flag == "--rotation-knot-spacing") {
      args.rotation_knot_spacing_s = line.Number<double>();
      if (!(args.rotation_knot_spacing_s >= 0.0)) {
        throw std::invalid_argument(
            "--rotation-knot-spacing expects seconds >= 0");
      }
    } else if (vio::ParseCurveFlag(line, &args.fit, &args.imu_curve)) {
      // --curve, --fit-*: tools/curve_flags.h
    } else if (flag == "--help" || flag == "-h") {
      args.help = true;
    } else {
      throw std::invalid_argument("unknown argument '" + flag + "'\n" + kUsage);
    }
  }
  if (args.flight.empty() &&
      (!args.ground_truth.empty() || args.imu != vio::FlightImu::kSynthetic)) {
    throw std::invalid_argument("--ground-truth and --imu need --flight");
  }
  std::string message;
  if (!args.imu_curve.Validate(&message)) {
    throw std::invalid_argument("--fit-*: " + message);
  }
  if (args.fit == vio::FlightCurve::kGroundTruthAndImu &&
      args.imu != vio::FlightImu::kRecorded) {
    throw std::invalid_argument(
        "--curve imu needs --flight and --imu recorded");
  }
  return args;
}

// Boxes keep this far from the body and the cameras [m].
constexpr double kBoxClearanceM = 0.5;

// Renders the simulation's frames into the folder and prints the summary.
void RenderImages(const vio::Simulation& sim, const Eigen::Vector3d& min_corner,
                  const Eigen::Vector3d& max_corner,
                  const vio::RenderOptions& render,
                  const vio::BodyPoseAt& body_pose, const std::string& out) {
  std::vector<int> left_out;
  const vio::SceneLayout layout = vio::LayoutClearOfPath(
      min_corner, max_corner, render.boxes, vio::SimulationPath(sim),
      kBoxClearanceM, &left_out);
  const vio::SimImagesSummary s =
      vio::RenderSimulationImages(sim, layout, render, body_pose, out);
  std::printf("%s", vio::DescribeSimImages(s, sim.options.camera.stereo ? 2 : 1,
                                           left_out)
                        .c_str());
}

// Flight mode: simulate along the recorded flight and write the folder.
vio::Simulation SimulateFlightToFolder(
    const Args& args, const vio::SimulatorOptions& preset,
    const vio::RenderOptions& render,
    const vio::SimulationFolderOptions& folder) {
  const vio::RecordedFlight flight =
      vio::LoadRecordedFlight(args.flight, args.ground_truth);
  vio::FlightOptions options;
  options.imu = args.imu;
  options.curve.knot_spacing_s = args.knot_spacing_s;
  options.curve.rotation_knot_spacing_s = args.rotation_knot_spacing_s;
  options.fit = args.fit;
  options.imu_curve = args.imu_curve;
  const vio::FlightSimulation f = vio::SimulateFlight(preset, options, flight);
  vio::WriteSimulationFolder(f.simulation, args.out, folder);
  const vio::CurveFitReport& c = f.curve;
  std::printf("flight %s\n", args.flight.c_str());
  std::printf("ground truth %s (%zu poses%s)\n",
              flight.ground_truth_path.c_str(), flight.ground_truth.size(),
              flight.has_biases ? ", with biases" : "");
  std::printf(
      "curve: %d control points every %.3f s (rotations every %.4f s), "
      "through %d poses: position rms %.2f mm max %.1f mm, rotation rms "
      "%.3f deg max %.2f deg\n",
      c.control_points,
      f.imu_fitted ? options.imu_curve.knot_spacing_s
                   : options.curve.knot_spacing_s,
      f.imu_fitted || options.curve.rotation_knot_spacing_s <= 0.0
          ? (f.imu_fitted ? options.imu_curve.knot_spacing_s
                          : options.curve.knot_spacing_s)
          : options.curve.rotation_knot_spacing_s,
      c.samples, 1e3 * c.position_rms_m, 1e3 * c.position_max_m,
      c.rotation_rms_rad * 180.0 / M_PI, c.rotation_max_rad * 180.0 / M_PI);
  if (f.imu_fitted) {
    const vio::ImuCurveFitReport& j = f.imu_fit;
    std::printf(
        "curve fitted to the ground truth and the recorded IMU: %d control "
        "points every %.4f s, bias knots every %.2f s, %d IMU samples, %d "
        "Gauss-Newton steps; recorded IMU against it (fitted biases removed), "
        "rms x, y, z: gyroscope %.2f, %.2f, %.2f mrad/s, accelerometer %.3f, "
        "%.3f, %.3f m/s^2\n",
        j.control_points, options.imu_curve.knot_spacing_s,
        options.imu_curve.bias_knot_spacing_s, j.imu_samples, j.iterations,
        1e3 * j.gyroscope_rms.x(), 1e3 * j.gyroscope_rms.y(),
        1e3 * j.gyroscope_rms.z(), j.accelerometer_rms.x(),
        j.accelerometer_rms.y(), j.accelerometer_rms.z());
  }
  std::printf("path length %.1f m\n", f.path_length_m);
  const Eigen::Vector3d size = f.room.max_corner - f.room.min_corner;
  std::printf(
      "room %.1f x %.1f x %.1f m: %d landmarks on its faces, %d clutter\n",
      size.x(), size.y(), size.z(), f.room.surface_landmarks,
      f.room.clutter_landmarks);
  std::printf("imu: %s\n",
              args.imu == vio::FlightImu::kRecorded
                  ? "recorded, passed through unchanged"
                  : "synthetic, from the curve with the preset's noise");
  std::printf("cameras: %s\n", f.cameras_from_folder
                                   ? "the folder's camN/sensor.yaml"
                                   : "EuRoC's built-in VI-Sensor calibration");
  std::printf("frames at recorded stamps %lld (%s), the rest at %.0f Hz\n",
              static_cast<long long>(f.recorded_frames),
              flight.frame_stamps_path.empty()
                  ? "none recorded"
                  : flight.frame_stamps_path.c_str(),
              f.simulation.options.camera.cam0.rate_hz);
  if (args.render) {
    // The curve the simulation followed, so the images move exactly as the
    // simulated IMU says.
    const std::shared_ptr<const vio::TrajectoryCurve>& curve = f.followed;
    RenderImages(
        f.simulation, f.room.min_corner, f.room.max_corner, render,
        vio::TrajectoryBodyPose(curve, curve->start_ns(), curve->duration_s()),
        args.out);
  }
  return f.simulation;
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

// A built-in preset: simulate, write the folder, render when asked.
vio::Simulation SimulatePresetToFolder(
    const Args& args, const vio::SimulatorOptions& options,
    const vio::RenderOptions& render,
    const vio::SimulationFolderOptions& folder) {
  const vio::Simulation sim = vio::Simulate(options);
  vio::WriteSimulationFolder(sim, args.out, folder);
  if (args.render) {
    const vio::SimRoomOptions& r = options.room;
    RenderImages(sim, {-r.half_length_x_m, -r.half_width_y_m, 0.0},
                 {r.half_length_x_m, r.half_width_y_m, r.height_m}, render,
                 vio::TrajectoryBodyPose(
                     std::make_shared<vio::SimTrajectory>(options.motion),
                     options.start_time_ns, options.duration_s),
                 args.out);
  }
  return sim;
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
              << (args.flight.empty()
                      ? ""
                      : "# flight mode: motion, room and duration_s are not "
                        "used\n")
              << vio::SimulatorOptionsToYaml(options)
              << (args.render ? vio::RenderOptionsToYaml(render) : "")
              << std::flush;
    vio::SimulationFolderOptions folder;
    folder.write_features = !args.render;
    const vio::Simulation sim =
        args.flight.empty()
            ? SimulatePresetToFolder(args, options, render, folder)
            : SimulateFlightToFolder(args, options, render, folder);
    PrintSummary(sim.summary, args.out);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
