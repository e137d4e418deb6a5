#ifndef VIO_CONFIG_RECORDED_FLIGHT_H_
#define VIO_CONFIG_RECORDED_FLIGHT_H_

// Reads what a flight simulation (dataset/flight_simulation.h) takes from a
// recorded sequence folder in the EuRoC ASL layout. Only the ground truth is
// required; everything else is used when present:
//
//   ground truth   the given file, else mav0/state_groundtruth_estimate0/
//                  data.csv, else mav0/ground_truth.tum. EuRoC ground truth
//                  (17 columns: with velocity and biases) or TUM (8 columns,
//                  poses only); the format is told from the first data line.
//   IMU            mav0/imu0/data.csv (recorded samples) and
//                  mav0/imu0/sensor.yaml (noise densities)
//   cameras        mav0/cam0/sensor.yaml, mav0/cam1/sensor.yaml
//   frame stamps   mav0/cam0/data.csv, else mav0/cam0_timestamps_only.csv
//                  (first column: t [ns]; the images need not exist)
//
// A file that is present but malformed is an error naming the file and the
// line (DatasetError) or the key (ConfigError); a missing optional file is
// simply not used (the FlightSimulation says what was).

#include <string>

#include "dataset/flight_simulation.h"

namespace vio {

// ground_truth_path empty: the folder's own (see above). Throws DatasetError
// when the folder has no mav0/ or no ground truth is found.
RecordedFlight LoadRecordedFlight(const std::string& folder,
                                  const std::string& ground_truth_path);

}  // namespace vio

#endif  // VIO_CONFIG_RECORDED_FLIGHT_H_
