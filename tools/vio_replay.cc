// vio_replay: the main job. Replays a sequence folder (EuRoC ASL layout with
// features.csv, e.g. one written by vio_sim, or with images, tracked by the
// frontend) through the estimator, writes the
// trajectory (TUM and state CSV) and, when the folder has ground truth,
// evaluates it (posyaw alignment, ATE, RPE) and draws the plot. With no
// sequence it simulates the default preset into a cache folder first.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/estimator_config.h"
#include "config/euroc_sequence.h"
#include "config/frontend_config.h"
#include "config/imu_config.h"
#include "config/visual_config.h"
#include "dataset/landmarks_io.h"
#include "dataset/sim_folder.h"
#include "estimator/sequence_runner.h"
#include "frontend/observation_builder.h"
#include "tools/command_line.h"
#include "tools/image_tracks.h"
#include "tools/replay_health.h"
#include "tools/vio_replay_report.h"

namespace {

namespace fs = std::filesystem;
using namespace vio;  // NOLINT(build/namespaces): a tool's main file

constexpr char kUsage[] =
    "usage: vio_replay [SEQUENCE] [--config FILE] [--out DIR]\n"
    "                  [--save-tracks FILE] [--strict] [--help]\n"
    "\n"
    "Replays SEQUENCE (a folder in the EuRoC ASL layout whose cameras carry\n"
    "features.csv, e.g. written by vio_sim, or images: data.csv + data/,\n"
    "tracked by the frontend) through the estimator. Writes\n"
    "DIR/trajectory.tum, DIR/states.csv and DIR/landmarks.csv (the mapped\n"
    "landmarks: world x,y,z [m] and triangulation angle [deg]); with\n"
    "ground truth in the folder\n"
    "also DIR/evaluation.png, and prints ATE and RPE (posyaw alignment).\n"
    "Without SEQUENCE it simulates the default preset (vio_sim's built-in\n"
    "defaults) into " VIO_REPLAY_CACHE
    " (made when missing) and replays it.\n"
    "\n"
    "  --config FILE  configuration with imu:, visual: and estimator: blocks\n"
    "                 (default: the built-in defaults = config/default.yaml;\n"
    "                 config/stereo.yaml for stereo)\n"
    "  --out DIR      output folder (default vio_replay_out)\n"
    "  --save-tracks FILE  the observations given to the estimator, in the\n"
    "                 features.csv format: cam0 to FILE, cam1 to FILE with\n"
    "                 .cam1 before the extension\n"
    "  --strict       refuse an IMU file whose stamps repeat or go backwards\n"
    "                 (default: such lines are dropped, counted and warned)\n"
    "\n"
    "Bad input is survived and reported (docs/robustness.md): a warning\n"
    "line per fault, counts in the summary. Exit status: 0 when most frames\n"
    "got a pose; 3 when the estimator never initialised; 4 when it did but\n"
    "most frames got no pose (the reason is printed); 1 on an error. Fewer\n"
    "than half of the frames initialised (a late start) prints a warning.\n"
    "\n"
    "Images: the frontend: block of the config (built-in defaults without\n"
    "--config) sets the tracker; mono or stereo follows estimator.use_stereo.\n"
    "Missing, unreadable and wrong-size images are skipped and counted.\n"
    "\n"
    "One thread (estimator.solver.num_threads: 1) makes runs bit-for-bit\n"
    "repeatable on the same machine.\n";

struct Args {
  std::string sequence;  // empty: the simulated default
  std::string config;    // empty: built-in defaults
  std::string out = "vio_replay_out";
  std::string save_tracks;  // empty: not written
  bool strict = false;      // refuse repeated or disordered IMU stamps
  bool help = false;
};

Args ParseArgs(int argc, char** argv) {
  Args args;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string a = line.Current();
    if (a == "--config") {
      args.config = line.Value();
    } else if (a == "--out") {
      args.out = line.Value();
    } else if (a == "--save-tracks") {
      args.save_tracks = line.Value();
    } else if (a == "--strict") {
      args.strict = true;
    } else if (a == "--help" || a == "-h") {
      args.help = true;
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + a + " (see --help)");
    } else if (args.sequence.empty()) {
      args.sequence = a;
    } else {
      throw std::invalid_argument("more than one SEQUENCE (" + args.sequence +
                                  ", " + a + ")");
    }
  }
  return args;
}

struct Config {
  ImuConfig imu;
  VisualFactorOptions visual;
  EstimatorOptions estimator;
  FrontendOptions frontend;
  std::string frontend_missing;  // non-empty: the file has no frontend: block
};

Config LoadConfig(const std::string& path) {
  Config c;
  if (path.empty()) return c;
  const YamlNode root = YamlNode::LoadFile(path);
  c.imu = LoadImuConfig(root);
  c.visual = ReadVisualOptions(root);
  c.estimator = ReadEstimatorOptions(root);
  // Only image sequences need the frontend: its block is required then.
  if (root.Has("frontend")) {
    c.frontend = ReadFrontendOptions(root.Child("frontend"));
  } else {
    c.frontend_missing = root.Where("frontend") +
                         " is missing (needed to "
                         "track images)";
  }
  return c;
}

std::string SequenceFolder(const Args& args) {
  if (!args.sequence.empty()) return args.sequence;
  const std::string cache = VIO_REPLAY_CACHE;
  if (!fs::exists(fs::path(cache) / "mav0")) {
    std::printf("simulating the default preset into %s\n", cache.c_str());
    fs::create_directories(cache);
    SimulateToFolder(SimulatorOptions(), cache);
  }
  return cache;
}

// True when every used camera has images and none has features.csv: the
// frontend tracks them.
bool UsesImages(const EurocSequence& seq, int cameras_used) {
  for (int c = 0; c < cameras_used; ++c) {
    const EurocCamera& camera = seq.data.cameras[c];
    if (camera.has_features || !camera.has_images) return false;
  }
  return true;
}

// Frames with xy and velocity, tracked from the images.
std::vector<FeatureFrame> TrackedObservations(
    const EurocSequence& seq, int cameras_used, Config config,
    ImageTrackingSummary* summary, ObservationBuilderSummary* removed) {
  if (!config.frontend_missing.empty()) {
    throw ConfigError(config.frontend_missing);
  }
  config.frontend.stereo = cameras_used == 2;
  const FrontendOptions& f = config.frontend;
  std::printf(
      "frontend: %s, %d features, min distance %.0f px, CLAHE %s, "
      "fundamental check %s\n",
      f.stereo ? "stereo" : "mono", f.tracker.max_features,
      f.tracker.min_distance_px, f.tracker.clahe ? "on" : "off",
      f.tracker.fundamental_check ? "on" : "off");
  return ImageObservations(seq, config.frontend, summary, removed);
}

// Frames with xy and velocity, from each camera's features.csv.
std::vector<FeatureFrame> Observations(const EurocSequence& seq,
                                       int cameras_used,
                                       ObservationBuilderSummary* removed) {
  std::vector<CameraModel> models;
  for (int c = 0; c < cameras_used; ++c) {
    if (!seq.data.cameras[c].has_features) {
      throw std::runtime_error(seq.data.cameras[c].folder +
                               " has no features.csv (and not every used "
                               "camera has images to track)");
    }
    models.emplace_back(seq.cameras[c]);
  }
  ObservationBuilder builder(models);
  std::vector<FeatureFrame> frames = MergedFeatureFrames(seq.data);
  for (FeatureFrame& f : frames) {
    auto& obs = f.observations;
    obs.erase(std::remove_if(obs.begin(), obs.end(),
                             [&](const FeatureObservation& o) {
                               return o.camera >= cameras_used;
                             }),
              obs.end());
    builder.Process(&f);
  }
  *removed = builder.summary();
  return frames;
}

std::vector<EstimatorCamera> Cameras(const EurocSequence& seq, int used) {
  std::vector<EstimatorCamera> cameras;
  for (int c = 0; c < used; ++c) {
    const CameraModel model(seq.cameras[c]);
    EstimatorCamera e;
    e.T_b_c.linear() = seq.cameras[c].q_b_c.toRotationMatrix();
    e.T_b_c.translation() = seq.cameras[c].t_b_c;
    e.focal_px = model.focal();
    cameras.push_back(e);
  }
  return cameras;
}

// DIR/landmarks.csv: the world positions of the landmarks the run mapped
// and their triangulation angles (Estimator::MappedLandmarks), for vio_plan
// --replay.
void WriteLandmarks(const std::string& dir, const Estimator& estimator) {
  std::vector<LandmarkRow> points;
  for (const auto& [id, m] : estimator.MappedLandmarks()) {
    points.push_back({m.p_w, m.parallax_deg});
  }
  const std::string path = (fs::path(dir) / "landmarks.csv").string();
  WriteLandmarksCsv(path, points);
  std::printf("wrote %s (%zu landmarks)\n", path.c_str(), points.size());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = ParseArgs(argc, argv);
    if (args.help) {
      std::printf("%s", kUsage);
      return 0;
    }
    Config config = LoadConfig(args.config);
    ApplyImuConfig(config.imu, &config.estimator);
    const std::string folder = SequenceFolder(args);
    EurocReadOptions read;
    read.strict = args.strict;
    const EurocSequence seq = LoadEurocSequence(folder, read);
    const int used = config.estimator.use_stereo ? 2 : 1;
    if (static_cast<int>(seq.cameras.size()) < used) {
      throw std::runtime_error(folder +
                               ": estimator.use_stereo needs cam0 and "
                               "cam1, the sequence has " +
                               std::to_string(seq.cameras.size()) +
                               " camera(s)");
    }
    std::printf("sequence %s\n%s", folder.c_str(),
                DescribeEstimatorOptions(config.estimator).c_str());
    const bool images = UsesImages(seq, used);
    ImageTrackingSummary image_summary;
    InputReport input;
    input.imu_file = JoinPath(folder, "mav0/imu0/data.csv");
    input.imu_stamps = seq.data.imu_stamps;
    input.start_ns = seq.data.start_ns;
    const std::vector<FeatureFrame> frames =
        images ? TrackedObservations(seq, used, config, &image_summary,
                                     &input.observations)
               : Observations(seq, used, &input.observations);
    if (!args.save_tracks.empty()) {
      for (const std::string& file :
           SaveTracks(args.save_tracks, frames, used)) {
        std::printf("wrote %s\n", file.c_str());
      }
    }
    Estimator estimator(config.estimator, config.visual, seq.imu.noise,
                        config.imu.preintegration, Cameras(seq, used));
    Progress progress(frames);
    const auto start = std::chrono::steady_clock::now();
    const std::vector<EstimatorOutput> outputs = RunSequence(
        &estimator, seq.data.imu, frames,
        [&](size_t i, const EstimatorOutput&) { progress.Update(i); });
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
    progress.Finish();
    fs::create_directories(args.out);
    const Trajectory estimate = WriteOutputs(args.out, outputs);
    WriteLandmarks(args.out, estimator);
    for (const std::string& line : InputWarnings(
             input, estimator.summary(), config.estimator.imu_stream.range)) {
      std::printf("%s\n", line.c_str());
    }
    PrintSummary(estimator.summary(), frames, wall_s);
    PrintStarts(estimator.summary());
    const int64_t with_pose = static_cast<int64_t>(estimate.size());
    std::printf(
        "%s",
        DescribeInputHandling(input, estimator.summary(), with_pose).c_str());
    std::printf("  time offset t_d      %.6f s (%s)\n",
                estimator.time_offset_s(),
                config.estimator.estimate_time_offset ? "estimated" : "fixed");
    if (images) {
      const double n = static_cast<double>(image_summary.frames);
      std::printf("%s", DescribeImageTracking(image_summary, used).c_str());
      std::printf(
          "  frontend    %.2f ms/frame CPU, %.2f ms wall (%.1f "
          "frames/s); image decoding %.2f ms/frame\n",
          n > 0 ? 1e3 * image_summary.track_cpu_seconds / n : 0.0,
          n > 0 ? 1e3 * image_summary.track_seconds / n : 0.0,
          image_summary.track_seconds > 0 ? n / image_summary.track_seconds
                                          : 0.0,
          n > 0 ? 1e3 * image_summary.read_seconds / n : 0.0);
      const double total_s =
          image_summary.read_seconds + image_summary.track_seconds + wall_s;
      std::printf(
          "  full replay %.1f frames/s wall (images, frontend and "
          "estimator)\n",
          total_s > 0 ? n / total_s : 0.0);
    }
    const std::string late =
        LateStartWarning(estimator.summary(), seq.data.start_ns);
    if (!late.empty()) std::printf("%s\n", late.c_str());
    // Without two poses there is nothing to align (the status says why).
    if (!seq.data.ground_truth.empty() && estimate.size() >= 2) {
      Evaluate(args.out, estimate, seq.data.ground_truth, frames.size());
    }
    std::string why;
    const int status = ReplayExitStatus(estimator.summary(), with_pose, &why);
    if (status != 0) std::fprintf(stderr, "error: %s\n", why.c_str());
    return status;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
