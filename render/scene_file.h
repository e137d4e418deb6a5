#ifndef VIO_RENDER_SCENE_FILE_H_
#define VIO_RENDER_SCENE_FILE_H_

// The truth of a rendered sequence, written beside its images so that any
// tool can measure a frontend against it (eval/track_truth.h):
//
//   <folder>/mav0/render/scene.csv         the planes of the scene
//   <folder>/mav0/render/frame_poses.tum   the body pose of every frame
//
// scene.csv, one plane per line (render/scene.h), seen from the side of
// axis_u x axis_v:
//   #plane,origin_x [m],origin_y [m],origin_z [m],axis_u_x,axis_u_y,axis_u_z,
//    axis_v_x,axis_v_y,axis_v_z,size_u [m],size_v [m]
// frame_poses.tum: TUM lines "t x y z qx qy qz qw", t the frame's camera
// stamp [s, 9 decimals, exact ns], the pose of B in W at the centre of its
// exposure (IMU time t + t_d), so that a camera-IMU time offset or motion
// blur does not blur the truth.

#include <string>

#include "dataset/trajectory.h"
#include "render/scene.h"

namespace vio {

// <folder>/mav0/render
std::string RenderTruthFolder(const std::string& sequence_folder);

// Writes scene.csv (numbers exact, shortest round trip). Throws DatasetError
// when the file cannot be written.
void WriteSceneCsv(const std::string& path, const SceneGeometry& scene);

// Reads scene.csv. Throws DatasetError naming the file and line for a
// missing file, a line without 12 fields, a non-number, a plane index out
// of order or a plane that is not valid (axes not orthonormal, size <= 0).
SceneGeometry ReadSceneCsv(const std::string& path);

// The truth of a rendered sequence folder.
struct RenderTruth {
  SceneGeometry scene;
  Trajectory frame_poses;  // by camera stamp
};

// True when <folder>/mav0/render/scene.csv exists.
bool HasRenderTruth(const std::string& sequence_folder);

// Reads both files; throws DatasetError as the readers do.
RenderTruth ReadRenderTruth(const std::string& sequence_folder);

}  // namespace vio

#endif  // VIO_RENDER_SCENE_FILE_H_
