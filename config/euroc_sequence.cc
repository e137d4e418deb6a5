#include "config/euroc_sequence.h"

namespace vio {

EurocSequence LoadEurocSequence(const std::string& folder,
                                const EurocReadOptions& options) {
  EurocSequence sequence;
  sequence.data = ReadEurocFolder(folder, options);
  const std::string mav0 = JoinPath(folder, "mav0");
  if (sequence.data.has_imu) {
    sequence.imu = ReadEurocImuYaml(JoinPath(mav0, "imu0/sensor.yaml"));
  }
  for (const EurocCamera& camera : sequence.data.cameras) {
    sequence.cameras.push_back(
        ReadEurocCameraYaml(JoinPath(camera.folder, "sensor.yaml")));
  }
  return sequence;
}

}  // namespace vio
