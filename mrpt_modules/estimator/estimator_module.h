#pragma once
// Pipeline module around SlidingWindowEstimator: buffers the IMU observations, and for every
// FeatureFrame hands the estimator the IMU samples since the previous frame (camera time moved to
// the IMU clock by the time offset: the calibration's, corrected by the estimator's estimate). A
// frame waits until the IMU stream has reached its time; at the end, the waiting frames are
// processed with the samples there are. Publishes an EstimatorFrame per frame processed and a
// StateEstimate per frame once initialized (a late initialization's frames since its window come
// with the frame that initialized it); says once per change why it is not (yet) tracking;
// publishes what leaves the window for the MapBuilderModule (map_sink.h) and, at the end, the
// EstimatorSummary. Options: section [SlidingWindowEstimatorModule] (see EstimatorOptions).
#include <deque>
#include <memory>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/estimator/sliding_window_estimator.h"

namespace rpvio {

class SlidingWindowEstimatorModule : public Module {
  DEFINE_MRPT_OBJECT(SlidingWindowEstimatorModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  const SlidingWindowEstimator& estimator() const { return *estimator_; }
  /// The last pending frames, then the map finished; publishes the EstimatorSummary.
  void finish() override;

 private:
  void onImu(const ObservationMessage& message);
  void onFrame(const FeatureFrame& frame);
  void processReadyFrames();
  void processOldestPending();

  /// The estimator's map information as messages (to the MapBuilderModule), and the map it
  /// announced (an empty one without a map builder).
  class BusMapSink : public MapSink {
   public:
    explicit BusMapSink(const Bus& bus) : bus_(bus) {}
    const PlanesMap& planesMap() const override { return map_ ? *map_ : empty_; }
    void planesSeen(const PlanesSeen& planes) override { bus_.publish(planes); }
    void keyframeLeft(const KeyframeLeft& keyframe) override { bus_.publish(keyframe); }
    void chainBroken() override { bus_.publish(KeyframeChainBroken{}); }
    void newWorld() override { bus_.publish(NewWorld{}); }
    void windowFinished(const WindowFinished& end) override { bus_.publish(end); }
    void setMap(const PlanesMap* map) { map_ = map; }

   private:
    const Bus& bus_;
    const PlanesMap* map_ = nullptr;
    PlanesMap empty_;
  };

  std::unique_ptr<BusMapSink> map_sink_;
  std::unique_ptr<SlidingWindowEstimator> estimator_;
  const Bus* bus_ = nullptr;
  std::deque<FeatureFrame> pending_;  // frames waiting for the IMU to reach their time
  std::deque<ImuSample> imu_;
  double previous_frame_t_ = -1;
  std::string last_status_;
  double initialized_at_ = -1;
  std::string reported_time_offset_note_;  // logged whenever it changes
};

}  // namespace rpvio
