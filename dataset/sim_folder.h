#ifndef VIO_DATASET_SIM_FOLDER_H_
#define VIO_DATASET_SIM_FOLDER_H_

// Writes a Simulation as a sequence folder in the EuRoC ASL layout, in
// EuRoC's own formats, so that the EuRoC reader (config/euroc_sequence.h)
// loads it like a recorded one:
//
//   <folder>/mav0/imu0/data.csv, sensor.yaml
//   <folder>/mav0/cam0/features.csv, sensor.yaml     (no images)
//   <folder>/mav0/cam1/features.csv, sensor.yaml     (stereo only)
//   <folder>/mav0/state_groundtruth_estimate0/data.csv   (200 Hz, with v, b_g,
//   b_a)
//
// The camera-IMU time offset is not written anywhere: it is what an
// estimator must find. Numbers are printed with a fixed format, so equal
// simulations give byte-identical folders.

#include <string>

#include "dataset/simulator.h"

namespace vio {

struct SimulationFolderOptions {
  // false: no camN/features.csv, for a folder whose cameras get rendered
  // images instead (vio_sim --render writes camN/data/ and data.csv).
  bool write_features = true;
};

// Throws DatasetError when <folder>/mav0 already exists (an old simulation's
// cam1 could survive beside a new mono one) or a file cannot be written.
void WriteSimulationFolder(const Simulation& simulation,
                           const std::string& folder,
                           const SimulationFolderOptions& options = {});

// Simulate(options), then WriteSimulationFolder; returns the simulation.
Simulation SimulateToFolder(const SimulatorOptions& options,
                            const std::string& folder);

}  // namespace vio

#endif  // VIO_DATASET_SIM_FOLDER_H_
