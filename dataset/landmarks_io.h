#ifndef VIO_DATASET_LANDMARKS_IO_H_
#define VIO_DATASET_LANDMARKS_IO_H_

// landmarks.csv: the world positions of a run's mapped landmarks, one per
// line, "x,y,z,parallax_deg" after a '#' header line: x, y, z in metres in
// the estimator's world frame W (gravity aligned, z up) and the landmark's
// triangulation angle in degrees (estimator/landmark_map.h), by which a user
// picks the well-triangulated ones. vio_replay writes it beside the
// trajectory, a row as each landmark is finished (so the rows are a set:
// their order is the order the run finished them in, not meaningful);
// vio_plan --replay reads it. Lines of 3 fields (x,y,z, from another
// source) are read too, with no angle.

#include <Eigen/Core>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace vio {

struct LandmarkRow {
  Eigen::Vector3d p_w = Eigen::Vector3d::Zero();  // [m]
  double parallax_deg = -1.0;  // triangulation angle [deg]; < 0: not given
};

// Throws DatasetError when the file cannot be written.
void WriteLandmarksCsv(const std::string& path,
                       const std::vector<LandmarkRow>& landmarks);

// Writes landmarks.csv a row at a time, for a run that hands its landmarks
// over as they are finished (Estimator::TakeFinishedLandmarks) and keeps
// none of them: the same lines as WriteLandmarksCsv of the same rows. The
// header is written on construction. Throws DatasetError naming the file
// when it cannot be opened or written.
class LandmarksCsvWriter {
 public:
  explicit LandmarksCsvWriter(const std::string& path);

  void Write(const LandmarkRow& row);
  // Flushes and closes the file (the destructor closes it unchecked).
  void Close();
  int64_t rows() const { return rows_; }

 private:
  std::string path_;
  std::ofstream out_;
  int64_t rows_ = 0;
};

// Reads every line (3 or 4 finite numbers); a malformed one is a
// DatasetError naming file and line. A file without data lines is an empty
// map, not an error (a run that never initialised maps nothing).
std::vector<LandmarkRow> ReadLandmarksCsv(const std::string& path);

}  // namespace vio

#endif  // VIO_DATASET_LANDMARKS_IO_H_
