#ifndef VIO_FRONTEND_DIRECT_OPTIONS_H_
#define VIO_FRONTEND_DIRECT_OPTIONS_H_

// Options of the direct method (docs/direct.md): the semi-dense stereo
// depth of a keyframe, the frame tracker (the notes' Algorithm 3, TrackFrame)
// and the frame-to-keyframe odometry. Kept free of OpenCV so that config/ can
// fill them (no YAML block reads them yet: vio_direct sets them from its
// flags). Every field has a default with its unit; Validate() checks the
// ranges and, on failure, writes a message that starts with the offending
// field's name.

#include <string>

namespace vio {

// Semi-dense inverse depth from a calibrated stereo pair
// (frontend/stereo_depth.h): pixels with a strong gradient along the
// epipolar line are matched along it in the other image.
struct StereoDepthOptions {
  int level = 1;                  // pyramid level searched (0: full resolution)
  double min_gradient = 8.0;      // |grad I| of a pixel that gets a depth
                                  // [grey/px at its level]
  double min_line_cosine = 0.35;  // |cos| of the angle between the gradient
                                  // and the epipolar line [-]
  double min_depth_m = 0.4;       // nearest depth searched [m]
  double max_depth_m = 40.0;      // farthest depth searched [m]
  double min_ncc = 0.85;  // zero-mean normalised cross-correlation of the
                          // best match [-]
  // Uniqueness: the second-best match (more than 2 px away) must score
  // (1 - ncc) at least this many times the best's [-].
  double uniqueness_ratio = 2.0;
  double sigma_intensity = 3.0;    // image noise sigma_I [grey]
  double sigma_epipolar_px = 0.3;  // error of the calibrated epipolar line
                                   // [px at level 0]

  bool Validate(std::string* message) const;
};

// How TrackFrame solves for the relative pose.
enum class DirectSolver {
  kNotesLm,  // the notes' Algorithm 3: normal equations by hand, Cholesky
  kCeres,    // ceres::Solver (Levenberg-Marquardt) on PhotometricFactor
};

// "notes" / "ceres"; Parse returns false for anything else.
const char* DirectSolverName(DirectSolver solver);
bool ParseDirectSolver(const std::string& text, DirectSolver* solver);

// Coarse-to-fine alignment of a frame to a keyframe (frontend/
// direct_tracker.h).
struct DirectTrackerOptions {
  DirectSolver solver = DirectSolver::kNotesLm;
  int coarsest_level = 4;   // pyramid level the alignment starts at [-]
  int finest_level = 1;     // level it ends at; >= the depth's level [-]
  int max_iterations = 30;  // k_max, iterations per level [-]
  // epsilon_1 of the notes: a level ends when a step's pose part is shorter
  // than this (norm of [dt (m), dtheta (rad)]) [-].
  double min_step = 1e-5;
  // The notes' damping rule: on success lambda is halved, or set to 0 once
  // <= lambda_floor; on failure it is set to lambda_floor from 0, else
  // doubled. A level also ends when lambda exceeds max_lambda [-].
  double lambda_floor = 0.2;
  double max_lambda = 1e8;
  // Image noise sigma_I at full resolution [grey]; level l uses
  // sigma_I / 2^l (it averages 4^l pixels).
  double sigma_intensity = 2.5;
  // The notes' weight W = (2 sigma_I^2 + (df/drho)^2 V)^-1; false: the
  // unweighted W = (2 sigma_I^2)^-1.
  bool variance_weight = true;
  // Huber kernel on sqrt(W) f [sigma]; 0: none (plain least squares).
  double huber_scale = 1.345;
  // Estimate DSO's affine brightness (a, b) of each target image.
  bool estimate_affine = true;
  // Weight (the notes' lambda of E_s) of the residuals into the target's
  // right image, when the frame has one; 0 turns the stereo term off [-].
  double stereo_weight = 1.0;
  // Fewer residuals than this at a level fail the track [-].
  int min_residuals = 30;
  // At most this many of a level's points are used, evenly spread over the
  // keyframe's list (row-major order); 0: all [-].
  int max_points = 0;

  bool Validate(std::string* message) const;
};

// Frame-to-keyframe stereo odometry (frontend/direct_odometry.h).
struct DirectOdometryOptions {
  int pyramid_levels = 5;  // levels built per image, full resolution first
  StereoDepthOptions depth;
  DirectTrackerOptions tracker;
  // A frame becomes a keyframe when fewer than this fraction of the
  // keyframe's points (at the finest level) land inside it [-].
  double min_overlap = 0.7;
  // ... or when it is farther than this from the keyframe, relative to the
  // keyframe's median depth [-].
  double max_distance_over_depth = 0.15;
  // Predict each frame by repeating the last frame-to-frame motion (else
  // from the last pose).
  bool constant_velocity = true;
  // A keyframe needs at least this many depth points; else the previous
  // keyframe is kept [-].
  int min_keyframe_points = 200;

  // Messages start with "depth." or "tracker." for the nested blocks.
  bool Validate(std::string* message) const;
};

}  // namespace vio

#endif  // VIO_FRONTEND_DIRECT_OPTIONS_H_
