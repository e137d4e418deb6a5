// vio_sim: writes a simulated sequence folder in the EuRoC ASL layout (IMU,
// feature observations instead of images, ground truth), prints the effective
// configuration and a summary.

#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "config/simulator_config.h"
#include "dataset/sim_folder.h"
#include "tools/command_line.h"

namespace {

struct Args {
  std::string config;  // empty: built-in defaults (= config/sim_default.yaml)
  std::string out = "sim_sequence";
  bool has_seed = false;
  int64_t seed = 0;
  bool help = false;
};

constexpr char kUsage[] =
    "usage: vio_sim [--config FILE] [--out DIR] [--seed N] [--help]\n"
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
    "                 seed and configuration give the same bytes\n";

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
    std::cout << "# effective configuration"
              << (args.config.empty() ? " (built-in defaults)"
                                      : " (" + args.config + ")")
              << "\n"
              << vio::SimulatorOptionsToYaml(options) << std::flush;
    const vio::Simulation sim = vio::SimulateToFolder(options, args.out);
    PrintSummary(sim.summary, args.out);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
