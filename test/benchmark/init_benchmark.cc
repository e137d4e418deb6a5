// init_benchmark: the figures of the starts in motion (docs/
// initialisation.md). For each in-motion preset it simulates `--seeds`
// sequences, each with its own seed and start phase (where on the lap the
// first frame lies), runs the estimator until it starts, and prints the
// distributions (median, p90, max) of
//   - the time from the first frame to the accepted start [s],
//   - the scale error of the first window: the RMS spread of its positions
//     about their centroid against the truth's, minus 1 [%],
//   - the gravity direction error: the angle between the estimated and the
//     true world z seen from the newest frame [deg],
//   - the gyroscope-bias error |b_g - b_g true| at the newest frame [rad/s],
// with the share of starts within the target time, the same scale error
// for the linear alignment alone (before the joint adjustment), and the
// running estimate's gravity direction error at fixed times after the first
// frame (kLaterTimes: what the window makes of the start's tilt); --verbose
// also prints per trial the scale's relative std the joint adjustment
// claims (estimator/scale_uncertainty.h). With --ate it also compares
// the ATE in motion against from rest on ONE sequence per run (2 s still, a
// 2 s blend, the preset's motion) replayed whole and cut at a moving instant
// (init_benchmark_ate.h; --cut S fixes the cut); --ate-separate instead
// compares two simulations (the preset, and the same motion after the still
// start), the former measurement; --ate-from S (repeatable) also both ATEs
// over the frames from S seconds after the cut (after the first frame with
// --ate-separate) on, aligned on those alone; --ate-runs N replays
// min(N, --seeds) sequences per preset instead of 5; --ate-only skips the
// start figures. With --verbose the same-sequence comparison also prints per
// run both runs' tilt, accelerometer- and gyroscope-bias errors at t0 + 0,
// 1, 2, 4, 8, 16 and 32 s (the first estimate at or after each).
//
// --first-seed N: the trials' seeds are N, N+1, ... (default 1000; the start
// phases stay spread over the lap whatever N), so that a limit chosen on one
// set of seeds can be validated on a disjoint one; --phase-shift X moves trial
// k's phase to (k + X) / seeds of a lap (0.5: between the default's). --drop-outliers (a
// diagnosis with the simulator's knowledge): the outlier sightings
// (camera.outlier_fraction) are left out instead of fed, the same draws
// otherwise.
//
// --diagnose prints, per frame until the start, the mono start's verdict and
// the pairs it could take (init_diagnosis.h). --stereo-span and
// --stereo-window override init.stereo's min_span_s and window_s,
// --stereo-outlier-rounds, --stereo-outlier-px, --stereo-prescreen-px and
// --stereo-max-change its refine_outlier_rounds, refine_outlier_threshold_px,
// refine_prescreen_threshold_px and max_refine_scale_change;
// --mono-outlier-rounds, --mono-outlier-px and --mono-max-outlier-share
// init.mono's outlier_rounds, outlier_threshold_px and max_outlier_share,
// --mono-refine-rounds its refine_outlier_rounds; --realign-after,
// --realign-window, --realign-max-sigma and --realign-min-change its
// realign_after_s, realign_window_s, realign_max_scale_uncertainty and
// realign_min_change;
// --min-parallax,
// --min-correspondences, --gyro-aided and --gyro-max-change-sigmas override
// init.mono's options, to measure them. --estimator-config FILE starts the
// estimator options from FILE's estimator: block (for example
// config/stereo.yaml; use_stereo and gravity stay the preset's) instead of
// the built-in defaults; the overrides apply on top.
//
//   init_benchmark [--preset NAME]... [--seeds N] [--first-seed N]
//                  [--phase-shift X] [--drop-outliers] [--seconds S] [--ate]
//                  [--verbose] [--diagnose] [--long-window S]
//                  [--max-scale-sigma X] [--min-parallax PX]
//                  [--min-correspondences N] [--gyro-aided 0|1]
//                  [--gyro-max-change-sigmas K]
//                  [--against-default] [--gyro-min-parallax PX]
//                  [--attempts] [--stereo-span S] [--stereo-window S]
//                  [--stereo-outlier-rounds N] [--stereo-outlier-px PX]
//                  [--stereo-prescreen-px PX] [--stereo-max-change X]
//                  [--mono-outlier-rounds N] [--mono-outlier-px PX]
//                  [--mono-refine-rounds N]
//                  [--mono-max-outlier-share X]
//                  [--ate-from S]... [--ate-runs N] [--ate-separate]
//                  [--cut S] [--ate-only] [--estimator-config FILE]
// NAME: motion_mono, motion_stereo, handheld (default: all three), or any
// config/sim_NAME.yaml. Deterministic; not run by ctest.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/simulator_config.h"
#include "dataset/simulator.h"
#include "estimator/estimator.h"
#include "estimator/sequence_runner.h"
#include "test/benchmark/distribution.h"
#include "test/benchmark/init_benchmark_args.h"
#include "test/benchmark/init_benchmark_ate.h"
#include "test/benchmark/init_diagnosis.h"
#include "test/testing/sim_replay.h"
#include "test/testing/spread.h"

namespace vio {
namespace {

const StampedState& TruthAt(const Simulation& sim, int64_t t_ns) {
  const auto it = std::lower_bound(
      sim.ground_truth.begin(), sim.ground_truth.end(), t_ns,
      [](const StampedState& s, int64_t t) { return s.t_ns < t; });
  return it == sim.ground_truth.end() ? sim.ground_truth.back() : *it;
}

using vio::testing::Spread;

// --diagnose: one line per frame with the mono start's verdict, the pairs
// (selected frame, newest) the structure from motion could take, and the
// truth's translation and depth.
void Diagnose(const Simulation& sim,
              const testing::PreparedSimulation& prepared,
              const EstimatorOptions& options, const FeatureFrame& frame,
              size_t attempts_before, const EstimatorSummary& summary,
              std::vector<BufferedFrame>* buffer) {
  const int64_t t_d = std::llround(sim.options.camera.time_offset_s * 1e9);
  buffer->push_back({frame.t_ns, frame.t_ns + t_d, frame.observations});
  const MonoInitOptions& m = options.init.mono;
  const std::vector<int> selected =
      SelectFrames(*buffer, m.window_s, m.max_frames);
  if (SpanSeconds(*buffer, selected) < m.min_span_s) return;
  std::string verdict = summary.starts.empty() ? "?" : "started";
  for (size_t i = attempts_before; i < summary.init_attempts.size(); ++i) {
    const InitAttempt& a = summary.init_attempts[i];
    if (a.method == InitMethod::kMono) {
      char b[128];
      std::snprintf(b, sizeof(b), "%s %.3g", InitFailureName(a.reason),
                    a.value);
      verdict = b;
    }
  }
  const double focal = prepared.cameras[0].focal_px;
  const std::vector<diagnosis::PairFigures> pairs = diagnosis::Pairs(
      sim, *buffer, selected, prepared.cameras[0].T_b_c, focal);
  std::printf("    t %.2f [%s]\n",
              1e-9 * static_cast<double>(frame.t_ns - prepared.frames[0].t_ns),
              verdict.c_str());
  std::pair<double, double> ages;
  const double any = diagnosis::BestAnyPair(
      *buffer, selected, m.min_correspondences, focal, &ages);
  std::printf("      best of any pair: %.1f px (frames %.2f and %.2f s old)\n",
              any, ages.first, ages.second);
  for (const diagnosis::PairFigures& p : pairs) {
    std::printf(
        "      pair age %.2f s: shared %3d, parallax kabsch %5.1f px, "
        "true rotation %5.1f px, baseline %.3f m, depth %.2f m, direction "
        "error %.1f deg\n",
        p.age_s, p.shared, p.kabsch_px, p.true_rot_px, p.baseline_m, p.depth_m,
        p.direction_error_deg);
  }
}

// --attempts: one line per refused attempt (not the span's).
void PrintAttempts(const EstimatorSummary& summary, int64_t t0_ns) {
  for (const InitAttempt& a : summary.init_attempts) {
    if (a.reason == InitFailure::kTooFewFrames) continue;
    std::printf("    attempt %s t %.2f: %s %.4g (limit %.4g)\n",
                InitMethodName(a.method),
                1e-9 * static_cast<double>(a.t_ns - t0_ns),
                InitFailureName(a.reason), a.value, a.limit);
  }
}

struct Trial {
  bool started = false;
  double time_s = 0.0;
  double scale_error = 0.0;            // after the joint adjustment
  double alignment_scale_error = 0.0;  // the linear alignment's
  double gravity_deg = 0.0;
  double gyro_bias = 0.0;
  double scale_sigma = -1.0;       // predicted by the joint adjustment
  double own_sigma = -1.0;         // the initialiser's own (before it)
  double accel_bias = 0.0;         // |b_a - b_a true| at the newest frame
  double initial_gyro_bias = 0.0;  // the initialiser's, before the adjustment
  // How far the joint adjustment moved the newest frame's biases from the
  // initialiser's [rad/s, m/s^2] (no truth needed: a check could use them).
  double gyro_bias_move = 0.0;
  double accel_bias_move = 0.0;
  double parallax_px = 0.0;        // the start's own parallax measure
  double refine_change = 0.0;      // the joint adjustment's path change
  int refine_outliers = 0;         // sightings its outlier rounds removed
  int prescreened = 0;             // of those, before its first solve
  int sfm_outliers = 0;  // mono: sightings the SfM's outlier rounds removed
  InitMethod method = InitMethod::kAuto;
  std::string failures;
  // The running estimate's gravity direction error at kLaterTimes after the
  // first frame [deg] (< 0: not yet started then).
  std::vector<double> later_gravity_deg;
};

// When the running estimate's tilt is measured, after the first frame [s].
const std::vector<double> kLaterTimes = {0.4, 0.5, 0.6, 0.7, 0.8, 0.9,
                                         1.0, 1.2, 1.5, 2.0, 3.0};

// The angle between the estimated and the true world z seen from the body.
double GravityErrorDeg(const Eigen::Quaterniond& q_est,
                       const Eigen::Quaterniond& q_true) {
  const Eigen::Vector3d z_est = q_est.conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d z_true = q_true.conjugate() * Eigen::Vector3d::UnitZ();
  return std::atan2(z_est.cross(z_true).norm(), z_est.dot(z_true)) * 180.0 /
         M_PI;
}

Trial RunTrial(const SimulatorOptions& sim_options, const Args& args) {
  const Simulation sim = Simulate(sim_options);
  std::vector<FeatureFrame> frames = sim.frames;
  if (args.drop_outliers) {
    for (size_t i = 0; i < frames.size() && i < sim.is_outlier.size(); ++i) {
      std::vector<FeatureObservation> kept;
      for (size_t j = 0; j < frames[i].observations.size(); ++j) {
        if (!sim.is_outlier[i][j]) kept.push_back(frames[i].observations[j]);
      }
      frames[i].observations = std::move(kept);
    }
  }
  const testing::PreparedSimulation prepared =
      testing::Prepare(sim, std::move(frames));
  const EstimatorOptions options = OptionsOf(sim_options, args);
  Estimator estimator(options, VisualFactorOptions(), sim_options.imu.noise,
                      PreintegrationOptions(), prepared.cameras);
  // Feed until the first start.
  size_t next_imu = 0;
  std::vector<BufferedFrame> buffer;  // --diagnose: the start's frames
  if (args.diagnose) {
    const std::vector<double> lags = {0.25, 0.5, 1.0, 1.5, 2.0};
    const std::vector<double> alive =
        diagnosis::Survival(prepared.frames, lags);
    std::printf("  seed %u: camera-0 features still tracked after",
                sim_options.seed);
    for (size_t i = 0; i < lags.size(); ++i) {
      std::printf(" %.2f s: %.0f %%%s", lags[i], 100 * alive[i],
                  i + 1 < lags.size() ? "," : "\n");
    }
  }
  Trial t;
  t.later_gravity_deg.assign(kLaterTimes.size(), -1.0);
  const int64_t t_first = prepared.frames.front().t_ns;
  size_t later = 0;  // the next of kLaterTimes to measure
  for (const FeatureFrame& frame : prepared.frames) {
    while (next_imu < sim.imu.size()) {
      const ImuSample& s = sim.imu[next_imu++];
      estimator.AddImu(s);
      if (s.t_ns >= frame.t_ns) break;
    }
    const size_t attempts_before = estimator.summary().init_attempts.size();
    const EstimatorOutput out = estimator.AddFrame(frame);
    if (args.diagnose) {
      Diagnose(sim, prepared, options, frame, attempts_before,
               estimator.summary(), &buffer);
    }
    // Past the start, only to measure the running estimate's tilt.
    const double age_s = 1e-9 * static_cast<double>(frame.t_ns - t_first);
    while (later < kLaterTimes.size() && age_s >= kLaterTimes[later] - 1e-6) {
      if (out.initialized) {
        t.later_gravity_deg[later] =
            GravityErrorDeg(out.q_w_b, TruthAt(sim, out.t_ns).q_w_b);
      }
      ++later;
    }
    if (!estimator.summary().starts.empty() && later >= kLaterTimes.size()) {
      break;
    }
  }
  const EstimatorSummary& summary = estimator.summary();
  if (summary.starts.empty()) {
    t.failures = DescribeNoStart(summary);
    if (args.attempts) PrintAttempts(summary, prepared.frames[0].t_ns);
    return t;
  }
  const StartRecord& start = summary.starts.front();
  t.started = true;
  t.method = start.method;
  t.time_s = 1e-9 * static_cast<double>(start.t_ns - prepared.frames[0].t_ns);
  std::vector<Eigen::Vector3d> est, truth;
  for (const InitialFrame& f : start.window) {
    est.push_back(f.p_w_b);
    truth.push_back(TruthAt(sim, f.t_imu_ns).p_w_b);
  }
  const double ratio = Spread(est) / Spread(truth);
  t.scale_error = ratio - 1.0;
  t.alignment_scale_error =
      ratio / (1.0 + start.diagnostics.refine_scale_change) - 1.0;
  const InitialFrame& newest = start.window.back();
  const StampedState& gt = TruthAt(sim, newest.t_imu_ns);
  t.gravity_deg = GravityErrorDeg(newest.q_w_b, gt.q_w_b);
  t.gyro_bias = (newest.b_g - gt.b_g).norm();
  t.scale_sigma = start.diagnostics.refined_scale_sigma;
  t.own_sigma = start.diagnostics.scale_uncertainty;
  t.accel_bias = (newest.b_a - gt.b_a).norm();
  t.initial_gyro_bias = (start.diagnostics.initial_b_g - gt.b_g).norm();
  t.gyro_bias_move = (newest.b_g - start.diagnostics.initial_b_g).norm();
  t.accel_bias_move = (newest.b_a - start.diagnostics.initial_b_a).norm();
  t.parallax_px = start.diagnostics.parallax_px;
  t.refine_change = start.diagnostics.refine_scale_change;
  t.refine_outliers = start.diagnostics.refine_outliers_removed;
  t.prescreened = start.diagnostics.refine_prescreen_removed;
  t.sfm_outliers = start.diagnostics.sfm_outliers_removed;
  if (!summary.init_attempts.empty()) {
    t.failures = DescribeInitFailures(summary.init_attempts);
  }
  if (args.attempts) PrintAttempts(summary, prepared.frames[0].t_ns);
  return t;
}

void StartFigures(const std::string& preset, const Args& args) {
  const SimulatorOptions base = LoadSimulatorOptions(
      std::string(VIO_SOURCE_DIR) + "/config/sim_" + preset + ".yaml");
  const double target_s = base.camera.stereo ? 0.5 : 2.0;
  Distribution time, scale, align, gravity, bias;
  std::vector<Distribution> later(kLaterTimes.size());
  std::vector<int> later_missing(kLaterTimes.size(), 0);
  int started = 0, within = 0;
  for (int k = 0; k < args.seeds; ++k) {
    SimulatorOptions o = base;
    o.seed = static_cast<uint32_t>(args.first_seed + k);
    // Start phases spread over one lap (--phase-shift: between those of
    // other trials).
    o.motion.start_phase_s =
        base.motion.start_phase_s +
        (k + args.phase_shift) * base.motion.lap_period_s / args.seeds;
    o.duration_s = args.seconds;
    const Trial t = RunTrial(o, args);
    if (args.verbose || args.diagnose) {
      std::printf("  seed %u phase %.2f s: %s", o.seed, o.motion.start_phase_s,
                  t.started ? "started" : "no start");
      if (t.started) {
        std::printf(
            " (%s) after %.2f s, scale %+.2f %% (alignment %+.2f %%), "
            "gravity %.3f deg, b_g %.5f (initialiser's %.5f), b_a %.3f, "
            "predicted scale sigma %.2f %% (initialiser's own %.2f %%), "
            "parallax %.2f px, adjustment's path change %+.2f %%, "
            "outliers removed %d (%d before its first solve), the adjustment "
            "moved b_g %.5f, b_a %.3f, SfM outliers removed %d",
            InitMethodName(t.method), t.time_s, 100 * t.scale_error,
            100 * t.alignment_scale_error, t.gravity_deg, t.gyro_bias,
            t.initial_gyro_bias, t.accel_bias, 100 * t.scale_sigma,
            100 * t.own_sigma, t.parallax_px, 100 * t.refine_change,
            t.refine_outliers, t.prescreened, t.gyro_bias_move,
            t.accel_bias_move, t.sfm_outliers);
      }
      std::printf("\n    %s\n", t.failures.c_str());
    }
    if (!t.started) continue;
    ++started;
    within += t.time_s <= target_s ? 1 : 0;
    time.Add(t.time_s);
    scale.Add(std::abs(t.scale_error));
    align.Add(std::abs(t.alignment_scale_error));
    gravity.Add(t.gravity_deg);
    bias.Add(t.gyro_bias);
    for (size_t i = 0; i < kLaterTimes.size(); ++i) {
      if (t.later_gravity_deg[i] >= 0.0) {
        later[i].Add(t.later_gravity_deg[i]);
      } else {
        ++later_missing[i];
      }
    }
  }
  std::printf("%s: %d trials (seeds x start phases), %.1f s each\n",
              preset.c_str(), args.seeds, args.seconds);
  std::printf("  started %d (%.0f %%), within %.1f s %d (%.0f %%)\n", started,
              100.0 * started / args.seeds, target_s, within,
              100.0 * within / args.seeds);
  std::printf("  time to start     %s\n", time.Describe(1.0, "s").c_str());
  std::printf("  scale error       %s\n", scale.Describe(100.0, "%").c_str());
  std::printf("    alignment alone %s\n", align.Describe(100.0, "%").c_str());
  std::printf("  gravity error     %s\n", gravity.Describe(1.0, "deg").c_str());
  std::printf("  gyro bias error   %s\n", bias.Describe(1.0, "rad/s").c_str());
  for (size_t i = 0; i < kLaterTimes.size(); ++i) {
    if (later[i].values.empty()) continue;  // none started by then
    std::printf(
        "  gravity error of the estimate %.1f s after the first frame "
        "%s (%d not started by then)\n",
        kLaterTimes[i], later[i].Describe(1.0, "deg").c_str(),
        later_missing[i]);
  }
}

}  // namespace
}  // namespace vio

int main(int argc, char** argv) {
  try {
    const vio::Args args = vio::Parse(argc, argv);
    for (const std::string& p : args.presets) {
      if (!args.ate_only) vio::StartFigures(p, args);
      if (args.ate_separate) {
        vio::SeparateSimulationsAte(p, args);
      } else if (args.ate) {
        vio::SameSequenceAte(p, args);
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
