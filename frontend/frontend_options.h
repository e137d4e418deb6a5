#ifndef VIO_FRONTEND_FRONTEND_OPTIONS_H_
#define VIO_FRONTEND_FRONTEND_OPTIONS_H_

// Options of the image frontend (KLT tracking, stereo matching), kept apart
// from the OpenCV code so that config/ can fill them without seeing OpenCV.
// Every field has a default with its unit; Validate() checks ranges and, on
// failure, writes a message that starts with the offending field's YAML name
// (config/frontend_config.h maps the two one to one).

#include <string>

namespace vio {

// Pyramidal Lucas-Kanade settings (cv::calcOpticalFlowPyrLK).
struct KltOptions {
  int window_px = 21;        // side of the square tracking window [px], odd
  int pyramid_levels = 3;    // levels above the full-resolution image [-]
  int max_iterations = 30;   // per pyramid level [-]
  double epsilon_px = 0.01;  // stop when an update is below this [px]

  // `prefix` is prepended to field names in the message ("klt_" in YAML).
  bool Validate(const std::string& prefix, std::string* message) const;
};

// Monocular frame-to-frame tracking (frontend/feature_tracker.h).
struct FeatureTrackerOptions {
  int max_features = 150;         // tracks kept per frame, refilled to this
  double min_distance_px = 30.0;  // between any two features [px]
  // Shi-Tomasi acceptance: minimum eigenvalue relative to the strongest
  // corner of the image (cv::goodFeaturesToTrack qualityLevel) [-].
  double corner_quality = 0.002;
  // Features closer than this to the image border are dropped [px].
  int border_px = 2;
  // New corners are looked for only when at least this many of the
  // max_features tracks are missing (1: whenever one is) [tracks]. Most
  // frames lose a few tracks and find few corners in the mask's gaps, while
  // the search costs as much as tracking (docs/frontend.md).
  int refill_min_missing = 5;
  KltOptions klt;
  // A track survives when tracking it back from the new frame lands within
  // this distance of where it started [px].
  double max_forward_backward_px = 0.5;
  // Fundamental-matrix RANSAC on undistorted points, rescaled to a virtual
  // pinhole of focal virtual_focal_px so that the threshold is in pixels.
  bool fundamental_check = true;
  double fundamental_threshold_px = 1.0;  // epipolar distance [px]
  double fundamental_confidence = 0.99;   // RANSAC confidence, in (0, 1)
  // The same RANSAC between this frame and the frame this many frames back,
  // on the tracks seen in both: a track that slides slowly (a corner
  // between two surfaces at different depths) stays within the threshold
  // from one frame to the next but not over several. 0: off [frames].
  int fundamental_baseline_frames = 5;
  double virtual_focal_px = 460.0;  // [px]
  // Refine every track against its first appearance with an affine warp,
  // so that its error does not grow along the track
  // (frontend/anchor_refiner.h). A refinement that would move the point
  // further than anchor_max_correction_px renews the anchor instead; a
  // patch that correlates with its anchor less than anchor_min_correlation
  // (zero-mean normalised) ends the track.
  bool anchor_refinement = true;
  double anchor_max_correction_px = 2.0;  // [px], in (0, 10]
  double anchor_min_correlation = 0.8;    // [-], in [-1, 1)
  // Contrast-limited adaptive histogram equalisation (cv::CLAHE) of every
  // image before tracking, for dark scenes.
  bool clahe = false;
  double clahe_clip_limit = 3.0;  // contrast limit [-]
  int clahe_tiles = 8;            // tiles per image side [-]

  bool Validate(std::string* message) const;
};

// Left-to-right matching of a calibrated stereo pair
// (frontend/stereo_matcher.h).
struct StereoMatcherOptions {
  // A 15 px window: the matched images are taken at the same instant, so
  // the patch does not deform as along a track, and it costs half of the
  // tracker's 21 px window per iteration (docs/frontend.md). 7 iterations
  // per level: most matches converge in fewer, and the points that do not
  // (occluded, out of view) spent most of the match's time in up to 30
  // (docs/speed.md, fifth pass).
  KltOptions klt = {15, 3, 7};
  // Equalise the histograms of both images before matching
  // (cv::equalizeHist). The two cameras expose differently (mean grey 145
  // against 130 on V1_01) and LK assumes equal brightness: on the first
  // V1_01 pair 36 of 150 features pass the reverse check without it, 86
  // with it.
  bool equalize = true;
  // Matching right -> left must return within this distance [px].
  double max_reverse_px = 0.5;
  // Pyramid levels above full resolution of that reverse LK [-]. It starts
  // at the left pixel, where a good match returns, so it needs no coarse
  // levels to reach it: 0 costs a quarter of klt.pyramid_levels + 1 levels
  // (docs/speed.md, fifth pass). At most klt.pyramid_levels.
  int reverse_pyramid_levels = 0;
  // Distance of the right observation to the epipolar line of the left one,
  // measured on the undistorted right image [px].
  double max_epipolar_px = 1.0;
  // Start the left -> right LK of a feature matched in the previous frame at
  // its previous offset from the left pixel (the disparity changes little
  // from frame to frame) instead of at the left pixel itself; features
  // without a previous match start at their left pixel. LK then needs fewer
  // iterations per level (docs/speed.md, fifth pass).
  bool start_from_previous = true;

  bool Validate(std::string* message) const;
};

// The whole frontend: tracking on cam0, and matching into cam1 when stereo.
struct FrontendOptions {
  bool stereo = true;  // false: cam0 only (monocular)
  FeatureTrackerOptions tracker;
  StereoMatcherOptions stereo_matcher;

  // Messages start with "tracker." or "stereo_matcher." and the field.
  bool Validate(std::string* message) const;
};

}  // namespace vio

#endif  // VIO_FRONTEND_FRONTEND_OPTIONS_H_
