#include "rawlog_io/rawlog_summary.h"

#include "common/input_error.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/rawlog_reader.h"

namespace rpvio {

RawlogSummary summarizeRawlog(const std::string& path) {
  RawlogSummary summary;
  RawlogReader reader(path);
  cv::Size camera_size;
  double camera_t = -1;
  while (auto obs = reader.next()) {
    const double t = toSeconds(obs->timestamp);
    if (summary.observations_per_label.empty()) summary.first_t = t;
    summary.last_t = t;
    ++summary.observations_per_label[obs->sensorLabel];
    if (auto img = std::dynamic_pointer_cast<mrpt::obs::CObservationImage>(obs)) {
      const cv::Size size = loadGrayImage(*img, reader).size();
      if (obs->sensorLabel == labels::kCamera) {
        camera_size = size;
        camera_t = t;
      } else if (obs->sensorLabel == labels::kPlaneMask && t == camera_t && size != camera_size) {
        throw InputError(path, "entry " + std::to_string(reader.entriesRead()),
                         "PLANE_MASK size differs from its CAM0 image");
      }
    } else if (auto imu = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(obs)) {
      toImuSample(*imu, reader);
    }
  }
  return summary;
}

}  // namespace rpvio
