#ifndef VIO_DATASET_FEATURES_CSV_H_
#define VIO_DATASET_FEATURES_CSV_H_

// The public feature-observation file, mav0/camN/features.csv: what a tracker
// would produce for camera N, written by vio_sim and by any other tool.
//
//   #timestamp [ns],feature_id,u [px],v [px]
//   1600000000000000000,17,412.503112,230.118000
//
// One row per observation: the camera stamp [ns] (integer), a feature id
// (integer >= 0; the same id for the same landmark in every camera and
// frame), and the measured, distorted pixel (u right, v down, origin at the
// centre of the top-left pixel, as OpenCV). Rows are in non-decreasing stamp
// order, so one frame's rows are consecutive; an id appears at most once per
// stamp. A frame without observations has no row. Lines starting with '#' and
// blank lines are ignored.

#include <string>
#include <vector>

#include "geometry/feature_observation.h"

namespace vio {

// Reads a features.csv into one frame per distinct stamp, setting feature_id,
// camera (= `camera`) and uv. Throws DatasetError naming file and line for a
// missing file, a short or long line, a non-numeric or non-finite field, a
// negative id, a stamp before the previous one, or an id repeated in a frame.
std::vector<FeatureFrame> ReadFeaturesCsv(const std::string& path, int camera);

// Writes the observations of camera `camera` of every frame (others are left
// out), rows in frame order and, within a frame, in the frames' own order.
// Pixels are written with 6 decimals. Throws DatasetError when the file cannot
// be written.
void WriteFeaturesCsv(const std::string& path,
                      const std::vector<FeatureFrame>& frames, int camera);

}  // namespace vio

#endif  // VIO_DATASET_FEATURES_CSV_H_
