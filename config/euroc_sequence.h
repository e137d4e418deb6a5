#ifndef VIO_CONFIG_EUROC_SEQUENCE_H_
#define VIO_CONFIG_EUROC_SEQUENCE_H_

// The one call that gives tools and tests a complete EuRoC-layout sequence:
// the data files (dataset/euroc_reader.h) and the calibrations of every
// sensor present (config/euroc_sensor.h). It works alike for a recorded
// sequence and for one written by vio_sim.

#include <string>
#include <vector>

#include "config/euroc_sensor.h"
#include "dataset/euroc_reader.h"
#include "geometry/camera_model.h"

namespace vio {

struct EurocSequence {
  EurocData data;
  // cameras[i] is the calibration of data.cameras[i] (camN/sensor.yaml).
  std::vector<CameraCalibration> cameras;
  EurocImuSensor imu;  // imu0/sensor.yaml (defaults when data.has_imu is false)
};

// Reads <folder>/mav0/... Throws DatasetError for the data files and
// ConfigError for a sensor.yaml (missing, malformed, lacking a key), each
// naming the file and the line or key. With options.require_imu false a
// folder without imu0/ loads without IMU; options.strict: IMU stamps repeated
// or out of order are errors instead of dropped and counted samples
// (EurocReadOptions in dataset/euroc_reader.h).
EurocSequence LoadEurocSequence(const std::string& folder,
                                const EurocReadOptions& options = {});

}  // namespace vio

#endif  // VIO_CONFIG_EUROC_SEQUENCE_H_
