#include "tools/sim_images.h"

#include <chrono>
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

void CheckClearOfBoxes(const SceneLayout& layout,
                       const std::vector<Eigen::Vector3d>& positions_w,
                       double clearance_m) {
  for (size_t i = 0; i < layout.boxes.size(); ++i) {
    const SceneBox& b = layout.boxes[i];
    const Eigen::Vector3d lo(b.center_xy_m.x() - 0.5 * b.size_m.x(),
                             b.center_xy_m.y() - 0.5 * b.size_m.y(), 0.0);
    const Eigen::Vector3d hi = lo + b.size_m;
    for (const Eigen::Vector3d& p : positions_w) {
      // Distance from the point to the box (0 inside).
      const Eigen::Vector3d d =
          (lo - p).cwiseMax(p - hi).cwiseMax(Eigen::Vector3d::Zero());
      if (d.norm() < clearance_m) {
        throw std::invalid_argument(
            "render.boxes[" + std::to_string(i) +
            "]: the trajectory passes "
            "within " +
            std::to_string(clearance_m) + " m of the box (at " +
            std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " +
            std::to_string(p.z()) + ")");
      }
    }
  }
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
