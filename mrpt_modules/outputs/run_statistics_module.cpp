#include "mrpt_modules/outputs/run_statistics_module.h"

#include <mrpt/core/initializer.h>

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "common/atomic_file.h"
#include "common/json_text.h"
#include "common/sensor_types.h"
#include "mrpt_modules/core/feature_frame.h"
#include "planes_map/planes_map.h"

IMPLEMENTS_MRPT_OBJECT(RunStatisticsModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_RunStatisticsModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::RunStatisticsModule));
}

namespace rpvio {

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
}

double peakMemoryMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // kB on Linux
}

namespace {

/// One object per reset: `{"t": 12.3, "cause": "..."}`.
std::vector<JsonObject> resetCausesJson(const std::vector<ResetEvent>& resets) {
  std::vector<JsonObject> out;
  for (const ResetEvent& r : resets)
    out.push_back(JsonObject().stamp("t", r.t).text("cause", r.cause));
  return out;
}

std::vector<JsonObject> planeRejectionsJson(const std::vector<PlaneRejection>& rejections) {
  std::vector<JsonObject> out;
  for (const PlaneRejection& r : rejections)
    out.push_back(
        JsonObject().integer("plane", r.plane_id).stamp("t", r.t).number("error_px", r.error_px));
  return out;
}

/// The discovered planes accepted (or rejected as moving): `{"plane": 257, "t": 0.45}`.
std::vector<JsonObject> discoveriesJson(const std::vector<PlaneDiscoveryEvent>& events,
                                        bool accepted) {
  std::vector<JsonObject> out;
  for (const PlaneDiscoveryEvent& e : events)
    if (e.accepted == accepted)
      out.push_back(JsonObject().integer("plane", e.plane_id).stamp("t", e.t));
  return out;
}

/// x, y, z (m) and yaw (deg, about the query body's z) of a relative pose.
std::vector<double> relativePose(const Eigen::Isometry3d& T) {
  const Eigen::Vector3d p = T.translation();
  const double yaw = std::atan2(T.linear()(1, 0), T.linear()(0, 0)) * 180 / M_PI;
  return {p.x(), p.y(), p.z(), yaw};
}

/// One object per revisit found by appearance:
/// `{"t": ..., "t_old": ..., "score": ..., "accepted": true, "why": "", "inliers": 61,
/// "map": false, "plane_pairs": 30, "same_plane_pairs": 30}` ("map": the old keyframe is a loaded
/// map's; the plane check's inliers on planes in both keyframes, and on the same one; "relative":
/// the old body seen from the query's, x y z m and yaw deg, as the check measured it).
std::vector<JsonObject> loopsJson(const std::vector<LoopEvent>& events) {
  std::vector<JsonObject> out;
  for (const LoopEvent& e : events)
    out.push_back(JsonObject()
                      .stamp("t", e.t)
                      .stamp("t_old", e.t_old)
                      .number("score", e.score)
                      .flag("accepted", e.check.accepted)
                      .text("why", e.check.why)
                      .integer("inliers", e.check.inliers)
                      .flag("map", e.old_from_map)
                      .integer("plane_pairs", e.check.plane_pairs)
                      .integer("same_plane_pairs", e.check.same_plane_pairs)
                      .numbers("relative", relativePose(e.relative)));
  return out;
}

}  // namespace

void RunStatisticsModule::initialize(const IniFile&, const std::string& section,
                                     PipelineContext& context) {
  output_dir_ = context.output_dir;
  start_ = frame_start_ = Clock::now();
  context.bus.subscribe<RunStart>(
      [this](const RunStart&) { start_ = frame_start_ = Clock::now(); });
  context.bus.subscribe<FrameDecoding>([this](const FrameDecoding& d) { load_ms_ += d.load_ms; });
  context.bus.subscribe<EstimatorFrame>(
      [this](const EstimatorFrame& e) { reports_.push_back(e.report); });
  context.bus.subscribe<FeatureFrame>([this](const FeatureFrame& f) { onFrame(f.t); });
  context.bus.subscribe<StateEstimate>([this](const StateEstimate&) { ++poses_; });
  context.bus.subscribe<RunEnd>([this](const RunEnd& e) { end_ = e; });
  context.bus.subscribe<EstimatorSummary>([this](const EstimatorSummary& s) { estimator_ = s; });
  context.bus.subscribe<MapSummary>([this](const MapSummary& s) { map_ = s; });
  context.bus.subscribe<LoopClosureSummary>([this](const LoopClosureSummary& s) { loops_ = s; });
  setOptionsText("[" + section + "]\n");
}

void RunStatisticsModule::onFrame(double t) {
  const auto now = Clock::now();
  double estimator_ms = 0;
  for (; reports_counted_ < reports_.size(); ++reports_counted_)
    estimator_ms += reports_[reports_counted_].optimization_ms;
  rows_.push_back({t, std::chrono::duration<double, std::milli>(now - frame_start_).count(),
                   load_ms_, estimator_ms});
  load_ms_ = 0;
  frame_start_ = now;
}

void RunStatisticsModule::finish() {
  if (!output_dir_.empty()) write(std::chrono::duration<double>(Clock::now() - start_).count());
}

void RunStatisticsModule::write(double wall) const {
  const auto path = [&](const char* name) {
    return (std::filesystem::path(output_dir_) / name).string();
  };
  std::vector<double> total_ms, optimization_ms, frontend_ms, load_ms, processing_ms;
  long long camera_height_frames = 0;
  writeFileAtomically(path("stats.csv"), [&](std::ostream& s) {
    s << "t,load_ms,frontend_ms,optimization_ms,total_ms,features,planes,state\n";
    s << std::fixed;
    for (size_t k = 0; k < rows_.size(); ++k) {
      const FrameReport report = k < reports_.size() ? reports_[k] : FrameReport{"no estimator"};
      // A frame's cost: the front-end's part of the wall time since the previous frame (without
      // the estimator's work in it, which may be another frame's: one still waiting for its IMU
      // data is optimized after the next is tracked) and the estimator's time on this frame.
      const FrameRow& row = rows_[k];
      load_ms.push_back(row.load_ms);
      frontend_ms.push_back(std::max(0.0, row.wall_ms - row.load_ms - row.estimator_ms));
      optimization_ms.push_back(report.optimization_ms);
      processing_ms.push_back(frontend_ms.back() + optimization_ms.back());
      total_ms.push_back(load_ms.back() + processing_ms.back());
      camera_height_frames += report.ground_plane >= 0;
      s << stampText(row.t) << std::setprecision(3) << "," << load_ms.back() << ","
        << frontend_ms.back() << "," << optimization_ms.back() << "," << total_ms.back() << ","
        << report.features << "," << report.planes << "," << report.state << "\n";
    }
  });
  const double sequence_s = rows_.size() < 2 ? 0 : rows_.back().t - rows_.front().t;
  const EstimatorSummary e = estimator_.value_or(EstimatorSummary{});
  const MapSummary m = map_.value_or(MapSummary{});
  const double odometry_wall = wall - m.refinement_s;  // the refinement runs after the rawlog
  const size_t map_planes = m.planes_map ? m.planes_map->confirmedPlanes().size() : 0;
  const size_t tentative_planes = m.planes_map ? m.planes_map->planes().size() - map_planes : 0;
  JsonObject summary;
  summary.flag("complete", end_.complete)
      .text("input_error", end_.input_error)
      .integer("frames", static_cast<long long>(rows_.size()))
      .integer("poses", static_cast<long long>(poses_))
      .stamp("initialized_at", e.initialized_at)
      .number("time_offset_s", e.time_offset_s)
      .text("time_offset_note", e.time_offset_note)
      .integer("resets", static_cast<long long>(e.resets.size()))
      .objects("reset_causes", resetCausesJson(e.resets))
      .objects("planes_rejected_as_moving", planeRejectionsJson(e.rejected_planes))
      .integer("camera_height_frames", camera_height_frames)
      .integer("planes_discovered", static_cast<long long>(e.planes_discovered))
      .objects("discovered_planes_accepted", discoveriesJson(e.discoveries, true))
      .objects("discovered_planes_rejected_as_moving", discoveriesJson(e.discoveries, false))
      .number("total_ms_median", percentile(total_ms, 0.5))
      .number("total_ms_p95", percentile(total_ms, 0.95))
      .number("load_ms_median", percentile(load_ms, 0.5))
      .number("processing_ms_median", percentile(processing_ms, 0.5))
      .number("processing_ms_p95", percentile(processing_ms, 0.95))
      .number("frontend_ms_median", percentile(frontend_ms, 0.5))
      .number("frontend_ms_p95", percentile(frontend_ms, 0.95))
      .number("optimization_ms_median", percentile(optimization_ms, 0.5))
      .number("optimization_ms_p95", percentile(optimization_ms, 0.95))
      .number("wall_s", wall)
      .number("sequence_s", sequence_s)
      .number("real_time_factor", odometry_wall > 0 ? sequence_s / odometry_wall : 0)
      .number("peak_memory_mb", peakMemoryMb())
      .integer("map_planes", static_cast<long long>(map_planes))
      .integer("tentative_planes", static_cast<long long>(tentative_planes))
      .number("refinement_s", m.refinement_s)
      .text("refinement", m.refinement_report);
  if (loops_) {
    const auto accepted = std::count_if(loops_->events.begin(), loops_->events.end(),
                                        [](const LoopEvent& e) { return e.check.accepted; });
    summary.integer("loop_keyframes", static_cast<long long>(loops_->keyframes))
        .integer("loops_found", static_cast<long long>(loops_->events.size()))
        .integer("loops_accepted", accepted)
        .integer("loops_rejected", static_cast<long long>(loops_->events.size()) - accepted)
        .integer("map_keyframes", static_cast<long long>(loops_->map_keyframes))
        .objects("loops", loopsJson(loops_->events));
    // The first keyframe that revisited the loaded map's; null when none did.
    if (loops_->relocalized_t)
      summary.stamp("relocalized_t", *loops_->relocalized_t);
    else
      summary.number("relocalized_t", std::nan(""));
  }
  summary.text("status", estimator_ ? e.status : "no estimator");
  writeFileAtomically(path("summary.json"), [&](std::ostream& s) { s << summary.str(); });
}

}  // namespace rpvio
