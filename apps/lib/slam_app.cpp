#include "apps/lib/slam_app.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "apps/lib/command_line.h"
#include "mrpt_modules/core/pipeline.h"
#include "mrpt_modules/estimator/estimator_module.h"
#include "mrpt_modules/frontend/feature_tracker_module.h"
#include "rawlog_io/atomic_file.h"
#include "rawlog_io/trajectory_io.h"

namespace fs = std::filesystem;

namespace rpvio::apps {
namespace {

const char* kUsage =
    "usage: rpvio-slam --config config/<mode>.ini --calib DIR/calib.ini --rawlog DIR/seq.rawlog\n"
    "                  --out OUTDIR [--quiet]\n"
    "  Plays the rawlog through the modules of the config and writes OUTDIR/trajectory.tum (body "
    "in\n"
    "  world, every frame once initialized), OUTDIR/stats.csv (per frame) and "
    "OUTDIR/summary.json.\n";

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1))];
}

double peakMemoryMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // kB on Linux
}

}  // namespace

int slamMain(int argc, char** argv) {
  return runApp("rpvio-slam", kUsage, [&] {
    const CommandLine cli(argc, argv, {"config", "calib", "rawlog", "out"}, {"quiet"});
    const std::string out = cli.value("out");
    registerFrontendModules();
    registerEstimatorModules();
    Pipeline pipeline(cli.value("config"), Calibration::load(cli.value("calib")));
    if (cli.has("quiet"))
      for (const auto& m : pipeline.modules()) m->setMinLoggingLevel(mrpt::system::LVL_WARN);
    Trajectory trajectory;
    pipeline.context().bus.subscribe<StateEstimate>([&](const StateEstimate& s) {
      StampedPose p;
      p.t = s.t;
      p.p = Eigen::Vector3d(s.pose[0], s.pose[1], s.pose[2]);
      p.q = Eigen::Quaterniond(s.pose[6], s.pose[3], s.pose[4], s.pose[5]);
      trajectory.push_back(p);
    });
    const bool terminal = isatty(STDERR_FILENO) && !cli.has("quiet");
    const auto start = std::chrono::steady_clock::now();
    size_t frames = 0;
    pipeline.context().bus.subscribe<FeatureFrame>([&](const FeatureFrame&) {
      ++frames;
      if (terminal && frames % 10 == 0) {
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "\rframe %zu  %.1f frames/s   ", frames, frames / s);
      }
    });
    pipeline.play(cli.value("rawlog"));
    if (terminal) std::fprintf(stderr, "\n");
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    fs::create_directories(out);
    writeTum((fs::path(out) / "trajectory.tum").string(), trajectory);
    const auto estimator = pipeline.find<SlidingWindowEstimatorModule>();
    std::vector<double> ms;
    if (estimator) {
      writeFileAtomically((fs::path(out) / "stats.csv").string(), [&](std::ostream& s) {
        s << "t,estimator_ms,features,tracking\n";
        for (const auto& f : estimator->timings()) {
          s << f.t << "," << f.estimator_ms << "," << f.features << "," << f.tracking << "\n";
          ms.push_back(f.estimator_ms);
        }
      });
    }
    const double sequence_s = trajectory.empty() || frames == 0 ? 0 : frames / 20.0;
    writeFileAtomically((fs::path(out) / "summary.json").string(), [&](std::ostream& s) {
      s << "{\n  \"frames\": " << frames << ",\n  \"poses\": " << trajectory.size()
        << ",\n  \"initialized_at\": " << (estimator ? estimator->initializedAt() : -1)
        << ",\n  \"resets\": " << (estimator ? estimator->estimator().resets() : 0)
        << ",\n  \"estimator_ms_median\": " << percentile(ms, 0.5)
        << ",\n  \"estimator_ms_p95\": " << percentile(ms, 0.95) << ",\n  \"wall_s\": " << wall
        << ",\n  \"real_time_factor_at_20hz\": " << (wall > 0 ? sequence_s / wall : 0)
        << ",\n  \"peak_memory_mb\": " << peakMemoryMb() << "\n}\n";
    });
    std::printf("%zu frames, %zu poses, wall %.1f s; outputs in %s\n", frames, trajectory.size(),
                wall, out.c_str());
    return 0;
  });
}

}  // namespace rpvio::apps
