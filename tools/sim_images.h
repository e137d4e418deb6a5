#ifndef VIO_TOOLS_SIM_IMAGES_H_
#define VIO_TOOLS_SIM_IMAGES_H_

// vio_sim --render: the images of a simulated sequence, rendered along its
// body trajectory (render/sequence_renderer.h) and written into the
// sequence folder in the EuRoC layout, with the truth a frontend is
// measured against (render/scene_file.h):
//
//   <folder>/mav0/camN/data/<t_ns>.png, camN/data.csv
//   <folder>/mav0/render/scene.csv, frame_poses.tum, render.yaml
//
// Any body trajectory works: the simulator's analytic one, or a curve
// fitted to a recorded flight.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dataset/simulator.h"
#include "dataset/trajectory_source.h"
#include "geometry/camera_model.h"
#include "render/render_options.h"
#include "render/scene.h"
#include "render/sequence_renderer.h"

namespace vio {

struct SimImagesSummary {
  RenderStats render;            // frames, images, blur, render CPU time
  double texture_seconds = 0.0;  // building the textured scene (CPU) [s]
  double write_seconds = 0.0;    // PNG encoding and writing (wall) [s]
};

// The body pose of a trajectory source (the simulator's analytic motion, a
// curve fitted to a recorded flight) at an IMU stamp: t = (t_ns - start_ns)
// seconds, clamped to [0, duration_s] (a blurred frame at the very end may
// reach a little beyond).
BodyPoseAt TrajectoryBodyPose(std::shared_ptr<const TrajectorySource> source,
                              int64_t start_ns, double duration_s);

// The room between the corners with the boxes that keep at least
// clearance_m from every one of `path_w` (body and camera positions along
// the trajectory) and fit in the room; the indices of the boxes left out
// are appended to *left_out.
SceneLayout LayoutClearOfPath(const Eigen::Vector3d& min_corner,
                              const Eigen::Vector3d& max_corner,
                              const std::vector<SceneBox>& boxes,
                              const std::vector<Eigen::Vector3d>& path_w,
                              double clearance_m, std::vector<int>* left_out);

// The body and camera positions along a simulation's ground truth.
std::vector<Eigen::Vector3d> SimulationPath(const Simulation& simulation);

// Renders the frames stamped `frame_stamps` (camera clock, increasing) for
// `cameras` (cam0, cam1, ...) into <folder>/mav0/camN and writes the truth
// files. `seed` drives the textures' tiling, the gain walk and the noise.
// Throws DatasetError when a file cannot be written, std::invalid_argument
// for invalid options, and std::runtime_error for unreadable textures.
SimImagesSummary RenderSequenceImages(
    const std::vector<int64_t>& frame_stamps,
    const std::vector<CameraCalibration>& cameras, const SceneLayout& layout,
    const RenderOptions& options, double time_offset_s, uint32_t seed,
    const BodyPoseAt& body_pose, const std::string& folder);

// Renders every camera frame of `simulation` (cam0, and cam1 when stereo)
// along `body_pose` into `folder`, as RenderSequenceImages.
SimImagesSummary RenderSimulationImages(const Simulation& simulation,
                                        const SceneLayout& layout,
                                        const RenderOptions& options,
                                        const BodyPoseAt& body_pose,
                                        const std::string& folder);

// vio_sim's lines about the rendering: images, CPU time per image and
// images per second on one core, blur, texture and PNG time, boxes left out.
std::string DescribeSimImages(const SimImagesSummary& summary, int cameras,
                              const std::vector<int>& boxes_left_out);

}  // namespace vio

#endif  // VIO_TOOLS_SIM_IMAGES_H_
