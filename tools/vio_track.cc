// vio_track: runs the image frontend alone over an EuRoC-layout sequence and
// reports what it tracked and how fast, and how accurately: against the
// exact truth of a rendered sequence (mav0/render/) and against ground-truth
// poses (epipolar error); optionally saves the tracks in the features.csv
// format so the sequence can be replayed without images.
//
//   vio_track <sequence folder> [--config FILE] [--save-tracks FILE]
//             [--ground-truth FILE] [--max-gap N] [--strict]

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/euroc_sequence.h"
#include "config/frontend_config.h"
#include "dataset/trajectory_io.h"
#include "render/scene_file.h"
#include "tools/command_line.h"
#include "tools/image_tracks.h"
#include "tools/track_report.h"

namespace {

constexpr char kUsage[] =
    "usage: vio_track <sequence folder> [--config FILE] [--save-tracks FILE]\n"
    "                 [--ground-truth FILE] [--max-gap N] [--strict]\n"
    "  --config FILE       YAML with a frontend: block, e.g.\n"
    "                      config/euroc_mono.yaml (default: built-in\n"
    "                      defaults = config/default.yaml, stereo)\n"
    "  --save-tracks FILE  cam0 observations to FILE, cam1 to FILE with .cam1\n"
    "                      before the extension (features.csv format)\n"
    "  --ground-truth FILE body poses (TUM or EuRoC ground truth) for the\n"
    "                      epipolar error of the tracks (default: the\n"
    "                      folder's state_groundtruth_estimate0, if any)\n"
    "  --max-gap N         epipolar error for tracks 1..N frames apart (6)\n"
    "  --strict            refuse an IMU file whose stamps repeat or go\n"
    "                      backwards (default: such lines are dropped)\n"
    "A rendered sequence (vio_sim --render) also gets the tracks' error\n"
    "against its exact truth (mav0/render/). The IMU is not used: a folder\n"
    "without imu0/ is tracked all the same.\n";

struct Arguments {
  std::string folder;
  std::string config;  // empty: built-in defaults
  std::string save_tracks;
  std::string ground_truth;  // empty: the folder's, if any
  int max_gap = 6;
  bool strict = false;  // refuse repeated or disordered IMU stamps
};

Arguments Parse(int argc, char** argv) {
  Arguments args;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string a = line.Current();
    if (a == "--config") {
      args.config = line.Value();
    } else if (a == "--save-tracks") {
      args.save_tracks = line.Value();
    } else if (a == "--ground-truth") {
      args.ground_truth = line.Value();
    } else if (a == "--max-gap") {
      const std::string v = line.Value();
      char* end = nullptr;
      const long gap = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || gap < 1 || gap > 100) {
        throw std::runtime_error(
            "--max-gap expects an integer in [1, 100] "
            "(got '" +
            v + "')");
      }
      args.max_gap = static_cast<int>(gap);
    } else if (a == "--strict") {
      args.strict = true;
    } else if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (!a.empty() && a[0] == '-') {
      throw std::runtime_error("unknown option " + a + "\n" + kUsage);
    } else if (args.folder.empty()) {
      args.folder = a;
    } else {
      throw std::runtime_error("more than one sequence folder\n" +
                               std::string(kUsage));
    }
  }
  if (args.folder.empty()) {
    throw std::runtime_error("no sequence folder\n" + std::string(kUsage));
  }
  return args;
}

void PrintCounts(const char* name, const vio::ImageCounts& c) {
  std::printf(
      "  %s images: %lld used; skipped: %lld missing, %lld "
      "unreadable, %lld wrong size; %lld without a cam0 partner\n",
      name, static_cast<long long>(c.used), static_cast<long long>(c.missing),
      static_cast<long long>(c.unreadable),
      static_cast<long long>(c.wrong_size), static_cast<long long>(c.unpaired));
}

// The reports against truth that the folder (or --ground-truth) allows.
// What the accuracy reports need, read before tracking so that a bad truth
// or ground-truth file stops the run at once.
struct AccuracyInputs {
  bool rendered = false;
  vio::RenderTruth truth;        // when rendered
  vio::Trajectory ground_truth;  // empty: no epipolar report
};

AccuracyInputs ReadAccuracyInputs(const Arguments& args,
                                  const vio::EurocSequence& sequence) {
  AccuracyInputs in;
  in.rendered = vio::HasRenderTruth(args.folder);
  if (in.rendered) in.truth = vio::ReadRenderTruth(args.folder);
  if (!args.ground_truth.empty()) {
    in.ground_truth = vio::ReadTrajectory(args.ground_truth);
  } else {
    for (const vio::StampedState& s : sequence.data.ground_truth) {
      in.ground_truth.push_back({s.t_ns, s.p_w_b, s.q_w_b});
    }
  }
  return in;
}

void PrintAccuracy(const Arguments& args, const vio::EurocSequence& sequence,
                   const AccuracyInputs& in,
                   const std::vector<vio::FeatureFrame>& frames) {
  if (in.rendered) {
    std::printf("%s", vio::DescribeTrackTruth(vio::TrackTruthOfRenderedSequence(
                                                  sequence, in.truth, frames))
                          .c_str());
  } else {
    std::printf(
        "%s",
        vio::DescribeTrackLengths(vio::ComputeTrackLengths(frames)).c_str());
  }
  const vio::Trajectory& ground_truth = in.ground_truth;
  if (ground_truth.empty()) return;
  std::printf("%s", vio::DescribeEpipolarError(
                        vio::EpipolarErrorAgainst(sequence, frames,
                                                  ground_truth, args.max_gap))
                        .c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Arguments args = Parse(argc, argv);
    const vio::FrontendOptions options =
        args.config.empty() ? vio::FrontendOptions()
                            : vio::LoadFrontendOptions(args.config);
    std::printf(
        "config %s: %s, %d features, min distance %.1f px, "
        "CLAHE %s\n",
        args.config.empty() ? "(built-in defaults)" : args.config.c_str(),
        options.stereo ? "stereo" : "mono", options.tracker.max_features,
        options.tracker.min_distance_px, options.tracker.clahe ? "on" : "off");
    // The frontend needs no IMU: a folder without imu0/ is tracked too.
    vio::EurocReadOptions read;
    read.require_imu = false;
    read.strict = args.strict;
    const vio::EurocSequence sequence =
        vio::LoadEurocSequence(args.folder, read);
    if (!sequence.data.has_imu) {
      std::printf("imu0: none (vio_track does not use the IMU)\n");
    }
    if (sequence.data.imu_stamps.dropped() > 0) {
      std::printf(
          "warning: %s/mav0/imu0/data.csv: %d IMU line(s) dropped for their "
          "stamps (repeated or out of order; --strict refuses them)\n",
          args.folder.c_str(), sequence.data.imu_stamps.dropped());
    }
    const AccuracyInputs accuracy = ReadAccuracyInputs(args, sequence);
    vio::ImageTrackingSummary summary;
    std::vector<vio::FeatureFrame> frames =
        vio::TrackEurocImages(sequence, options, &summary);
    if (!args.save_tracks.empty()) {
      for (const std::string& file :
           vio::SaveTracks(args.save_tracks, frames, options.stereo ? 2 : 1)) {
        std::printf("wrote %s\n", file.c_str());
      }
    }
    std::printf(
        "summary: %lld frames (%lld stereo), %lld + %lld "
        "observations, %lld images skipped\n",
        static_cast<long long>(summary.frames),
        static_cast<long long>(summary.stereo_frames),
        static_cast<long long>(summary.observations[0]),
        static_cast<long long>(summary.observations[1]),
        static_cast<long long>(summary.skipped()));
    PrintCounts("cam0", summary.cameras[0]);
    if (options.stereo) PrintCounts("cam1", summary.cameras[1]);
    const double n = static_cast<double>(summary.frames);
    std::printf(
        "time: frontend %.2f ms/frame wall (%.1f frames/s), %.2f "
        "ms/frame CPU (%.1f frames/s); image decoding %.2f ms/frame "
        "wall\n",
        n > 0 ? 1e3 * summary.track_seconds / n : 0.0,
        summary.track_seconds > 0 ? n / summary.track_seconds : 0.0,
        n > 0 ? 1e3 * summary.track_cpu_seconds / n : 0.0,
        summary.track_cpu_seconds > 0 ? n / summary.track_cpu_seconds : 0.0,
        n > 0 ? 1e3 * summary.read_seconds / n : 0.0);
    PrintAccuracy(args, sequence, accuracy, frames);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
