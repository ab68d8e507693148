#include "mrpt_modules/loop/loop_closure_module.h"

#include <mrpt/core/initializer.h>

#include "common/input_error.h"
#include "mrpt_modules/factors/parameter_blocks.h"
#include "mrpt_modules/loop/keyframe_map_file.h"
#include "planes_map/plane_map_exporters.h"
#include "rawlog_io/rawlog_labels.h"

IMPLEMENTS_MRPT_OBJECT(LoopClosureModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_LoopClosureModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::LoopClosureModule));
}

namespace rpvio {

void LoopClosureModule::initialize(const IniFile& config, const std::string& section,
                                   PipelineContext& context) {
  options_ = loadOptions<LoopClosureOptions>(config, section);
  calibration_ = context.calibration;
  maps_ = context.maps;
  detector_ = std::make_unique<LoopDetector>(options_.detection, context.calibration.T_BC);
  graph_ = std::make_unique<FourDofPoseGraph>(options_.graph);
  if (!maps_.load.empty()) loadMap(maps_.load, context.calibration);
  worker_ = std::make_unique<SerialWorker>();
  bus_ = &context.bus;
  context.bus.subscribeSensor(labels::kCamera, [this](const ObservationMessage& m) {
    images_[toSeconds(m.observation->timestamp)] =
        locateImage(dynamic_cast<const mrpt::obs::CObservationImage&>(*m.observation), *m.reader);
  });
  context.bus.subscribe<KeyframeLeft>([this](const KeyframeLeft& k) { onKeyframe(k); });
  // Read on this thread only, as the keyframe leaves (the map builder updates it on this thread).
  context.bus.subscribe<MapReady>([this](const MapReady& m) { planes_map_ = m.planes_map; });
  context.bus.subscribe<MapSummary>([this](const MapSummary& s) {
    if (s.planes_map) run_planes_ = s.planes_map->confirmedPlanes();
  });
  context.bus.subscribe<StateEstimate>([this](const StateEstimate& s) {
    // Composed as quaternions: without a correction, exactly the odometry's pose.
    const Eigen::Isometry3d& C = correction_.T;
    const Eigen::Quaterniond q_C(C.linear());
    corrected_.push_back({s.t, C * posePosition(s.pose), q_C * poseRotation(s.pose)});
    if (correction_.in_map && !relocalized_t_) relocalized_t_ = s.t;
  });
  // Another world: the keyframes so far cannot be revisited in it.
  context.bus.subscribe<NewWorld>([this](const NewWorld&) {
    while (!results_.empty()) takeResult();
    worker_
        ->submit([this] {
          detector_->clearSession();
          graph_->clearSession();
          loop_unsolved_ = false;
          keyframes_since_solve_ = 1 << 20;
          map_loops_ = 0;
        })
        .get();
    correction_ = {};
  });
  setOptionsText("[" + section + "]\n" + describeOptions(options_));
}

int LoopClosureModule::mapPlaneOf(int label) const {
  const Plane* plane = label != 0 && planes_map_ ? planes_map_->planeOfMask(label) : nullptr;
  return plane ? plane->id : 0;
}

void LoopClosureModule::onKeyframe(const KeyframeLeft& left) {
  const double t = left.keyframe.t;
  const auto found = images_.find(left.keyframe.image_t);
  if (found == images_.end()) return;
  const ImageFileRef image = found->second;
  images_.erase(images_.begin(), std::next(found));  // keyframes leave in time order
  std::vector<AppearancePoint> tracked;
  for (const ArchivedObservation& o : left.observations)
    tracked.push_back({o.observation.normalized, o.world, mapPlaneOf(o.plane_id)});
  const Eigen::Isometry3d body = poseIsometry(left.keyframe.pose);
  results_.push_back(worker_->submit([this, t, image, tracked = std::move(tracked), body] {
    return processKeyframe(t, image, tracked, body);
  }));
  while (results_.size() > static_cast<size_t>(std::max(options_.loop_result_lag, 0))) takeResult();
}

LoopClosureModule::Correction LoopClosureModule::processKeyframe(
    double t, const ImageFileRef& image, const std::vector<AppearancePoint>& tracked,
    const Eigen::Isometry3d& body) {
  if (error_) return {};
  try {
    KeyframeAppearance appearance = describeKeyframe(
        decodeGrayImage(image), tracked, calibration_.camera, options_.detection.loop_corners);
    const auto event = detector_->add(t, body, std::move(appearance));
    const size_t k = graph_->addKeyframe(body);
    if (event) {
      events_.push_back(*event);
      if (event->check.accepted) {
        graph_->addLoop(event->old_index, k, event->check.old_body);
        loop_unsolved_ = true;
        // Relocalized by one revisit, the run is moved by each of the next ones at once.
        if (event->old_from_map && ++map_loops_ <= options_.loop_map_solves)
          keyframes_since_solve_ = 1 << 20;
      }
    }
    ++keyframes_since_solve_;
    if (loop_unsolved_ && keyframes_since_solve_ >= options_.loop_solve_every) {
      graph_->optimize();
      loop_unsolved_ = false;
      keyframes_since_solve_ = 0;
    }
    return {graph_->correction(k), graph_->relocalized()};
  } catch (...) {
    error_ = std::current_exception();
    return {};
  }
}

void LoopClosureModule::takeResult() {
  correction_ = results_.front().get();
  results_.pop_front();
}

void LoopClosureModule::finish() {
  while (!results_.empty()) takeResult();
  if (error_) std::rethrow_exception(error_);
  LoopClosureSummary summary;
  summary.keyframes = detector_->keyframes();
  summary.map_keyframes = detector_->mapKeyframes();
  summary.events = events_;
  summary.corrected = corrected_;
  size_t accepted = 0;
  summary.relocalized_t = relocalized_t_;
  for (const LoopEvent& e : events_) accepted += e.check.accepted;
  MRPT_LOG_INFO_STREAM("loop closure: " << summary.keyframes << " keyframes, " << events_.size()
                                        << " revisits found by appearance, " << accepted
                                        << " accepted");
  // The map (keyframes and planes) after a last solve; the published poses are as they were.
  if (loop_unsolved_) graph_->optimize();
  const bool in_map = detector_->mapKeyframes() == 0 || graph_->relocalized();
  if (run_planes_) {
    summary.planes = planesInGraphFrame(*run_planes_, runCorrections());
    if (in_map && !map_planes_.empty()) summary.planes = mergedPlanes(map_planes_, summary.planes);
  }
  if (!maps_.save.empty()) saveMap(maps_.save, in_map ? summary.planes : map_planes_);
  bus_->publish(summary);
}

KeyframeCorrections LoopClosureModule::runCorrections() const {
  KeyframeCorrections corrections;
  const auto& stored = detector_->stored();
  for (size_t k = detector_->mapKeyframes(); k < stored.size(); ++k)
    corrections.emplace_back(stored[k].t, graph_->correction(k));
  return corrections;
}

void LoopClosureModule::loadMap(const std::string& dir, const Calibration& calibration) {
  const std::string path = keyframeMapPath(dir);
  KeyframeMap map = readKeyframeMap(path);
  const std::string mismatch = calibrationMismatch(map, calibration);
  if (!mismatch.empty()) throw InputError(path, "", "saved with another calibration: " + mismatch);
  for (const StoredKeyframe& k : map.keyframes) graph_->addMapKeyframe(k.body);
  map_planes_ = readPlanesYaml(mapPlanesPath(dir));
  MRPT_LOG_INFO_STREAM("map " << path << ": " << map.keyframes.size() << " keyframes, "
                              << map_planes_.size() << " planes");
  detector_->addMapKeyframes(std::move(map.keyframes));
}

void LoopClosureModule::saveMap(const std::string& dir, const std::vector<Plane>& planes) const {
  KeyframeMap map{calibration_.camera, calibration_.T_BC, {}};
  const auto& stored = detector_->stored();
  // The run's keyframes join a loaded map only in its frame.
  const bool with_run = detector_->mapKeyframes() == 0 || graph_->relocalized();
  if (!with_run)
    MRPT_LOG_WARN_STREAM("the run never revisited the map of " << maps_.load
                                                               << ": its keyframes are not saved");
  const size_t count = with_run ? stored.size() : detector_->mapKeyframes();
  for (size_t k = 0; k < count; ++k) {
    // The file keeps each point's normalized coordinates and descriptor, not its world point.
    map.keyframes.push_back({stored[k].t, graph_->corrected(k), stored[k].appearance});
  }
  writeKeyframeMap(keyframeMapPath(dir), map);
  writePlanesYaml(mapPlanesPath(dir), planes);
  MRPT_LOG_INFO_STREAM("map saved: " << keyframeMapPath(dir) << ", " << count << " keyframes, "
                                     << planes.size() << " planes");
}

}  // namespace rpvio
