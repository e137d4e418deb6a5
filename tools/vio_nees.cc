// vio_nees: the consistency of the estimator's newest-pose covariance. Runs a
// simulated preset over many seeds in memory, asks the estimator for the
// covariance of its newest pose (Estimator::NewestPoseCovariance) every K
// frames, and prints the average NEES against the truth (eval/nees.h): 6 for
// the pose when the covariance is honest, above when overconfident.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/estimator_config.h"
#include "config/imu_config.h"
#include "config/simulator_config.h"
#include "config/visual_config.h"
#include "dataset/simulator.h"
#include "estimator/estimator.h"
#include "eval/nees.h"
#include "frontend/observation_builder.h"
#include "geometry/so3.h"
#include "tools/command_line.h"

namespace {

using namespace vio;  // NOLINT(build/namespaces): a tool's main file

constexpr char kUsage[] =
    "usage: vio_nees [--preset FILE] [--config FILE] [--seeds N]\n"
    "                [--first-seed S] [--every K] [--help]\n"
    "\n"
    "Simulates the preset with seeds S .. S+N-1 (in memory), replays each\n"
    "through the estimator and, every K frames after initialisation,\n"
    "compares the newest pose with the truth under the covariance the\n"
    "estimator reports. Prints, per seed and over all, the average NEES of\n"
    "the pose (dimension 6), its position and rotation parts (3 each) and of\n"
    "the yaw (1), with the ATE of the run. An honest covariance gives NEES\n"
    "near the dimension; [0.5, 2] x dimension is the accepted band.\n"
    "\n"
    "  --preset FILE   simulator preset (default: vio_sim's built-in\n"
    "                  defaults = config/sim_default.yaml)\n"
    "  --config FILE   estimator configuration (imu:, visual:, estimator:;\n"
    "                  default: the built-in defaults = config/default.yaml);\n"
    "                  imu.noise_from: sequence takes the preset's noise\n"
    "  --seeds N       runs (default 20)\n"
    "  --first-seed S  (default 1)\n"
    "  --every K       frames between covariance evaluations (default 10)\n"
    "  --trace         also print every evaluation: seed, time [s], position\n"
    "                  error [m], its claimed std sqrt(trace P_p) [m], yaw\n"
    "                  error and std [deg], NEES of the pose\n";

struct Args {
  std::string preset;
  std::string config;
  int seeds = 20;
  int first_seed = 1;
  int every = 10;
  bool trace = false;
  bool help = false;
};

int ParseInt(const std::string& flag, const std::string& text, int min) {
  std::istringstream in(text);
  int value = 0;
  if (!(in >> value) || !in.eof() || value < min) {
    throw std::invalid_argument(flag + " expects an integer >= " +
                                std::to_string(min) + " (got '" + text + "')");
  }
  return value;
}

Args ParseArgs(int argc, char** argv) {
  Args args;
  CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string flag = line.Current();
    if (flag == "--preset") {
      args.preset = line.Value();
    } else if (flag == "--config") {
      args.config = line.Value();
    } else if (flag == "--seeds") {
      args.seeds = ParseInt(flag, line.Value(), 1);
    } else if (flag == "--first-seed") {
      args.first_seed = ParseInt(flag, line.Value(), 0);
    } else if (flag == "--every") {
      args.every = ParseInt(flag, line.Value(), 1);
    } else if (flag == "--trace") {
      args.trace = true;
    } else if (flag == "--help" || flag == "-h") {
      args.help = true;
    } else {
      throw std::invalid_argument("unknown argument '" + flag +
                                  "' (see --help)");
    }
  }
  return args;
}

struct Config {
  ImuConfig imu;
  VisualFactorOptions visual;
  EstimatorOptions estimator;
};

Config LoadConfig(const std::string& path) {
  Config c;
  if (path.empty()) return c;
  const YamlNode root = YamlNode::LoadFile(path);
  c.imu = LoadImuConfig(root);
  c.visual = ReadVisualOptions(root);
  c.estimator = ReadEstimatorOptions(root);
  return c;
}

// Sums of NEES over evaluations.
struct NeesSum {
  double pose = 0, position = 0, rotation = 0, yaw = 0;
  int count = 0;
  void Add(const PoseNees& n) {
    pose += n.pose;
    position += n.position;
    rotation += n.rotation;
    yaw += n.yaw;
    ++count;
  }
  void Add(const NeesSum& s) {
    pose += s.pose;
    position += s.position;
    rotation += s.rotation;
    yaw += s.yaw;
    count += s.count;
  }
  void Print(const char* label) const {
    const double n = count > 0 ? count : 1;
    std::printf("%-8s %6d  %8.2f  %8.2f  %8.2f  %6.2f", label, count, pose / n,
                position / n, rotation / n, yaw / n);
  }
};

// The truth at t_ns (the simulation's ground truth is at the IMU stamps,
// which the frames' IMU times fall on; the nearest is taken).
StampedPose TruthAt(const Simulation& sim, int64_t t_ns) {
  const auto& gt = sim.ground_truth;
  auto it = std::lower_bound(
      gt.begin(), gt.end(), t_ns,
      [](const StampedState& s, int64_t t) { return s.t_ns < t; });
  if (it == gt.end()) --it;
  if (it != gt.begin() && t_ns - (it - 1)->t_ns < it->t_ns - t_ns) --it;
  return PoseOf(*it);
}

// One seed: the run's NEES sums and its ATE (aligned by the gauge only).
NeesSum RunSeed(const SimulatorOptions& preset, const Config& config, int every,
                bool trace, double* gauge_rmse, int64_t* resets) {
  const Simulation sim = Simulate(preset);
  const SimCameraOptions& cam = preset.camera;
  const int used = config.estimator.use_stereo ? 2 : 1;
  if (used == 2 && !cam.stereo) {
    throw std::invalid_argument("estimator.use_stereo on a mono preset");
  }
  std::vector<CameraModel> models = {CameraModel(cam.cam0)};
  if (used == 2) models.push_back(CameraModel(cam.cam1));
  std::vector<EstimatorCamera> cameras;
  for (const CameraModel& m : models) {
    EstimatorCamera c;
    c.T_b_c.linear() = m.calibration().q_b_c.toRotationMatrix();
    c.T_b_c.translation() = m.calibration().t_b_c;
    c.focal_px = m.focal();
    cameras.push_back(c);
  }
  ObservationBuilder builder(models);
  const ImuNoise noise = config.imu.noise_from == ImuNoiseSource::kSequence
                             ? preset.imu.noise
                             : config.imu.noise;
  EstimatorOptions options = config.estimator;
  options.gravity_magnitude = preset.gravity_m_s2;
  Estimator estimator(options, config.visual, noise, config.imu.preintegration,
                      cameras);
  const int64_t t_d_ns = std::llround(cam.time_offset_s * 1e9);
  NeesSum sum;
  size_t next_imu = 0;
  bool have_gauge = false;
  Eigen::Isometry3d gauge = Eigen::Isometry3d::Identity();
  double squared = 0.0;
  int poses = 0, since = 0;
  for (FeatureFrame frame : sim.frames) {
    frame.observations.erase(
        std::remove_if(
            frame.observations.begin(), frame.observations.end(),
            [&](const FeatureObservation& o) { return o.camera >= used; }),
        frame.observations.end());
    builder.Process(&frame);
    // Every IMU sample up to the first at or after the frame's IMU time.
    const int64_t t_imu = frame.t_ns + t_d_ns;
    while (next_imu < sim.imu.size()) {
      estimator.AddImu(sim.imu[next_imu]);
      if (sim.imu[next_imu++].t_ns >= t_imu) break;
    }
    const EstimatorOutput out = estimator.AddFrame(frame);
    if (!out.processed || !out.initialized) continue;
    const StampedPose estimate{t_imu, out.p_w_b, out.q_w_b};
    const StampedPose truth_raw = TruthAt(sim, t_imu);
    if (!have_gauge) {
      gauge = GaugeTransform(estimate, truth_raw);
      have_gauge = true;
    }
    const StampedPose truth = Transform(gauge, truth_raw);
    squared += (estimate.p_w_b - truth.p_w_b).squaredNorm();
    ++poses;
    if (++since < every) continue;
    since = 0;
    Eigen::Matrix<double, 6, 6> covariance;
    if (!estimator.NewestPoseCovariance(&covariance)) continue;
    const PoseNees n = ComputePoseNees(estimate, truth, covariance);
    sum.Add(n);
    if (trace) {
      const Eigen::Vector3d u =
          estimate.q_w_b.conjugate() * Eigen::Vector3d::UnitZ();
      const double yaw_error =
          u.dot(Log(truth.q_w_b.conjugate() * estimate.q_w_b));
      const double yaw_sigma =
          std::sqrt(u.dot(covariance.bottomRightCorner<3, 3>() * u));
      std::printf("trace %u %.2f %.4f %.4f %.3f %.3f %.2f\n", preset.seed,
                  static_cast<double>(t_imu - sim.imu.front().t_ns) * 1e-9,
                  (estimate.p_w_b - truth.p_w_b).norm(),
                  std::sqrt(covariance.topLeftCorner<3, 3>().trace()),
                  yaw_error * 180.0 / M_PI, yaw_sigma * 180.0 / M_PI, n.pose);
    }
  }
  *gauge_rmse = poses > 0 ? std::sqrt(squared / poses) : 0.0;
  *resets = estimator.summary().resets;
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = ParseArgs(argc, argv);
    if (args.help) {
      std::printf("%s", kUsage);
      return 0;
    }
    SimulatorOptions preset;
    if (!args.preset.empty()) preset = LoadSimulatorOptions(args.preset);
    const Config config = LoadConfig(args.config);
    std::printf("preset %s, config %s, seeds %d..%d, every %d frames\n",
                args.preset.empty() ? "(built-in)" : args.preset.c_str(),
                args.config.empty() ? "(built-in)" : args.config.c_str(),
                args.first_seed, args.first_seed + args.seeds - 1, args.every);
    std::printf(
        "seed      evals  NEES pose  position  rotation    yaw  "
        "(dims 6, 3, 3, 1)  error rmse [m]  resets\n");
    NeesSum all;
    for (int s = args.first_seed; s < args.first_seed + args.seeds; ++s) {
      preset.seed = static_cast<uint32_t>(s);
      double rmse = 0.0;
      int64_t resets = 0;
      const NeesSum sum =
          RunSeed(preset, config, args.every, args.trace, &rmse, &resets);
      sum.Print(std::to_string(s).c_str());
      std::printf("  %20.4f  %6lld\n", rmse, static_cast<long long>(resets));
      std::fflush(stdout);
      all.Add(sum);
    }
    all.Print("all");
    std::printf(
        "\nNEES / dimension: pose %.2f, position %.2f, rotation %.2f, "
        "yaw %.2f (accepted band [0.5, 2])\n",
        all.pose / all.count / 6.0, all.position / all.count / 3.0,
        all.rotation / all.count / 3.0, all.yaw / all.count);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
