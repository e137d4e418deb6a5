#include "tools/sim_images.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "config/render_config.h"
#include "dataset/csv.h"
#include "dataset/euroc_image_writer.h"
#include "dataset/euroc_reader.h"
#include "dataset/trajectory_io.h"
#include "render/scene_file.h"
#include "render/texture_atlas.h"

namespace vio {
namespace {

StampedPose ToStampedPose(int64_t t_ns, const Eigen::Isometry3d& T_w_b) {
  StampedPose p;
  p.t_ns = t_ns;
  p.p_w_b = T_w_b.translation();
  p.q_w_b = Eigen::Quaterniond(T_w_b.linear()).normalized();
  return p;
}

void WriteText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) throw DatasetError(path + ": cannot write the file");
}

}  // namespace

BodyPoseAt TrajectoryBodyPose(std::shared_ptr<const TrajectorySource> source,
                              int64_t start_ns, double duration_s) {
  return [source, start_ns, duration_s](int64_t t_ns) {
    const double t = std::clamp(static_cast<double>(t_ns - start_ns) * 1e-9,
                                0.0, duration_s);
    const SimState s = source->At(t);
    Eigen::Isometry3d T_w_b = Eigen::Isometry3d::Identity();
    T_w_b.linear() = s.q_w_b.normalized().toRotationMatrix();
    T_w_b.translation() = s.p_w_b;
    return T_w_b;
  };
}

SceneLayout LayoutClearOfPath(const Eigen::Vector3d& min_corner,
                              const Eigen::Vector3d& max_corner,
                              const std::vector<SceneBox>& boxes,
                              const std::vector<Eigen::Vector3d>& path_w,
                              double clearance_m, std::vector<int>* left_out) {
  SceneLayout layout;
  layout.min_corner = min_corner;
  layout.max_corner = max_corner;
  const Eigen::Vector3d c = layout.FloorCentre();
  for (size_t i = 0; i < boxes.size(); ++i) {
    const SceneBox& b = boxes[i];
    const Eigen::Vector3d lo(c.x() + b.center_xy_m.x() - 0.5 * b.size_m.x(),
                             c.y() + b.center_xy_m.y() - 0.5 * b.size_m.y(),
                             c.z());
    const Eigen::Vector3d hi = lo + b.size_m;
    bool clear = true;
    for (const Eigen::Vector3d& p : path_w) {
      // Distance from the point to the box (0 inside).
      const Eigen::Vector3d d =
          (lo - p).cwiseMax(p - hi).cwiseMax(Eigen::Vector3d::Zero());
      if (d.norm() < clearance_m) {
        clear = false;
        break;
      }
    }
    SceneLayout trial = layout;
    trial.boxes.push_back(b);
    std::string message;
    if (clear && trial.Validate(&message)) {
      layout = trial;
    } else {
      left_out->push_back(static_cast<int>(i));
    }
  }
  return layout;
}

std::vector<Eigen::Vector3d> SimulationPath(const Simulation& simulation) {
  std::vector<Eigen::Vector3d> path;
  const SimCameraOptions& c = simulation.options.camera;
  for (const StampedState& s : simulation.ground_truth) {
    path.push_back(s.p_w_b);
    path.push_back(s.p_w_b + s.q_w_b * c.cam0.t_b_c);
    if (c.stereo) path.push_back(s.p_w_b + s.q_w_b * c.cam1.t_b_c);
  }
  return path;
}

SimImagesSummary RenderSimulationImages(const Simulation& simulation,
                                        const SceneLayout& layout,
                                        const RenderOptions& options,
                                        const BodyPoseAt& body_pose,
                                        const std::string& folder) {
  const SimulatorOptions& o = simulation.options;
  std::vector<CameraCalibration> cameras = {o.camera.cam0};
  if (o.camera.stereo) cameras.push_back(o.camera.cam1);
  std::vector<int64_t> stamps;
  for (const FeatureFrame& f : simulation.frames) stamps.push_back(f.t_ns);
  return RenderSequenceImages(stamps, cameras, layout, options,
                              o.camera.time_offset_s, o.seed, body_pose,
                              folder);
}

std::string DescribeSimImages(const SimImagesSummary& s, int cameras,
                              const std::vector<int>& boxes_left_out) {
  const double images = static_cast<double>(s.render.images);
  const double ms = images > 0 ? 1e3 * s.render.cpu_seconds / images : 0.0;
  char line[400];
  std::snprintf(
      line, sizeof(line),
      "render: %lld frames x %d camera(s), %.2f ms CPU per image (%.1f "
      "images/s on one core); blur: %.2f renders per frame on average, max "
      "%d; textures %.2f s; PNG writing %.2f ms per image\n",
      static_cast<long long>(s.render.frames), cameras, ms,
      ms > 0 ? 1e3 / ms : 0.0,
      s.render.frames > 0
          ? static_cast<double>(s.render.blur_samples) / s.render.frames
          : 0.0,
      s.render.max_blur_samples, s.texture_seconds,
      images > 0 ? 1e3 * s.write_seconds / images : 0.0);
  std::string text = line;
  for (const int i : boxes_left_out) {
    text += "render: boxes[" + std::to_string(i) +
            "] left out (too near the trajectory or outside the room)\n";
  }
  return text;
}

SimImagesSummary RenderSequenceImages(
    const std::vector<int64_t>& frame_stamps,
    const std::vector<CameraCalibration>& cameras, const SceneLayout& layout,
    const RenderOptions& options, double time_offset_s, uint32_t seed,
    const BodyPoseAt& body_pose, const std::string& folder) {
  SimImagesSummary summary;
  const std::clock_t texture_start = std::clock();
  const std::string texture_folder = options.texture_folder.empty()
                                         ? BuiltInTextureFolder()
                                         : options.texture_folder;
  const TexturedScene scene = MakeTexturedScene(
      MakeRoomScene(layout), LoadTextureCrops(texture_folder), options, seed);
  summary.texture_seconds =
      static_cast<double>(std::clock() - texture_start) / CLOCKS_PER_SEC;

  SequenceRenderer renderer(cameras, &scene, options, time_offset_s, seed);
  const std::string mav0 = JoinPath(folder, "mav0");
  std::vector<EurocImageWriter> writers;
  for (size_t c = 0; c < cameras.size(); ++c) {
    writers.emplace_back(JoinPath(mav0, "cam" + std::to_string(c)));
  }
  Trajectory frame_poses;
  RenderedFrame frame;  // its images are reused from frame to frame
  for (const int64_t t_ns : frame_stamps) {
    renderer.Render(t_ns, body_pose, &frame);
    const auto write_start = std::chrono::steady_clock::now();
    for (size_t c = 0; c < cameras.size(); ++c) {
      writers[c].Write(t_ns, frame.images[c]);
    }
    summary.write_seconds += std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - write_start)
                                 .count();
    frame_poses.push_back(ToStampedPose(t_ns, frame.T_w_b));
  }
  for (EurocImageWriter& w : writers) w.Close();
  summary.render = renderer.stats();

  const std::string truth = RenderTruthFolder(folder);
  std::error_code ec;
  std::filesystem::create_directories(truth, ec);
  if (ec) throw DatasetError(truth + ": cannot create the folder");
  WriteSceneCsv(JoinPath(truth, "scene.csv"), scene.geometry);
  WriteTum(JoinPath(truth, "frame_poses.tum"), frame_poses);
  WriteText(JoinPath(truth, "render.yaml"),
            "# the options these images were rendered with (vio_sim)\n" +
                RenderOptionsToYaml(options));
  return summary;
}

}  // namespace vio
