#ifndef VIO_DATASET_EUROC_READER_H_
#define VIO_DATASET_EUROC_READER_H_

// Reads the data files of a sequence folder in the EuRoC ASL layout:
//
//   <folder>/mav0/imu0/data.csv                      required (unless the
//                                                    caller says otherwise)
//   <folder>/mav0/camN/data.csv + data/*.png          images, or
//   <folder>/mav0/camN/features.csv                   feature observations
//   <folder>/mav0/state_groundtruth_estimate0/data.csv  optional
//
// Camera folders are cam0, cam1, ... (consecutive from cam0; none is fine: a
// sequence may carry only IMU and ground truth). The sensor.yaml files are
// not read here (yaml-cpp lives in config/): config/euroc_sequence.h reads the
// whole sequence, calibrations included.
//
// Stamps are kept exactly as the files hold them (int64_t nanoseconds).
// Bad input is a DatasetError naming the file and the line. Two faults are
// tolerated, skipped and counted: an image that data.csv lists but that does
// not exist (EurocCamera::missing_images), and, unless the read is strict,
// IMU lines whose stamps do not strictly increase (repeated lines, repeated
// stamps, samples out of order: dataset/imu_stamp_filter.h; counted in
// EurocData::imu_stamps). A strict read refuses those too. Non-finite numbers
// (nan, inf) in any file are errors naming the line, IMU samples included.

#include <cstdint>
#include <string>
#include <vector>

#include "dataset/euroc_csv_stream.h"
#include "dataset/imu_stamp_filter.h"
#include "dataset/trajectory.h"
#include "geometry/feature_observation.h"
#include "preintegration/imu_types.h"

namespace vio {

// What one camera folder holds: images, feature observations, or both.
struct EurocCamera {
  int index = 0;                   // N of camN
  std::string folder;              // <folder>/mav0/camN
  bool has_images = false;         // data.csv was present
  bool has_features = false;       // features.csv was present
  std::vector<ImageEntry> images;  // listed and existing, in stamp order;
                                   // empty when the lists are not kept
  int missing_images = 0;          // listed but absent: skipped
  // Kept or not: how many images are listed and exist, and the first one's
  // stamp (0 when there is none) [ns].
  int64_t image_count = 0;
  int64_t first_image_ns = 0;
  // One frame per distinct stamp of features.csv, in stamp order; only `uv`,
  // `feature_id` and `camera` (= index) are set: xy and velocity are the
  // frontend's job (frontend/observation_builder.h).
  std::vector<FeatureFrame> feature_frames;
};

// How to read a sequence.
struct EurocReadOptions {
  // True: an IMU stamp repeated or out of order is a DatasetError naming the
  // line; false: the sample is dropped and counted (EurocData::imu_stamps).
  bool strict = false;
  // false: a folder without imu0/ is read (data.imu empty, has_imu false).
  // Only for callers that never use the IMU or that say so explicitly (a
  // tool flag): an estimator must not run on a silently missing IMU.
  bool require_imu = true;
  // false: the ground truth is read and checked (a bad line is an error
  // here, as when kept) but not kept: EurocData::ground_truth stays empty
  // and ground_truth_path names the file, for a caller that reads it again
  // later a state at a time (ForEachEurocGroundTruth) and keeps
  // only the states it needs, so that its memory does not grow with the
  // ground truth's rate and length.
  bool keep_ground_truth = true;
  // false: imu0/data.csv is read and checked through (a bad line is an
  // error here, the stamp filter's drops are counted in
  // EurocData::imu_stamps) but not kept: EurocData::imu stays empty and
  // imu_path names the file, for a caller that reads it again as it goes
  // (ImuCsvStream, dataset/euroc_csv_stream.h), so that its memory does not
  // grow with the sequence's length. The counts, imu_count and imu_first_ns
  // are those of the kept samples all the same.
  bool keep_imu = true;
  // false: each camN/data.csv is read and checked through (bad lines are
  // errors here, missing images counted) but not kept: EurocCamera::images
  // stays empty, image_count and first_image_ns are set, for a caller that
  // reads the list again as it goes (ImageListStream).
  bool keep_image_lists = true;
};

// The data of a whole sequence.
struct EurocData {
  std::string folder;          // the sequence folder (the one holding mav0/)
  bool has_imu = false;        // imu0/data.csv was read
  std::vector<ImuSample> imu;  // strictly increasing stamps; empty when
                               // not kept (EurocReadOptions::keep_imu)
  ImuStampReport imu_stamps;   // IMU lines dropped for their stamps
  std::string imu_path;        // imu0/data.csv; empty without has_imu
  // Kept or not: the samples read (after the stamp filter) and the first
  // one's stamp [ns] (0 when there is none).
  int64_t imu_count = 0;
  int64_t imu_first_ns = 0;
  std::vector<EurocCamera> cameras;        // cam0, cam1, ... as present
  std::vector<StampedState> ground_truth;  // empty when absent or not kept
  std::string ground_truth_path;           // empty when absent
  int64_t start_ns = 0;  // the earliest stamp of any stream [ns]

  // Seconds from the sequence start to `t_ns`, computed from the integer
  // difference so no precision is lost.
  double SecondsSinceStart(int64_t t_ns) const {
    return static_cast<double>(t_ns - start_ns) * 1e-9;
  }
};

// Reads everything listed above. Throws DatasetError when the folder or
// mav0/ is missing, when imu0/data.csv is missing (unless
// options.require_imu is false and there is no imu0/ folder at all), when a
// camN folder holds neither data.csv nor features.csv, and for any bad line
// of any file.
EurocData ReadEurocFolder(const std::string& folder,
                          const EurocReadOptions& options = {});

// The feature frames of every camera that has a features.csv, merged into one
// frame per distinct stamp (a stereo pair shares one), in stamp order; within
// a frame, cam0's observations come first.
std::vector<FeatureFrame> MergedFeatureFrames(const EurocData& data);

// The single files, for callers that need only one of them. Each throws
// DatasetError naming the file (and line) when it is missing or malformed.

// imu0/data.csv: t [ns], w_x, w_y, w_z [rad/s], a_x, a_y, a_z [m/s^2]; at
// least one sample. Strict (report null): stamps must strictly increase.
// Otherwise repeated and out-of-order stamps are dropped and counted in
// *report (dataset/imu_stamp_filter.h); the result strictly increases.
// The whole of ImuCsvStream's samples (dataset/euroc_csv_stream.h).
std::vector<ImuSample> ReadEurocImu(const std::string& path,
                                    ImuStampReport* report = nullptr);

// camN/data.csv: t [ns], filename; stamps strictly increasing. Files missing
// from `image_folder` are skipped and counted in *missing. The whole of
// ImageListStream's entries.
std::vector<ImageEntry> ReadEurocImageList(const std::string& path,
                                           const std::string& image_folder,
                                           int* missing);

// The path of a file or folder below another: "a" + "b" -> "a/b".
std::string JoinPath(const std::string& folder, const std::string& name);

}  // namespace vio

#endif  // VIO_DATASET_EUROC_READER_H_
