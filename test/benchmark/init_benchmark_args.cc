#include "test/benchmark/init_benchmark_args.h"

#include <stdexcept>
#include <string>

#include "config/estimator_config.h"
#include "config/yaml_reader.h"
#include "test/testing/sim_replay.h"

namespace vio {

EstimatorOptions OptionsOf(const SimulatorOptions& simulation,
                           const Args& args) {
  EstimatorOptions o = testing::OptionsFor(simulation);
  if (!args.estimator_config.empty()) {
    o = ReadEstimatorOptions(YamlNode::LoadFile(args.estimator_config));
    o.use_stereo = simulation.camera.stereo;
    o.gravity_magnitude = simulation.gravity_m_s2;
  }
  if (args.long_window_s > 0.0) o.init.mono.long_window_s = args.long_window_s;
  if (args.max_scale_sigma > 0.0) {
    o.init.mono.max_refined_scale_uncertainty = args.max_scale_sigma;
  }
  if (args.min_parallax_px >= 0.0) {
    o.init.mono.min_parallax_px = args.min_parallax_px;
  }
  if (args.min_correspondences > 0) {
    o.init.mono.min_correspondences = args.min_correspondences;
  }
  if (args.gyro_aided >= 0) o.init.mono.gyro_aided = args.gyro_aided > 0;
  if (args.gyro_max_change_sigmas > 0.0) {
    o.init.mono.gyro_max_refine_change_sigmas = args.gyro_max_change_sigmas;
  }
  if (args.gyro_min_parallax_px >= 0.0) {
    o.init.mono.gyro_min_parallax_px = args.gyro_min_parallax_px;
  }
  if (args.stereo_span_s > 0.0) o.init.stereo.min_span_s = args.stereo_span_s;
  if (args.stereo_window_s > 0.0) {
    o.init.stereo.window_s = args.stereo_window_s;
  }
  if (args.stereo_outlier_rounds >= 0) {
    o.init.stereo.refine_outlier_rounds = args.stereo_outlier_rounds;
  }
  if (args.stereo_outlier_px > 0.0) {
    o.init.stereo.refine_outlier_threshold_px = args.stereo_outlier_px;
  }
  if (args.stereo_prescreen_px >= 0.0) {
    o.init.stereo.refine_prescreen_threshold_px = args.stereo_prescreen_px;
  }
  if (args.stereo_max_change > 0.0) {
    o.init.stereo.max_refine_scale_change = args.stereo_max_change;
  }
  if (args.mono_outlier_rounds >= 0) {
    o.init.mono.outlier_rounds = args.mono_outlier_rounds;
  }
  if (args.mono_outlier_px > 0.0) {
    o.init.mono.outlier_threshold_px = args.mono_outlier_px;
  }
  if (args.realign_after_s >= 0.0) {
    o.init.mono.realign_after_s = args.realign_after_s;
  }
  if (args.realign_window_s > 0.0) {
    o.init.mono.realign_window_s = args.realign_window_s;
  }
  if (args.realign_max_sigma > 0.0) {
    o.init.mono.realign_max_scale_uncertainty = args.realign_max_sigma;
  }
  if (args.realign_min_change >= 0.0) {
    o.init.mono.realign_min_change = args.realign_min_change;
  }
  if (args.mono_max_outlier_share > 0.0) {
    o.init.mono.max_outlier_share = args.mono_max_outlier_share;
  }
  if (args.mono_refine_rounds >= 0) {
    o.init.mono.refine_outlier_rounds = args.mono_refine_rounds;
  }
  return o;
}

Args Parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(s + " needs a value");
      return argv[++i];
    };
    if (s == "--preset") {
      a.presets.push_back(value());
    } else if (s == "--seeds") {
      a.seeds = std::stoi(value());
    } else if (s == "--first-seed") {
      a.first_seed = std::stoi(value());
    } else if (s == "--drop-outliers") {
      a.drop_outliers = true;
    } else if (s == "--phase-shift") {
      a.phase_shift = std::stod(value());
    } else if (s == "--seconds") {
      a.seconds = std::stod(value());
    } else if (s == "--ate") {
      a.ate = true;
    } else if (s == "--against-default") {  // a part of --ate-separate
      a.against_default = true;
      a.ate = true;
      a.ate_separate = true;
    } else if (s == "--long-window") {
      a.long_window_s = std::stod(value());
    } else if (s == "--max-scale-sigma") {
      a.max_scale_sigma = std::stod(value());
    } else if (s == "--min-parallax") {
      a.min_parallax_px = std::stod(value());
    } else if (s == "--min-correspondences") {
      a.min_correspondences = std::stoi(value());
    } else if (s == "--gyro-aided") {
      a.gyro_aided = std::stoi(value());
    } else if (s == "--gyro-max-change-sigmas") {
      a.gyro_max_change_sigmas = std::stod(value());
    } else if (s == "--gyro-min-parallax") {
      a.gyro_min_parallax_px = std::stod(value());
    } else if (s == "--stereo-span") {
      a.stereo_span_s = std::stod(value());
    } else if (s == "--stereo-window") {
      a.stereo_window_s = std::stod(value());
    } else if (s == "--stereo-outlier-rounds") {
      a.stereo_outlier_rounds = std::stoi(value());
    } else if (s == "--stereo-outlier-px") {
      a.stereo_outlier_px = std::stod(value());
    } else if (s == "--stereo-prescreen-px") {
      a.stereo_prescreen_px = std::stod(value());
    } else if (s == "--stereo-max-change") {
      a.stereo_max_change = std::stod(value());
    } else if (s == "--mono-outlier-rounds") {
      a.mono_outlier_rounds = std::stoi(value());
    } else if (s == "--mono-outlier-px") {
      a.mono_outlier_px = std::stod(value());
    } else if (s == "--mono-refine-rounds") {
      a.mono_refine_rounds = std::stoi(value());
    } else if (s == "--realign-after") {
      a.realign_after_s = std::stod(value());
    } else if (s == "--realign-window") {
      a.realign_window_s = std::stod(value());
    } else if (s == "--realign-max-sigma") {
      a.realign_max_sigma = std::stod(value());
    } else if (s == "--realign-min-change") {
      a.realign_min_change = std::stod(value());
    } else if (s == "--mono-max-outlier-share") {
      a.mono_max_outlier_share = std::stod(value());
    } else if (s == "--ate-runs") {
      a.ate_runs = std::stoi(value());
    } else if (s == "--ate-from") {
      a.ate_from_s.push_back(std::stod(value()));
    } else if (s == "--ate-separate") {
      a.ate = true;
      a.ate_separate = true;
    } else if (s == "--ate-only") {
      a.ate = true;
      a.ate_only = true;
    } else if (s == "--ate-run") {
      a.ate_run_only.push_back(std::stoi(value()));
    } else if (s == "--estimator-config") {
      a.estimator_config = value();
    } else if (s == "--cut") {
      a.cut_s = std::stod(value());
    } else if (s == "--attempts") {
      a.attempts = true;
    } else if (s == "--diagnose") {
      a.diagnose = true;
    } else if (s == "--verbose") {
      a.verbose = true;
    } else {
      throw std::invalid_argument("unknown option " + s);
    }
  }
  if (a.presets.empty())
    a.presets = {"motion_mono", "motion_stereo", "handheld"};
  return a;
}

}  // namespace vio
