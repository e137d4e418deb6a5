#ifndef VIO_TEST_BENCHMARK_INIT_BENCHMARK_ARGS_H_
#define VIO_TEST_BENCHMARK_INIT_BENCHMARK_ARGS_H_

// init_benchmark's command line (the options are listed in
// init_benchmark.cc) and the estimator options it makes of them.

#include <string>
#include <vector>

#include "dataset/simulator.h"
#include "estimator/estimator_options.h"

namespace vio {

struct Args {
  std::vector<std::string> presets;
  int seeds = 20;
  // The first trial's seed; trial k has seed first_seed + k (its start
  // phase k / seeds of a lap, whatever the first seed), so that one set of
  // seeds can choose a limit and a disjoint one validate it.
  int first_seed = 1000;
  // --drop-outliers (a diagnosis, the truth's knowledge): the simulation's
  // outlier sightings are left out of the frames instead of fed.
  bool drop_outliers = false;
  // --phase-shift X: the start phases shifted X of a step (k + X) / seeds
  // of a lap, so that held-out trials can also lie between the first ones.
  double phase_shift = 0.0;
  double seconds = 6.0;  // simulated per start trial [s]
  bool ate = false;
  // --against-default (implies --ate-separate): also replay in motion with
  // the preset's default options and compare on the frames both runs
  // estimate (from the later first start).
  bool against_default = false;
  bool verbose = false;
  bool diagnose = false;  // per attempt: pairs, parallax, truth
  // init.mono.long_window_s and max_refined_scale_uncertainty (< 0: the
  // defaults), to measure the wait for the scale.
  double long_window_s = -1.0;
  double max_scale_sigma = -1.0;
  // init.mono.min_parallax_px and min_correspondences (< 0: the defaults).
  double min_parallax_px = -1.0;
  int min_correspondences = -1;
  // init.mono.gyro_aided: 0 off, 1 on, < 0 the default.
  int gyro_aided = -1;
  // init.mono.gyro_max_refine_change_sigmas (< 0: the default).
  double gyro_max_change_sigmas = -1.0;
  // init.mono.gyro_min_parallax_px (< 0: the default).
  double gyro_min_parallax_px = -1.0;
  // --verbose: also every refused attempt of the trial (method, time,
  // reason, value), to measure a check's values.
  bool attempts = false;
  // init.stereo.min_span_s and window_s (< 0: the defaults).
  double stereo_span_s = -1.0;
  double stereo_window_s = -1.0;
  // init.stereo.refine_outlier_rounds and max_refine_scale_change (< 0:
  // the defaults).
  int stereo_outlier_rounds = -1;
  double stereo_max_change = -1.0;
  double stereo_outlier_px = -1.0;  // refine_outlier_threshold_px
  double stereo_prescreen_px = -1.0;  // refine_prescreen_threshold_px
  // init.mono.outlier_rounds, outlier_threshold_px, max_outlier_share (< 0:
  // the defaults).
  int mono_outlier_rounds = -1;
  double mono_outlier_px = -1.0;
  double mono_max_outlier_share = -1.0;
  // init.mono.realign_after_s, realign_window_s,
  // realign_max_scale_uncertainty, realign_min_change (< 0: the config's).
  double realign_after_s = -1.0;
  double realign_window_s = -1.0;
  double realign_max_sigma = -1.0;
  double realign_min_change = -1.0;
  // init.mono.refine_outlier_rounds (< 0: the config's).
  int mono_refine_rounds = -1;
  // --estimator-config FILE: the estimator options start from that
  // configuration's estimator: block (use_stereo and gravity still the
  // preset's) instead of the built-in defaults; the overrides above apply
  // on top. Empty: the built-in defaults (EstimatorOptions).
  std::string estimator_config;
  // With --ate (repeatable --ate-from S): also the ATE of both runs over
  // their frames from S seconds after the cut (--ate-separate: after the
  // first frame) on, aligned on those alone.
  std::vector<double> ate_from_s;
  int ate_runs = 5;  // --ate: runs per preset (seeds 2000 on)
  // --ate-separate: the former comparison, two simulations (the preset in
  // motion, another from rest) instead of one sequence replayed whole and
  // cut (init_benchmark_ate.h).
  bool ate_separate = false;
  // --cut S: the same-sequence comparison cuts every run at S seconds after
  // its first sample (> 4: after the blend) instead of 5, 6.5, 8, 9.5 s in
  // turn (<= 0: those).
  double cut_s = -1.0;
  bool ate_only = false;  // --ate-only: not the start figures
  // --ate-run K (repeatable): the same-sequence comparison replays only
  // run K of the --ate-runs (seed 2000 + K, its phase and cut unchanged), so
  // that a few runs of the full set can be measured alone. Empty: all.
  std::vector<int> ate_run_only;
};

// The estimator options for replaying `simulation`
// (testing::OptionsFor) with the overrides of `args`.
EstimatorOptions OptionsOf(const SimulatorOptions& simulation,
                           const Args& args);

// Parses the command line; throws std::invalid_argument on an unknown
// option or a missing value.
Args Parse(int argc, char** argv);

}  // namespace vio

#endif  // VIO_TEST_BENCHMARK_INIT_BENCHMARK_ARGS_H_
