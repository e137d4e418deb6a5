#ifndef VIO_ESTIMATOR_ESTIMATOR_H_
#define VIO_ESTIMATOR_ESTIMATOR_H_

// The sliding-window visual-inertial estimator. It takes IMU samples and, per
// camera frame, feature observations (undistorted normalised coordinates and
// image velocity); it never sees an image or a file.
//
// Start (estimator/initialization.h): static, monocular or stereo in motion,
// or whichever is ready first; failed attempts are logged in the summary.
//
// Per frame (after the start):
//   1. the IMU interval from the newest window frame is preintegrated and the
//      new frame's state predicted from it;
//   2. the frame is a keyframe when its median parallax to the last keyframe
//      (pixels) or its tracked-feature count says so (DecideKeyframe);
//   3. a non-keyframe second-newest frame is dropped: its IMU interval is
//      merged into the new one and its observations leave the window;
//   4. new landmarks are triangulated; one Ceres problem over the window (IMU
//      factors, visual factors, marginalisation prior, zero-motion factors
//      between frames the vehicle stood still between) is solved;
//   5. failure rules are checked (reset on failure, counted and logged;
//      the in-motion initialiser then runs again and its states replace the
//      restarted window, position and yaw kept); outlier landmarks are
//      removed;
//   6. when the newest frame is a keyframe and the window holds more than
//      window_size keyframes, the oldest is marginalised into the prior.
// The output never holds NaN: a failed step resets to the prediction, and a
// window holding a non-finite or exploding state is never handed to Ceres
// (estimator/state_check.h): it resets too.
//
// Bad IMU input (docs/robustness.md): a sample outside the measuring range
// is replaced from its neighbours (preintegration/imu_glitch_filter.h); a
// short gap is integrated across; across a long one the frames are tracked
// on vision alone and the window carries on (estimator/imu_gaps.h).
//
// Determinism: with solver.num_threads = 1 the same input gives the same
// output bit for bit (every container is iterated in a fixed order).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/failure_detection.h"
#include "estimator/feature_manager.h"
#include "estimator/imu_gaps.h"
#include "estimator/init_attempt.h"
#include "estimator/initial_window.h"
#include "estimator/initialization.h"
#include "estimator/landmark_map.h"
#include "estimator/scale_realignment.h"
#include "estimator/static_initializer.h"
#include "estimator/value_histogram.h"
#include "estimator/window.h"
#include "estimator/window_problem.h"
#include "estimator/zero_velocity.h"
#include "factors/marginalization_prior.h"
#include "factors/visual_factor_options.h"
#include "geometry/feature_observation.h"
#include "preintegration/imu_glitch_filter.h"
#include "preintegration/imu_types.h"

namespace vio {

// One camera as the estimator needs it.
struct EstimatorCamera {
  Eigen::Isometry3d T_b_c = Eigen::Isometry3d::Identity();  // p_b = T_b_c p_c
  double focal_px = 460.0;  // for pixel thresholds and residual weights [px]
};

// The estimate after one frame.
struct EstimatorOutput {
  int64_t t_ns = 0;          // the frame's camera stamp [ns]
  bool processed = false;    // false: the frame was skipped (see summary)
  bool initialized = false;  // false: the state below is not an estimate
  bool keyframe = false;
  bool zero_velocity = false;  // held by the zero-motion constraint
  Eigen::Vector3d p_w_b = Eigen::Vector3d::Zero();  // [m]
  Eigen::Quaterniond q_w_b = Eigen::Quaterniond::Identity();
  Eigen::Vector3d v_w = Eigen::Vector3d::Zero();  // [m/s]
  Eigen::Vector3d b_a = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d b_g = Eigen::Vector3d::Zero();  // [rad/s]
};

struct ResetEvent {
  int64_t t_ns = 0;  // camera stamp of the failed step [ns]
  Failure reason = Failure::kNone;
};

// Counters over the run; everything skipped or reset is counted here.
struct EstimatorSummary {
  static constexpr double kTimeUnitS = 1e-5;  // time histograms' bins [s]
  static constexpr int kTimeExactBits = 11;   // exact below 2^11 units
  static constexpr int kCountExactBits = 13;  // exact below 2^13

  int64_t frames = 0;            // AddFrame calls
  int64_t frames_processed = 0;  // frames that reached the window
  int64_t keyframes = 0;
  int64_t resets = 0;
  std::vector<ResetEvent> reset_log;
  int64_t imu_samples = 0;       // accepted (replaced ones too)
  int64_t imu_non_finite = 0;    // skipped
  int64_t imu_out_of_order = 0;  // stamp not after the last: skipped
  int64_t imu_replaced = 0;      // outside the measuring range: replaced
  int64_t imu_dropped = 0;       // outside it for too long to replace: dropped
  int64_t imu_first_glitch_t_ns = -1;  // the first of those [ns]; -1: none
  int64_t imu_short_gaps = 0;          // missed samples, integrated across
  std::vector<ImuGap> imu_gaps;     // longer than max_sample_gap, in time order
  int64_t frames_visual_only = 0;   // tracked on vision alone across a gap
  int64_t frames_out_of_order = 0;  // stamp not after the last: skipped
  int64_t frames_without_imu = 0;   // no IMU and no visual pose: skipped
  // imu_stream.noise_adaptation: steps that updated it and the final
  // white-noise scales (1 when off) [-].
  int64_t imu_noise_updates = 0;
  double imu_noise_scale_accelerometer = 1.0;
  double imu_noise_scale_gyroscope = 1.0;
  int64_t frames_before_init = 0;           // before a start was accepted
  int64_t frames_without_observations = 0;  // processed on the IMU alone
  int64_t observations_skipped = 0;         // non-finite, unknown camera, ...
  int64_t landmarks_triangulated = 0;
  int64_t outlier_landmarks_removed = 0;  // most of their sightings bad
  int64_t outlier_sightings_removed = 0;  // single sightings, landmark kept
  int64_t landmarks_behind_removed = 0;   // inverse depth <= 0 after a solve
  int64_t marginalizations = 0;
  int64_t marginalization_failures = 0;  // prior replaced by a fresh one
  // keep_point: world points marginalised out of the prior apart from a
  // frame's marginalisation (their track ended otherwise), by batch.
  int64_t points_released = 0;
  // keep_point with max_world_points: world points marginalised with all
  // their sightings to keep within the bound, and the most world points
  // held after any marginalisation of the oldest frame (seen in a frame
  // that stays).
  int64_t points_capped = 0;
  int64_t most_world_points = 0;
  // How each successful marginalisation took its prior's square root
  // (marginalization.h step 4): H*'s Cholesky factor; the floor block by
  // block (world points, null_space_floor.h); the floor of exact zeros by
  // subspace iteration; the eigen path (the fallback of both floors).
  int64_t prior_cholesky = 0;
  int64_t prior_block_floor = 0;
  int64_t prior_subspace_floor = 0;
  int64_t prior_eigen = 0;
  int64_t solver_failures = 0;           // Ceres reported failure
  // Per step: Ceres' wall time, and the CPU time of this thread during the
  // solve (unaffected by other processes competing for the cores) [s]. As
  // histograms (estimator/value_histogram.h), so that a run of any length
  // keeps them in fixed memory: times in bins of 10 us below 20.48 ms (the
  // 0.01 ms vio_replay prints, so its medians and p95 print as the exact
  // ones would), 1/2048 of the value above.
  ValueHistogram solver_time_s{kTimeUnitS, kTimeExactBits};
  ValueHistogram solver_cpu_time_s{kTimeUnitS, kTimeExactBits};
  // Where the solver time goes, summed over all steps [s], and iterations.
  double solver_jacobian_time_s = 0.0;    // residual + Jacobian evaluation
  double solver_residual_time_s = 0.0;    // residual-only evaluation
  double solver_linear_time_s = 0.0;      // linear solver (Schur, Cholesky)
  double solver_preprocess_time_s = 0.0;  // problem setup inside Ceres
  int64_t solver_iterations = 0;
  // Each marginalisation: wall and thread CPU [s], binned as the solver's
  // (the CPU one also has keep_point's releases of world points).
  ValueHistogram marginalization_time_s{kTimeUnitS, kTimeExactBits};
  ValueHistogram marginalization_cpu_time_s{kTimeUnitS, kTimeExactBits};
  // Per step, the landmarks in the problem and the work the solver time is
  // spent on: the frames in the window and the residuals in the problem
  // (visual, IMU, priors, zero motion). Counts, exact below 8192.
  ValueHistogram landmarks_per_step{1.0, kCountExactBits};
  ValueHistogram window_frames_per_step{1.0, kCountExactBits};
  ValueHistogram residuals_per_step{1.0, kCountExactBits};
  // The start: every failed attempt (at most one per method and frame), and
  // every accepted start (the first, then re-initialisations after resets).
  std::vector<InitAttempt> init_attempts;
  std::vector<StartRecord> starts;
  int64_t reinitializations = 0;     // starts after a reset
  int64_t zero_velocity_frames = 0;  // frames held by the zero-motion factor
  // Scales found by the realignment after a monocular start in motion
  // (estimator/scale_realignment.h), applied or not.
  std::vector<RealignmentRecord> realignments;
};

// Why the run never started (the attempts' reasons, or why none was made),
// for a tool to print when summary.starts is empty.
std::string DescribeNoStart(const EstimatorSummary& summary);

class Estimator {
 public:
  // Throws std::invalid_argument when an options struct does not validate,
  // when cameras has not 1 or 2 entries, or when options.use_stereo asks for
  // a second camera that is not there.
  Estimator(const EstimatorOptions& options, const VisualFactorOptions& visual,
            const ImuNoise& noise, const PreintegrationOptions& preintegration,
            const std::vector<EstimatorCamera>& cameras);
  ~Estimator();

  // Buffers one IMU sample. A non-finite sample or one not after the last is
  // skipped and counted; one outside the measuring range is replaced from
  // its neighbours and counted; gaps are counted and logged.
  void AddImu(const ImuSample& sample);

  // Processes one camera frame. The IMU must already cover its stamp (plus
  // the time offset); otherwise it is skipped and counted, unless the IMU has
  // been silent for longer than max_sample_gap (a gap: the frame is tracked
  // on vision alone). Never throws on bad data.
  EstimatorOutput AddFrame(const FeatureFrame& frame);

  // The covariance of the newest pose, tangent [dt (world, m), dtheta (body,
  // rad)], from the window's information at the current estimate: the
  // window's problem (prior, IMU and visual factors) is rebuilt and handed
  // to estimator/pose_covariance.h. False before initialisation or when the
  // information is singular. It costs about one solver step: call it only
  // when the covariance is wanted.
  bool NewestPoseCovariance(Eigen::Matrix<double, 6, 6>* covariance);

  const EstimatorSummary& summary() const { return summary_; }
  const EstimatorOptions& options() const { return options_; }
  bool initialized() const { return initialized_; }
  // The current camera-IMU time offset [s].
  double time_offset_s() const { return window_.t_d; }
  // The extrinsic of camera 0 or 1, as estimated (or held fixed).
  Eigen::Isometry3d T_b_c(int camera) const { return window_.T_b_c(camera); }
  // The landmarks triangulated so far and not taken by
  // TakeFinishedLandmarks, by feature id, with world position [m] and
  // triangulation angle (estimator/landmark_map.h: each as when its anchor
  // frame was last marginalised, or as now when still in the window; a
  // world point as last solved, one row per feature id).
  // Landmarks lost to a reset, or removed as outliers before their anchor left,
  // are not in it. Read-only: it does not change the estimate.
  std::map<int64_t, MappedLandmark> MappedLandmarks() const {
    return landmark_map_.WithWindow(features_, PoseFn());
  }
  // Hands over the mapped landmarks that can no longer change (out of the
  // window, their tracks ended; estimator/landmark_map.h), by feature id,
  // and forgets them. A caller that writes them out as the run goes (as
  // vio_replay does landmarks.csv), then MappedLandmarks() at the end, gets
  // every landmark once and keeps only the window's in memory. Read-only
  // for the estimate.
  std::map<int64_t, MappedLandmark> TakeFinishedLandmarks() {
    return landmark_map_.TakeFinished();
  }

 private:
  // AddFrame before the landmark map learns which tracks ended.
  EstimatorOutput Step(const FeatureFrame& frame);
  bool TryInitialize(const FeatureFrame& frame, int64_t t_imu_ns);
  // The rest of the start (estimator_start.cc): the window from an
  // initialiser's states, the joint visual-inertial adjustment and its
  // checks. On failure the previous window is restored, the reason logged,
  // and false returned.
  bool StartFromInitialWindow(const InitialWindow& start, bool restart);
  // The adjustment's gauge (position, yaw) is held on the oldest frame of a
  // first start and on the newest of a re-start (`restart`), the frame
  // SetGauge gave the running pose.
  bool BuildWindow(const InitialWindow& start, bool restart);
  // Appends an initialiser's frames to *w as keyframes, ids from *next_id
  // on, preintegrated on `imu` from the previous frame's biases, their
  // observations to *features; adds the observations AddFrame skipped to
  // *skipped. False when a preintegration refuses its interval.
  bool AppendInitialFrames(const std::vector<InitialFrame>& frames,
                           const std::vector<ImuSample>& imu, Window* w,
                           FeatureManager* features, int64_t* next_id,
                           int64_t* skipped) const;
  InitFailure RefineStart(InitMethod method, InitDiagnostics* diagnostics,
                          double* value, double* limit);
  // After a reset while moving: feeds the in-motion initialiser and, when it
  // succeeds, replaces the restarted window (*out updated).
  void TryReinitialize(const FeatureFrame& frame, int64_t t_imu_ns,
                       EstimatorOutput* out);
  // Zero velocity (estimator_zero_velocity.cc): judges the newest frame and
  // adds the zero-motion factors of the window's still intervals.
  void MarkStillness(WindowFrame* newest);
  // The detector's verdict now, with the estimated speed [m/s] deciding
  // when the images give none.
  bool StillNow(double speed_m_s) const;
  void AddZeroVelocityFactors(WindowProblem* problem) const;
  void StartWindow(const FeatureFrame& frame, int64_t t_imu_ns,
                   const EstimatorOutput& state, double velocity_sigma);
  bool ProcessFrame(const FeatureFrame& frame, int64_t t_imu_ns,
                    EstimatorOutput* out);
  bool AppendFrame(const FeatureFrame& frame, int64_t t_imu_ns,
                   EstimatorOutput* predicted);
  // Adds the frame's observations, decides whether it is a keyframe and
  // appends it to the window.
  void PushFrame(std::unique_ptr<WindowFrame> f, const FeatureFrame& frame);
  // IMU gaps (estimator_gaps.cc).
  void NoteImuStep();
  ImuGap* GapBefore(int64_t t_ns);
  ImuGap* GapFor(int64_t t_imu_ns);
  bool ImuHasGap(int64_t t0_ns, int64_t t1_ns) const;
  bool AppendVisualFrame(const FeatureFrame& frame, int64_t t_imu_ns,
                         EstimatorOutput* predicted);
  bool RestartAfterGap(const FeatureFrame& frame, int64_t t_imu_ns,
                       EstimatorOutput* out);
  void ResumeImuAfterGap();
  void RefreshVisualVelocity(WindowFrame* newest) const;
  void DropSecondNewest();
  void Solve(WindowProblem* problem);
  Failure CheckStep(const EstimatorOutput& predicted, int landmarks,
                    int64_t t_ns) const;
  void Slide(const WindowProblem& problem);
  void MarginalizeOldest(const WindowProblem& problem,
                         const OutlierReport& outliers);
  void UpdateImuLinearization();
  void Realign(const FeatureFrame& frame, int64_t t_imu_ns);
  bool AdjustSpan(InitialWindow* span) const;
  WindowProblemSettings ProblemSettings() const;
  // landmarks.reuse_after_moving_start_s: the newest frame before
  // reuse_tracks_until_ns_ and no world point yet (estimator_window.cc).
  bool InReuseAfterMovingStart() const;
  void SetPriorOnOldest(double velocity_sigma);
  // keep_point (estimator_points.cc): marginalises the world points left
  // without sightings out of the prior and deletes them; a failure puts a
  // fresh state prior on the oldest frame, as MarginalizeOldest does.
  void ReleaseOrphanPoints();
  // Deletes every world point: for when prior_ is replaced by one that holds
  // none.
  void DropWorldPoints();
  // A fresh extrinsic prior at the current T_b_c (null when not estimated).
  void SetExtrinsicPrior();
  void Reset(int64_t t_ns, Failure reason);
  // The one place the window starts afresh while running: a reset (counted,
  // logged with its reason) and a new window at `frame` from `state`. An
  // initialiser in motion replaces the state guess here.
  void Restart(const FeatureFrame& frame, int64_t t_imu_ns, Failure reason,
               const EstimatorOutput& state);
  void TrimImu();
  // After a successful step: the window's IMU residuals into
  // noise_adaptation_ (when on, and only when every frame is IMU-linked).
  void AdaptImuNoise();
  CameraPoseFn PoseFn() const;
  EstimatorOutput OutputOf(const WindowFrame& frame, int64_t t_ns) const;

  EstimatorOptions options_;
  VisualFactorOptions visual_;
  ImuNoise noise_;  // as configured; new intervals use noise_adaptation_'s
  ImuNoiseAdaptation noise_adaptation_;
  PreintegrationOptions preintegration_;
  std::vector<EstimatorCamera> cameras_;

  Initialization init_;
  ZeroVelocityDetector zero_velocity_;
  ScaleRealignment realign_;
  bool newest_still_ = false;    // the last processed frame was still
  bool reinit_pending_ = false;  // a reset while moving awaits a re-start
  FeatureManager features_;
  LandmarkMap landmark_map_;
  Window window_;
  std::unique_ptr<MarginalizationPrior> prior_;
  std::vector<double*> prior_blocks_;
  // With estimate_extrinsics: the calibration's prior on T_b_c, until the
  // first marginalisation folds it into prior_ (then null).
  std::unique_ptr<MarginalizationPrior> extrinsic_prior_;
  std::vector<double*> extrinsic_prior_blocks_;
  // After an IMU gap: the biases of the frame where the IMU resumes, tied to
  // those before the gap, until the prior absorbs the tie (then null).
  std::unique_ptr<MarginalizationPrior> gap_bias_prior_;
  std::vector<double*> gap_bias_prior_blocks_;
  std::vector<ImuSample> imu_;
  ImuGlitchFilter imu_filter_;
  WindowSolver solver_;  // its buffers serve every step
  bool initialized_ = false;
  int64_t next_frame_id_ = 0;
  int64_t last_keyframe_id_ = -1;
  int64_t last_frame_t_ns_ = 0;
  bool have_frame_ = false;
  EstimatorOutput last_output_;
  EstimatorSummary summary_;
  // Until this camera stamp a keep_point* run handles the leaving keyframe's
  // landmarks as reuse: set by a start in motion (its own first
  // marginalisation included) to its stamp plus
  // landmarks.reuse_after_moving_start_s [ns].
  int64_t reuse_tracks_until_ns_ = INT64_MIN;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_ESTIMATOR_H_
