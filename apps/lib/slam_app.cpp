#include "apps/lib/slam_app.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <opencv2/core/utility.hpp>
#include <optional>

#include "apps/lib/command_line.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "mrpt_modules/core/feature_frame.h"
#include "mrpt_modules/core/pipeline.h"
#include "mrpt_modules/estimator/estimator_types.h"
#include "mrpt_modules/loop/loop_closure_module.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/rawlog_labels.h"

namespace fs = std::filesystem;

namespace rpvio::apps {
namespace {

const char* kUsage =
    "usage: rpvio-slam --config config/<mode>.ini --calib DIR/calib.ini --rawlog DIR/seq.rawlog\n"
    "                  --out OUTDIR [--quiet] [--threads N] [--map DIR] [--save-map DIR]\n"
    "  Plays the rawlog through the modules of the config. OUTDIR gets config_used.ini and what\n"
    "  the config's output modules write (those of the shipped configs: docs/data-formats.md):\n"
    "    trajectory.tum  body in world, every frame from the initialization window's first\n"
    "                    (written when it initializes; a reset leaves a gap)\n"
    "    trajectory_refined.tum  the keyframes after the batch refinement at the end of the run\n"
    "                    ([MapBuilderModule] batch_refinement = true), in the plane map's frame\n"
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
    "  --save-map DIR  saves the loop closure's keyframes (poses in the map's frame, appearance)\n"
    "               in DIR/keyframes.rpvmap at the end of the run\n"
    "  --map DIR    starts from a map --save-map wrote: the run relocalizes in it at its first\n"
    "               revisit of a map keyframe (summary.json relocalized_t) and "
    "trajectory_loop.tum\n"
    "               is in the map's frame from then on; a map saved with another calibration is\n"
    "               refused. Both need LoopClosureModule in the config's [Pipeline] modules.\n"
    "  --threads N  OpenCV threads (default 1: the whole pipeline on one core, the setting of the\n"
    "               published timings; the benchmark runs sequences in parallel instead)\n";

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

/// A progress line on stderr every 10 frames: frames done (of the images in the rawlog's folder),
/// a bar and an ETA, the frame rate.
class ProgressLine {
 public:
  explicit ProgressLine(const std::string& rawlog) : expected_(countCameraImages(rawlog)) {}
  void frameDone() {
    if (++frames_ % 10 != 0) return;
    const double s = std::chrono::duration<double>(Clock::now() - start_).count();
    const double rate = static_cast<double>(frames_) / s;
    std::fprintf(stderr, "\r%zu", frames_);
    if (expected_ >= frames_) {
      const int width = 30;
      const int done = static_cast<int>(width * frames_ / expected_);
      std::fprintf(stderr, "/%zu [%s%s] ETA %.0f s", expected_, std::string(done, '#').c_str(),
                   std::string(width - done, '.').c_str(),
                   static_cast<double>(expected_ - frames_) / rate);
    }
    std::fprintf(stderr, "  %.1f frames/s   ", rate);
  }
  ~ProgressLine() {
    if (frames_ >= 10) std::fprintf(stderr, "\n");
  }

 private:
  using Clock = std::chrono::steady_clock;
  const size_t expected_;
  size_t frames_ = 0;
  const Clock::time_point start_ = Clock::now();
};

}  // namespace

SlamAppResult runSlam(const SlamAppOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  Pipeline pipeline(o.config, loadCalibration(o.calib),
                    o.quiet ? mrpt::system::LVL_WARN : mrpt::system::LVL_INFO, o.out,
                    {o.map, o.save_map});
  if ((!o.map.empty() || !o.save_map.empty()) && !pipeline.find<LoopClosureModule>())
    throw InputError(o.config, "",
                     "--map and --save-map need LoopClosureModule in [Pipeline] modules");
  const auto missing = pipeline.missingSensors(o.rawlog);
  if (!missing.empty()) throw InputError(o.rawlog, "", missingSensorReason(missing.front()));
  requireOutputFolder(o.out);
  if (!o.save_map.empty()) requireOutputFolder(o.save_map);
  writeFileAtomically((fs::path(o.out) / "config_used.ini").string(),
                      [&](std::ostream& s) { s << pipeline.effectiveConfig(); });
  SlamAppResult result;
  std::optional<ProgressLine> progress;
  if (o.progress && !o.quiet) progress.emplace(o.rawlog);
  // Subscribed after the modules: runs once they have processed the frame.
  pipeline.context().bus.subscribe<FeatureFrame>([&](const FeatureFrame&) {
    ++result.frames;
    if (progress) progress->frameDone();
  });
  pipeline.context().bus.subscribe<StateEstimate>([&](const StateEstimate&) { ++result.poses; });
  pipeline.context().bus.subscribe<EstimatorSummary>([&](const EstimatorSummary& s) {
    result.resets = s.resets.size();
    result.status = s.status;
  });
  // A write failing (disk full, the folder removed meanwhile) is bad output: one line, exit 2;
  // every file is written whole or not at all.
  try {
    try {
      pipeline.play(o.rawlog);
    } catch (const InputError& e) {
      // Bad input part-way (a truncated rawlog, a missing image, ...): the frames before it are
      // kept, written like a complete run's, then the error is reported.
      if (result.frames == 0) throw;
      result.input_error = e;
      progress.reset();
      pipeline.finish({false, e.what()});
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw InputError(o.out, "", std::string("writing the outputs failed: ") + e.what());
  }
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (result.frames == 0)
    throw InputError(o.rawlog, "", "no frame was processed (last status: " + result.status + ")");
  return result;
}

int slamMain(int argc, char** argv) {
  return runApp("rpvio-slam", kUsage, [&] {
    const CommandLine cli(
        argc, argv, {"config", "calib", "rawlog", "out", "threads", "map", "save-map"}, {"quiet"});
    cv::setNumThreads(cli.count("threads", 1));
    SlamAppOptions o;
    o.config = cli.value("config");
    o.calib = cli.value("calib");
    o.rawlog = cli.value("rawlog");
    o.out = cli.value("out");
    o.map = cli.valueOr("map", "");
    o.save_map = cli.valueOr("save-map", "");
    o.quiet = cli.has("quiet");
    o.progress = isatty(STDERR_FILENO);
    const SlamAppResult r = runSlam(o);
    std::printf("%zu frames, %zu poses, %zu resets, wall %.1f s; outputs in %s%s\n", r.frames,
                r.poses, r.resets, r.wall_s, o.out.c_str(),
                r.input_error ? " (the frames before the error below)" : "");
    if (r.poses == 0)
      std::printf("no pose: never initialized (last status: %s)\n", r.status.c_str());
    std::fflush(stdout);
    if (r.input_error) throw *r.input_error;
    return 0;
  });
}

}  // namespace rpvio::apps
