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
#include "dataset/euroc_csv_stream.h"
#include "dataset/sim_folder.h"
#include "estimator/estimator.h"
#include "frontend/observation_builder.h"
#include "tools/command_line.h"
#include "tools/frame_pipeline.h"
#include "tools/image_tracks.h"
#include "tools/replay_health.h"
#include "tools/vio_replay_images.h"
#include "tools/vio_replay_report.h"

namespace {

namespace fs = std::filesystem;
using namespace vio;  // NOLINT(build/namespaces): a tool's main file

constexpr char kUsage[] =
    "usage: vio_replay [SEQUENCE] [--config FILE] [--out DIR]\n"
    "                  [--save-tracks FILE] [--strict] [--sequential]\n"
    "                  [--queue-frames N] [--help]\n"
    "\n"
    "Replays SEQUENCE (a folder in the EuRoC ASL layout whose cameras carry\n"
    "features.csv, e.g. written by vio_sim, or images: data.csv + data/,\n"
    "tracked by the frontend) through the estimator. Writes\n"
    "DIR/trajectory.tum, DIR/states.csv and DIR/landmarks.csv (the mapped\n"
    "landmarks: world x,y,z [m] and triangulation angle [deg], a row as\n"
    "each is finished, in no meaningful order); with\n"
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
    "  --imu-noise config|sequence  the IMU noise the estimator assumes:\n"
    "                 the config's imu: densities, or SEQUENCE's\n"
    "                 mav0/imu0/sensor.yaml (default: the config's\n"
    "                 imu.noise_from, config in the shipped files;\n"
    "                 sequence for the built-in simulated default)\n"
    "  --save-tracks FILE  the observations given to the estimator, in the\n"
    "                 features.csv format: cam0 to FILE, cam1 to FILE with\n"
    "                 .cam1 before the extension\n"
    "  --strict       refuse an IMU file whose stamps repeat or go backwards\n"
    "                 (default: such lines are dropped, counted and warned)\n"
    "  --sequential   images: read and track each frame, then estimate it,\n"
    "                 on one thread (default: reading, cam0 tracking and\n"
    "                 the stereo match each run on their own thread, ahead\n"
    "                 of the estimator; same output)\n"
    "  --queue-frames N  images: how many tracked frames the frontend may\n"
    "                 be ahead of the estimator (default 8, >= 1)\n"
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
  std::string save_tracks;     // empty: not written
  bool has_imu_noise = false;  // --imu-noise given: overrides imu.noise_from
  ImuNoiseSource imu_noise = ImuNoiseSource::kConfig;
  bool strict = false;       // refuse repeated or disordered IMU stamps
  PipelineOptions pipeline;  // images: frontend thread or --sequential
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
    } else if (a == "--imu-noise") {
      const std::string name = line.Value();
      if (!ParseImuNoiseSource(name, &args.imu_noise)) {
        throw std::invalid_argument(
            "--imu-noise expects config or sequence (got '" + name + "')");
      }
      args.has_imu_noise = true;
    } else if (a == "--strict") {
      args.strict = true;
    } else if (a == "--sequential") {
      args.pipeline.sequential = true;
    } else if (a == "--queue-frames") {
      const std::string value = line.Value();
      size_t used = 0;
      int n = 0;
      try {
        n = std::stoi(value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != value.size() || n < 1) {
        throw std::invalid_argument(
            "--queue-frames expects a whole number >= 1 (got '" + value + "')");
      }
      args.pipeline.queue_frames = n;
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

// The frontend options for tracking the images (announced on stdout).
FrontendOptions ImageFrontendOptions(int cameras_used, const Config& config,
                                     const PipelineOptions& pipeline) {
  if (!config.frontend_missing.empty()) {
    throw ConfigError(config.frontend_missing);
  }
  FrontendOptions f = config.frontend;
  f.stereo = cameras_used == 2;
  std::printf(
      "frontend: %s, %d features, min distance %.0f px, CLAHE %s, "
      "fundamental check %s; %s\n",
      f.stereo ? "stereo" : "mono", f.tracker.max_features,
      f.tracker.min_distance_px, f.tracker.clahe ? "on" : "off",
      f.tracker.fundamental_check ? "on" : "off",
      pipeline.sequential ? "sequential (one thread)"
                          : ("pipelined (reading, tracking and matching "
                             "threads, queue of " +
                             std::to_string(pipeline.queue_frames) + " frames)")
                                .c_str());
  return f;
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

// The IMU noise the estimator assumes: the config's (its imu: block, or
// the built-in defaults) or the sequence's imu0/sensor.yaml, as
// imu.noise_from or --imu-noise says; *description gives the values and
// their origin. With neither SEQUENCE nor --config (the built-in simulated
// default) the simulator's own noise: the built-in defaults assume a real
// MAV's, 6 times larger, which would under-weight the exact synthetic IMU.
ImuNoise ChooseImuNoise(const Args& args, const Config& config,
                        const EurocSequence& seq, std::string* description) {
  const bool simulated_default = args.sequence.empty() && args.config.empty();
  const ImuNoiseSource source = args.has_imu_noise  ? args.imu_noise
                                : simulated_default ? ImuNoiseSource::kSequence
                                                    : config.imu.noise_from;
  const bool from_config = source == ImuNoiseSource::kConfig;
  const ImuNoise& n = from_config ? config.imu.noise : seq.imu.noise;
  const std::string origin =
      from_config ? (args.config.empty() ? std::string("built-in defaults")
                                         : args.config + " imu:")
                  : JoinPath(seq.data.folder, "mav0/imu0/sensor.yaml");
  char text[512];
  std::snprintf(text, sizeof(text),
                "accelerometer %.4g m/s^2/sqrt(Hz), gyroscope %.4g "
                "rad/s/sqrt(Hz), random walks %.4g m/s^3/sqrt(Hz), %.4g "
                "rad/s^2/sqrt(Hz); from %s (chosen by %s)",
                n.accelerometer_noise_density, n.gyroscope_noise_density,
                n.accelerometer_random_walk, n.gyroscope_random_walk,
                origin.c_str(),
                args.has_imu_noise  ? "--imu-noise"
                : simulated_default ? "the built-in simulated sequence"
                                    : "imu.noise_from");
  *description = text;
  return n;
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
    // Checked now, read again at the end at the estimate's stamps only.
    read.keep_ground_truth = false;
    // Checked now (errors, counts, first stamps), read again as the replay
    // goes: the IMU by the estimator's feed, the image lists by the reading
    // thread; memory does not grow with the sequence's length.
    read.keep_imu = false;
    read.keep_image_lists = false;
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
    // Images are tracked while the estimator runs (ReplayImages); features
    // are read whole first.
    const FrontendOptions frontend =
        images ? ImageFrontendOptions(used, config, args.pipeline)
               : FrontendOptions();
    std::vector<FeatureFrame> frames;
    if (!images) frames = Observations(seq, used, &input.observations);
    if (!images && !args.save_tracks.empty()) {
      for (const std::string& file :
           SaveTracks(args.save_tracks, frames, used)) {
        std::printf("wrote %s\n", file.c_str());
      }
    }
    std::string noise_description;
    const ImuNoise noise =
        ChooseImuNoise(args, config, seq, &noise_description);
    std::printf("imu noise: %s\n", noise_description.c_str());
    Estimator estimator(config.estimator, config.visual, noise,
                        config.imu.preintegration, Cameras(seq, used));
    fs::create_directories(args.out);
    LandmarkStream landmarks(args.out);
    std::vector<EstimatorOutput> outputs;
    double wall_s = 0.0;
    double cpu_s = 0.0;
    // The loader counted the stamp filter's drops (input.imu_stamps); this
    // second pass over the same file counts the same and is not reported.
    ImuStampReport reread;
    ImuCsvStream imu_file(seq.data.imu_path, args.strict ? nullptr : &reread);
    const ImuSource imu = [&imu_file](ImuSample* s) {
      return imu_file.Next(s);
    };
    if (images) {
      ImageReplay replay = ReplayImages(
          seq, frontend, args.pipeline, !args.save_tracks.empty(), imu,
          &estimator, &landmarks, &image_summary, &input.observations);
      outputs = std::move(replay.outputs);
      frames = std::move(replay.frames);
      wall_s = replay.wall_s;
      cpu_s = replay.cpu_s;
      if (!args.save_tracks.empty()) {
        for (const std::string& file :
             SaveTracks(args.save_tracks, frames, used)) {
          std::printf("wrote %s\n", file.c_str());
        }
      }
    } else {
      Progress progress(frames.size(), frames.empty() ? 0 : frames[0].t_ns);
      const auto start = std::chrono::steady_clock::now();
      // RunSequence's order, the IMU read as it goes.
      StreamingRunner runner(&estimator, imu);
      outputs.reserve(frames.size());
      for (size_t i = 0; i < frames.size(); ++i) {
        outputs.push_back(runner.AddFrame(frames[i]));
        landmarks.Take(&estimator);
        progress.Update(i, outputs.back().t_ns);
      }
      wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                             start)
                   .count();
      progress.Finish();
    }
    const Trajectory estimate = WriteOutputs(args.out, outputs);
    landmarks.Finish(&estimator);
    for (const std::string& line : InputWarnings(
             input, estimator.summary(), config.estimator.imu_stream.range)) {
      std::printf("%s\n", line.c_str());
    }
    PrintSummary(estimator.summary(), outputs, wall_s);
    PrintStarts(estimator.summary());
    const int64_t with_pose = static_cast<int64_t>(estimate.size());
    std::printf(
        "%s",
        DescribeInputHandling(input, estimator.summary(), with_pose).c_str());
    std::printf("  time offset t_d      %.6f s (%s)\n",
                estimator.time_offset_s(),
                config.estimator.estimate_time_offset ? "estimated" : "fixed");
    std::printf("  imu noise            %s\n", noise_description.c_str());
    if (images) {
      std::printf("%s", DescribeImageReplay(image_summary, used, wall_s, cpu_s,
                                            args.pipeline.sequential)
                            .c_str());
    }
    const std::string late =
        LateStartWarning(estimator.summary(), seq.data.start_ns);
    if (!late.empty()) std::printf("%s\n", late.c_str());
    // Without two poses Evaluate prints the ATE as n/a (the status says why).
    if (!seq.data.ground_truth_path.empty()) {
      Evaluate(args.out, estimate,
               GroundTruthAt(seq.data.ground_truth_path, estimate),
               outputs.size());
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
