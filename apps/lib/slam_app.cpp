#include "apps/lib/slam_app.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <opencv2/core/utility.hpp>

#include "apps/lib/command_line.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "common/json_text.h"
#include "mrpt_modules/core/pipeline.h"
#include "mrpt_modules/estimator/estimator_module.h"
#include "mrpt_modules/frontend/feature_tracker_module.h"
#include "planes_map/plane_map_exporters.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/rawlog_labels.h"
#include "rawlog_io/trajectory_io.h"

namespace fs = std::filesystem;

namespace rpvio::apps {
namespace {

const char* kUsage =
    "usage: rpvio-slam --config config/<mode>.ini --calib DIR/calib.ini --rawlog DIR/seq.rawlog\n"
    "                  --out OUTDIR [--quiet] [--threads N]\n"
    "  Plays the rawlog through the modules of the config and writes to OUTDIR:\n"
    "    trajectory.tum  body in world, every frame once initialized (a reset leaves a gap)\n"
    "    trajectory_refined.tum  the keyframes after the batch refinement at the end of the run\n"
    "                    (batch_refinement = true in the config), in the plane map's frame\n"
    "    stats.csv       per frame: t, load_ms (image and mask decoding), frontend_ms,\n"
    "                    optimization_ms, total_ms (wall time from the previous frame's end to\n"
    "                    this one's, the sum of the three: a frame still waiting for IMU data\n"
    "                    is optimized with the next frame, in its optimization_ms), features,\n"
    "                    planes, state\n"
    "    summary.json    frames, initialization time, resets and causes, timing, real-time\n"
    "                    factor, peak memory; complete (false: the rawlog ended in bad input,\n"
    "                    input_error says where, the outputs hold the frames before it),\n"
    "                    map_planes (confirmed, exported), tentative_planes (seen too few times),\n"
    "                    refinement (the batch refinement's summary, \"\" if it did not run),\n"
    "                    refinement_s (its time, in wall_s but not in real_time_factor),\n"
    "                    status (the estimator's last status, e.g. why it never initialized)\n"
    "    planes.{yaml,ply,bt,3Dscene}, planes_topview.png  the plane map\n"
    "    config_used.ini the configuration in effect: every module's options, all keys\n"
    "  --threads N  OpenCV threads (default 1: the whole pipeline on one core, the setting of the\n"
    "               published timings; the benchmark runs sequences in parallel instead)\n";

constexpr double kOctomapResolution = 0.1;  // m

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
}

StampedPose stampedPose(const StateEstimate& s) {
  StampedPose p;
  p.t = s.t;
  p.p = Eigen::Vector3d(s.pose[0], s.pose[1], s.pose[2]);
  p.q = Eigen::Quaterniond(s.pose[6], s.pose[3], s.pose[4], s.pose[5]);
  return p;
}

double peakMemoryMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // kB on Linux
}

/// Camera images in the rawlog's image folder (for the ETA; 0 when unknown).
size_t countCameraImages(const std::string& rawlog) {
  const fs::path p(rawlog);
  const fs::path dir = p.parent_path() / (p.stem().string() + "_Images");
  std::error_code ec;
  size_t n = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().filename().string().rfind(labels::kCamera, 0) == 0) ++n;
  return n;
}

/// Per-frame wall times: the whole pipeline since the previous frame, the part spent decoding the
/// frame's image files, and the part the estimator spent (a frame whose IMU data is still to come
/// is optimized with the next one, so a slot can hold zero or two optimizations).
struct FrameRow {
  double t = 0, total_ms = 0, load_ms = 0, estimator_ms = 0;
};

/// `out` as a folder the outputs can be written to (created if needed); InputError otherwise.
void requireOutputFolder(const std::string& out) {
  std::error_code ec;
  if (fs::exists(out, ec) && !fs::is_directory(out, ec))
    throw InputError(out, "", "--out must be a folder, not a file");
  fs::create_directories(out, ec);
  if (ec) throw InputError(out, "", "cannot create the output folder: " + ec.message());
  const fs::path probe = fs::path(out) / ".rpvio-write-test";
  if (!std::ofstream(probe)) throw InputError(out, "", "cannot write in the output folder");
  fs::remove(probe, ec);
}

/// Why a rawlog without `label` cannot be played through this config.
std::string missingSensorReason(const std::string& label) {
  if (label == labels::kPlaneMask)
    return "no PLANE_MASK observation (plane masks) in its first 10 s, which this mode needs "
           "(use_masks = true); without masks, run the vins-mono mode (config/vins-mono.ini)";
  return "no " + label + " observation in its first 10 s; every mode needs " +
         (label == labels::kImu ? "the IMU" : "the camera images");
}

}  // namespace

int slamMain(int argc, char** argv) {
  return runApp("rpvio-slam", kUsage, [&] {
    const CommandLine cli(argc, argv, {"config", "calib", "rawlog", "out", "threads"}, {"quiet"});
    const std::string out = cli.value("out");
    cv::setNumThreads(cli.count("threads", 1));
    registerFrontendModules();
    registerEstimatorModules();
    Pipeline pipeline(cli.value("config"), loadCalibration(cli.value("calib")),
                      cli.has("quiet") ? mrpt::system::LVL_WARN : mrpt::system::LVL_INFO);
    Trajectory trajectory;
    pipeline.context().bus.subscribe<StateEstimate>(
        [&](const StateEstimate& s) { trajectory.push_back(stampedPose(s)); });
    // Subscribed after the modules: runs once the estimator has processed the frame.
    const bool terminal = isatty(STDERR_FILENO) && !cli.has("quiet");
    const size_t expected_frames = terminal ? countCameraImages(cli.value("rawlog")) : 0;
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto frame_start = start;
    std::vector<FrameRow> rows;
    const auto tracker = pipeline.find<FeatureTrackerModule>();
    const auto estimator = pipeline.find<SlidingWindowEstimatorModule>();
    size_t optimizations_counted = 0;
    pipeline.context().bus.subscribe<FeatureFrame>([&](const FeatureFrame& f) {
      const auto now = Clock::now();
      double estimator_ms = 0;
      for (; estimator && optimizations_counted < estimator->timings().size();
           ++optimizations_counted)
        estimator_ms += estimator->timings()[optimizations_counted].report.optimization_ms;
      rows.push_back({f.t, std::chrono::duration<double, std::milli>(now - frame_start).count(),
                      tracker ? tracker->takeLoadMs() : 0.0, estimator_ms});
      frame_start = now;
      if (!terminal || rows.size() % 10 != 0) return;
      const double s = std::chrono::duration<double>(now - start).count();
      const double rate = static_cast<double>(rows.size()) / s;
      std::fprintf(stderr, "\r%zu", rows.size());
      if (expected_frames >= rows.size()) {
        const int width = 30;
        const int done = static_cast<int>(width * rows.size() / expected_frames);
        std::fprintf(stderr, "/%zu [%s%s] ETA %.0f s", expected_frames,
                     std::string(done, '#').c_str(), std::string(width - done, '.').c_str(),
                     static_cast<double>(expected_frames - rows.size()) / rate);
      }
      std::fprintf(stderr, "  %.1f frames/s   ", rate);
    });
    // Bad input part-way (a truncated rawlog, a missing image, ...): the frames before it are
    // kept, written like a complete run's, then the error is reported and the exit code is 2.
    const auto missing = pipeline.missingSensors(cli.value("rawlog"));
    if (!missing.empty())
      throw InputError(cli.value("rawlog"), "", missingSensorReason(missing.front()));
    requireOutputFolder(out);
    std::exception_ptr input_error;
    std::string input_error_text;
    try {
      pipeline.play(cli.value("rawlog"));
    } catch (const InputError& e) {
      if (rows.empty()) throw;
      input_error = std::current_exception();
      input_error_text = e.what();
    }
    if (terminal) std::fprintf(stderr, "\n");
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();

    const std::string status = estimator ? estimator->estimator().statusDetail() : "no estimator";
    // A write failing (disk full, the folder removed meanwhile) is bad output: one line, exit 2;
    // every file is written whole or not at all.
    try {
      const auto path = [&](const char* name) { return (fs::path(out) / name).string(); };
      writeFileAtomically(path("config_used.ini"),
                          [&](std::ostream& s) { s << pipeline.effectiveConfig(); });
      writeTum(path("trajectory.tum"), trajectory);
      Trajectory refined;
      if (estimator)
        for (const auto& s : estimator->estimator().refinedTrajectory())
          refined.push_back(stampedPose(s));
      if (!refined.empty()) writeTum(path("trajectory_refined.tum"), refined);
      std::vector<double> total_ms, optimization_ms, frontend_ms, load_ms, processing_ms;
      writeFileAtomically(path("stats.csv"), [&](std::ostream& s) {
        s << "t,load_ms,frontend_ms,optimization_ms,total_ms,features,planes,state\n";
        s << std::fixed;
        for (size_t k = 0; k < rows.size(); ++k) {
          const FrameReport report = estimator && k < estimator->timings().size()
                                         ? estimator->timings()[k].report
                                         : FrameReport{"no estimator"};
          total_ms.push_back(rows[k].total_ms);
          load_ms.push_back(rows[k].load_ms);
          processing_ms.push_back(std::max(0.0, rows[k].total_ms - rows[k].load_ms));
          optimization_ms.push_back(report.optimization_ms);
          frontend_ms.push_back(std::max(0.0, processing_ms.back() - rows[k].estimator_ms));
          s << std::setprecision(6) << rows[k].t << std::setprecision(3) << "," << load_ms.back()
            << "," << frontend_ms.back() << "," << rows[k].estimator_ms << "," << total_ms.back()
            << "," << report.features << "," << report.planes << "," << report.state << "\n";
        }
      });
      const double sequence_s = rows.size() < 2 ? 0 : rows.back().t - rows.front().t;
      const double refinement_s = estimator ? estimator->estimator().refinementSeconds() : 0;
      const double odometry_wall = wall - refinement_s;  // the refinement runs after the rawlog
      const std::vector<Plane> planes =
          estimator ? estimator->estimator().planesMap().confirmedPlanes() : std::vector<Plane>{};
      const size_t tentative_planes =
          estimator ? estimator->estimator().planesMap().planes().size() - planes.size() : 0;
      writeFileAtomically(path("summary.json"), [&](std::ostream& s) {
        s << "{\n  \"complete\": " << (input_error ? "false" : "true")
          << ",\n  \"input_error\": " << jsonString(input_error_text)
          << ",\n  \"frames\": " << rows.size() << ",\n  \"poses\": " << trajectory.size()
          << ",\n  \"initialized_at\": " << (estimator ? estimator->initializedAt() : -1)
          << ",\n  \"time_offset_s\": " << (estimator ? estimator->estimator().timeOffset() : 0)
          << ",\n  \"time_offset_note\": "
          << jsonString(estimator ? estimator->estimator().timeOffsetNote() : "");
        s << ",\n  \"resets\": " << (estimator ? estimator->estimator().resets() : 0)
          << ",\n  \"reset_causes\": [";
        if (estimator) {
          const auto& log = estimator->estimator().resetLog();
          for (size_t k = 0; k < log.size(); ++k)
            s << (k ? ", " : "") << "{\"t\": " << log[k].t
              << ", \"cause\": " << jsonString(log[k].cause) << "}";
        }
        s << "],\n  \"total_ms_median\": " << percentile(total_ms, 0.5)
          << ",\n  \"total_ms_p95\": " << percentile(total_ms, 0.95)
          << ",\n  \"load_ms_median\": " << percentile(load_ms, 0.5)
          << ",\n  \"processing_ms_median\": " << percentile(processing_ms, 0.5)
          << ",\n  \"processing_ms_p95\": " << percentile(processing_ms, 0.95)
          << ",\n  \"frontend_ms_median\": " << percentile(frontend_ms, 0.5)
          << ",\n  \"frontend_ms_p95\": " << percentile(frontend_ms, 0.95)
          << ",\n  \"optimization_ms_median\": " << percentile(optimization_ms, 0.5)
          << ",\n  \"optimization_ms_p95\": " << percentile(optimization_ms, 0.95)
          << ",\n  \"wall_s\": " << wall << ",\n  \"sequence_s\": " << sequence_s
          << ",\n  \"real_time_factor\": " << (odometry_wall > 0 ? sequence_s / odometry_wall : 0)
          << ",\n  \"peak_memory_mb\": " << peakMemoryMb()
          << ",\n  \"map_planes\": " << planes.size()
          << ",\n  \"tentative_planes\": " << tentative_planes
          << ",\n  \"refinement_s\": " << refinement_s << ",\n  \"refinement\": "
          << jsonString(estimator ? estimator->estimator().refinementReport() : "")
          << ",\n  \"status\": " << jsonString(status) << "\n}\n";
      });
      if (estimator) {
        writePlanesYaml(path("planes.yaml"), planes);
        writePlanesPly(path("planes.ply"), planes);
        writePlanesOctomap(path("planes.bt"), planes, kOctomapResolution);
        writePlanesScene(path("planes.3Dscene"), planes);
        // The planes are the refinement's when it ran: drawn with its trajectory.
        writePlanesTopView(path("planes_topview.png"), planes,
                           refined.empty() ? trajectory : refined);
      }
    } catch (const InputError&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw InputError(out, "", std::string("writing the outputs failed: ") + e.what());
    }
    std::printf("%zu frames, %zu poses, %zu resets, wall %.1f s; outputs in %s%s\n", rows.size(),
                trajectory.size(), estimator ? estimator->estimator().resets() : 0, wall,
                out.c_str(), input_error ? " (the frames before the error below)" : "");
    if (trajectory.empty())
      std::printf("no pose: never initialized (last status: %s)\n", status.c_str());
    std::fflush(stdout);
    if (input_error) std::rethrow_exception(input_error);
    if (rows.empty())
      throw InputError(cli.value("rawlog"), "",
                       "no frame was processed (last status: " + status + ")");
    return 0;
  });
}

}  // namespace rpvio::apps
