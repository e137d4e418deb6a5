// vio_direct: the user's direct method as a stereo odometry
// (frontend/direct_odometry.h) over an EuRoC-layout sequence's images; writes
// the body trajectory as TUM for vio_eval. Optionally runs the feature
// frontend on the same images in the same process, so that the two speeds
// come as a ratio measured under the same load. docs/direct.md.
//
//   vio_direct <sequence folder> [--out FILE] [options, see kUsage]

#include <Eigen/Geometry>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "config/euroc_sensor.h"
#include "dataset/euroc_reader.h"
#include "dataset/trajectory_io.h"
#include "frontend/direct_odometry.h"
#include "frontend/image_frontend.h"
#include "tools/command_line.h"

namespace {

constexpr char kUsage[] =
    "usage: vio_direct <sequence folder> [--out FILE] [--solver notes|ceres]\n"
    "                  [--no-variance-weight] [--stereo-weight W]\n"
    "                  [--sigma-intensity S] [--max-points N] [--frames N]\n"
    "                  [--log] [--frontend]\n"
    "  <sequence folder>     holds mav0/cam0 and mav0/cam1 (data.csv,\n"
    "                        data/, sensor.yaml); no IMU is read\n"
    "  --out FILE            TUM trajectory of the body (IMU) frame, the\n"
    "                        first frame's body as the world\n"
    "                        (default vio_direct.tum)\n"
    "  --solver S            notes: the notes' TrackFrame LM (default);\n"
    "                        ceres: Ceres' LM on PhotometricFactors\n"
    "  --no-variance-weight  W = (2 sigma_I^2)^-1 instead of the notes'\n"
    "                        (2 sigma_I^2 + (df/drho)^2 V)^-1\n"
    "  --stereo-weight W     weight of the right-image term E_s [-]\n"
    "                        (default 1, 0: left image only)\n"
    "  --sigma-intensity S   image noise sigma_I at full resolution [grey]\n"
    "                        (default 2.5)\n"
    "  --max-points N        at most N keyframe points per level [-]\n"
    "                        (default 0: all)\n"
    "  --frames N            only the first N cam0 images (default 0: all)\n"
    "  --log                 print each frame's iteration log (level, iter,\n"
    "                        error, lambda)\n"
    "  --frontend            also run the feature frontend (KLT stereo, the\n"
    "                        built-in defaults) on the same images and print\n"
    "                        the CPU-time ratio\n";

struct Arguments {
  std::string folder;
  std::string out = "vio_direct.tum";
  vio::DirectOdometryOptions options;
  int frames = 0;
  bool log = false;
  bool frontend = false;
};

Arguments Parse(int argc, char** argv) {
  Arguments args;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string a = line.Current();
    if (a == "--out") {
      args.out = line.Value();
    } else if (a == "--solver") {
      const std::string s = line.Value();
      if (!vio::ParseDirectSolver(s, &args.options.tracker.solver)) {
        throw std::invalid_argument("--solver expects notes or ceres (got '" +
                                    s + "')");
      }
    } else if (a == "--no-variance-weight") {
      args.options.tracker.variance_weight = false;
    } else if (a == "--stereo-weight") {
      args.options.tracker.stereo_weight = line.Number<double>();
    } else if (a == "--sigma-intensity") {
      args.options.tracker.sigma_intensity = line.Number<double>();
    } else if (a == "--max-points") {
      args.options.tracker.max_points = line.Number<int>();
    } else if (a == "--frames") {
      args.frames = line.Number<int>();
      if (args.frames < 0) throw std::invalid_argument("--frames must be >= 0");
    } else if (a == "--log") {
      args.log = true;
    } else if (a == "--frontend") {
      args.frontend = true;
    } else if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + a + " (see --help)");
    } else if (args.folder.empty()) {
      args.folder = a;
    } else {
      throw std::invalid_argument("more than one sequence folder (see --help)");
    }
  }
  if (args.folder.empty()) {
    throw std::invalid_argument("no sequence folder (see --help)");
  }
  std::string message;
  if (!args.options.Validate(&message)) {
    throw std::invalid_argument("bad option: " + message);
  }
  return args;
}

Eigen::Isometry3d BodyFromCamera(const vio::CameraCalibration& c) {
  Eigen::Isometry3d T_b_c = Eigen::Isometry3d::Identity();
  T_b_c.linear() = c.q_b_c.normalized().toRotationMatrix();
  T_b_c.translation() = c.t_b_c;
  return T_b_c;
}

// Skipped images by reason, per camera.
struct Skips {
  int missing = 0, unreadable = 0, wrong_size = 0;
};

// An 8-bit grey image of the calibration's size, or an empty Mat and a count.
cv::Mat ReadImage(const std::string& path, const vio::CameraCalibration& c,
                  Skips* skips) {
  cv::Mat image = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (image.empty()) {
    ++skips->unreadable;
    std::fprintf(stderr, "warning: %s: not a readable image, skipped\n",
                 path.c_str());
  } else if (image.cols != c.width || image.rows != c.height) {
    ++skips->wrong_size;
    std::fprintf(stderr, "warning: %s: %dx%d, not %dx%d, skipped\n",
                 path.c_str(), image.cols, image.rows, c.width, c.height);
    image = cv::Mat();
  }
  return image;
}

double Cpu(std::clock_t start) {
  return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
}

int Run(const Arguments& args) {
  const std::string mav0 = vio::JoinPath(args.folder, "mav0");
  vio::CameraCalibration cams[2];
  std::vector<vio::ImageEntry> lists[2];
  Skips skips[2];
  for (int c = 0; c < 2; ++c) {
    const std::string cam = vio::JoinPath(mav0, "cam" + std::to_string(c));
    cams[c] = vio::ReadEurocCameraYaml(vio::JoinPath(cam, "sensor.yaml"));
    lists[c] =
        vio::ReadEurocImageList(vio::JoinPath(cam, "data.csv"),
                                vio::JoinPath(cam, "data"), &skips[c].missing);
  }
  std::map<int64_t, const vio::ImageEntry*> right_by_stamp;
  for (const vio::ImageEntry& e : lists[1]) right_by_stamp[e.t_ns] = &e;

  vio::DirectOdometry odometry(cams[0], cams[1], args.options);
  const vio::CameraModel model0(cams[0]), model1(cams[1]);
  vio::ImageFrontend frontend(model0, &model1, vio::FrontendOptions());
  const Eigen::Isometry3d T_b_c = BodyFromCamera(cams[0]);
  vio::Trajectory trajectory;
  double direct_cpu = 0.0, frontend_cpu = 0.0;
  int frames = 0, unpaired = 0;
  for (const vio::ImageEntry& entry : lists[0]) {
    if (args.frames > 0 && frames >= args.frames) break;
    const cv::Mat left = ReadImage(entry.path, cams[0], &skips[0]);
    if (left.empty()) continue;
    cv::Mat right;
    const auto it = right_by_stamp.find(entry.t_ns);
    if (it != right_by_stamp.end()) {
      right = ReadImage(it->second->path, cams[1], &skips[1]);
    } else {
      ++unpaired;
    }
    std::clock_t start = std::clock();
    const vio::DirectFrame f = odometry.Process(entry.t_ns, left, right);
    direct_cpu += Cpu(start);
    if (args.frontend) {
      start = std::clock();
      frontend.Process(entry.t_ns, left, right);
      frontend_cpu += Cpu(start);
    }
    ++frames;
    // The body in the first frame's body: T_b0_b = T_b_c T_c0_c T_c_b.
    const Eigen::Isometry3d T_w_b = T_b_c * f.T_w_c * T_b_c.inverse();
    vio::StampedPose pose;
    pose.t_ns = entry.t_ns;
    pose.p_w_b = T_w_b.translation();
    pose.q_w_b = Eigen::Quaterniond(T_w_b.linear()).normalized();
    trajectory.push_back(pose);
    if (args.log) {
      std::printf("frame %d t %.3f s: %s%s%s\n", frames - 1, entry.t_ns * 1e-9,
                  f.tracked ? "tracked" : (f.lost ? "LOST" : "first"),
                  f.keyframe ? ", keyframe" : "",
                  f.lost && !f.track.failure.empty()
                      ? (" (" + f.track.failure + ")").c_str()
                      : "");
      for (const vio::TrackIteration& r : f.track.log) {
        std::printf("  level %d iter %2d error %.5f lambda %-8.4g %s\n",
                    r.level, r.iteration, r.error, r.lambda,
                    r.accepted ? "accepted" : "rejected");
      }
    }
  }
  vio::WriteTum(args.out, trajectory);
  const vio::DirectOdometrySummary& s = odometry.summary();
  std::printf(
      "summary: %d frames, %d keyframes, %d lost, %d weak keyframes, %d "
      "without a right image\n",
      s.frames, s.keyframes, s.lost, s.weak_keyframes, s.mono_frames);
  for (int c = 0; c < 2; ++c) {
    std::printf(
        "  cam%d images skipped: %d missing, %d unreadable, %d wrong "
        "size\n",
        c, skips[c].missing, skips[c].unreadable, skips[c].wrong_size);
  }
  std::printf("  cam0 images without a cam1 partner: %d\n", unpaired);
  const double n = frames > 0 ? frames : 1;
  std::printf("time: direct odometry %.1f ms/frame CPU (solver %s)\n",
              1e3 * direct_cpu / n,
              vio::DirectSolverName(args.options.tracker.solver));
  if (args.frontend) {
    std::printf(
        "time: feature frontend %.1f ms/frame CPU; direct / frontend = "
        "%.2f\n",
        1e3 * frontend_cpu / n,
        frontend_cpu > 0 ? direct_cpu / frontend_cpu : 0.0);
  }
  std::printf("wrote %s (%zu poses)\n", args.out.c_str(), trajectory.size());
  return s.frames > 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(Parse(argc, argv));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
