#pragma once
// Feeds the simulator's images through the front-end and its IMU through preintegrations:
// frames as the initializer receives them (test helper).
#include <memory>
#include <vector>

#include "mrpt_modules/frontend/feature_tracker.h"
#include "mrpt_modules/imu/imu_preintegration.h"
#include "sim/simulator.h"

namespace rpvio::test {

struct WindowFrame {
  FeatureFrame features;
  std::shared_ptr<ImuPreintegration> imu_from_previous;  // null for the first frame
};

class SimWindowSource {
 public:
  explicit SimWindowSource(const sim::SimConfig& config)
      : sim_(config),
        tracker_(sim_.calibration().camera, TrackerOptions{}),
        imu_(sim_.imuStream()),
        times_(sim_.frameTimes()) {}

  bool done() const { return next_ >= times_.size(); }
  double time() const { return times_[next_ - 1]; }
  sim::Simulator& simulator() { return sim_; }

  /// The next frame: tracked features and the IMU since the previous frame (zero biases).
  WindowFrame next() {
    const double t = times_[next_];
    const sim::RenderedFrame image = sim_.render(t, static_cast<int>(next_));
    WindowFrame frame;
    frame.features = tracker_.track(t, image.image, image.mask);
    const size_t k = static_cast<size_t>(std::llround(t * sim_.config().imu.rate_hz));
    if (next_ > 0) {
      frame.imu_from_previous = std::make_shared<ImuPreintegration>(
          imu_[last_imu_].accel, imu_[last_imu_].gyro, Eigen::Vector3d::Zero(),
          Eigen::Vector3d::Zero(), sim_.config().imu);
      for (size_t j = last_imu_ + 1; j <= k; ++j)
        frame.imu_from_previous->push(imu_[j].t - imu_[j - 1].t, imu_[j].accel, imu_[j].gyro);
    }
    last_imu_ = k;
    ++next_;
    return frame;
  }

 private:
  sim::Simulator sim_;
  FeatureTracker tracker_;
  std::vector<ImuSample> imu_;
  std::vector<double> times_;
  size_t next_ = 0, last_imu_ = 0;
};

}  // namespace rpvio::test
