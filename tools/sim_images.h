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
#include <string>
#include <vector>

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

// Throws std::invalid_argument naming the box when any of `positions_w`
// (body or camera positions along the trajectory) comes within
// `clearance_m` of a box: the renderer's cameras must stay outside them.
void CheckClearOfBoxes(const SceneLayout& layout,
                       const std::vector<Eigen::Vector3d>& positions_w,
                       double clearance_m);

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

}  // namespace vio

#endif  // VIO_TOOLS_SIM_IMAGES_H_
