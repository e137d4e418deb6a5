#ifndef VIO_TOOLS_VIO_REPLAY_REPORT_H_
#define VIO_TOOLS_VIO_REPLAY_REPORT_H_

// What vio_replay shows and writes: the progress display, the output files,
// the run summary and the evaluation against ground truth.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "dataset/landmarks_io.h"
#include "dataset/trajectory.h"
#include "estimator/estimator.h"

namespace vio {

// A progress bar on a terminal (frames, percent, real-time factor), redrawn
// in place; plain lines at every 10 % otherwise.
class Progress {
 public:
  // total: the frames expected; first_ns: the stamp of the first [ns].
  Progress(size_t total, int64_t first_ns);
  // After frame `frame_index` (stamp t_ns) was estimated.
  void Update(size_t frame_index, int64_t t_ns);
  void Finish();

 private:
  size_t total_;
  int64_t first_ns_;
  bool terminal_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

// DIR/landmarks.csv: the world positions of the landmarks the run mapped
// and their triangulation angles (Estimator::MappedLandmarks), for vio_plan
// --replay. Written as the run goes: after each frame the landmarks the
// estimator has finished (TakeFinishedLandmarks), at the end those still in
// its map; so the rows come in the order the landmarks were finished (by
// feature id within a frame), and none is kept in memory once written.
class LandmarkStream {
 public:
  explicit LandmarkStream(const std::string& dir);

  // The landmarks `estimator` finished since the last call.
  void Take(Estimator* estimator);
  // Those still in its map; closes the file and says how many rows it has.
  void Finish(Estimator* estimator);

 private:
  std::string path_;
  LandmarksCsvWriter writer_;
};

// Writes DIR/trajectory.tum and DIR/states.csv from the initialised outputs
// and returns their poses.
Trajectory WriteOutputs(const std::string& dir,
                        const std::vector<EstimatorOutput>& outputs);

// frames, keyframes, resets (with reasons), solver time per step (median,
// p95, max), marginalisation time, wall time and real-time factor (over the
// span of the outputs' stamps, one output per frame).
void PrintSummary(const EstimatorSummary& summary,
                  const std::vector<EstimatorOutput>& outputs, double wall_s);

// The starts (first and re-initialisations) with their figures, and the
// failed start attempts counted by method and reason.
void PrintStarts(const EstimatorSummary& summary);

// The ground-truth states Evaluate needs for `estimate`, read from the
// EuRoC ground-truth file a state at a time (eval/association.h,
// NearestGroundTruth): one per estimate pose, so that memory follows the
// trajectory, not the ground truth's rate. The whole file when it holds
// fewer states than the estimate has poses.
std::vector<StampedState> GroundTruthAt(const std::string& path,
                                        const Trajectory& estimate);

// Associates, aligns (posyaw), prints ATE and RPE (1 m of travel) and writes
// DIR/evaluation.png. The ATE line says how many of the sequence's `frames`
// it covers (poses associated with the ground truth).
void Evaluate(const std::string& dir, const Trajectory& estimate,
              const std::vector<StampedState>& ground_truth, size_t frames);

}  // namespace vio

#endif  // VIO_TOOLS_VIO_REPLAY_REPORT_H_
