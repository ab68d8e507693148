#include "apps/lib/sim_app.h"

#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "apps/lib/command_line.h"
#include "planes_map/plane_map_exporters.h"
#include "sim/sequence_name.h"
#include "sim/sequence_writer.h"
#include "sim/simulator.h"

namespace fs = std::filesystem;

namespace rpvio::apps {
namespace {

const char* kUsage =
    "usage: rpvio-sim --characters N | --sequence NAME [--profile P] [--seed S]\n"
    "                 [--duration SEC] [--time-offset SEC] [--config INI] --out DIR\n"
    "       rpvio-sim --suite [--profile P] [--seed S] [--duration SEC] [--config INI]\n"
    "                 --out DIR\n"
    "       rpvio-sim --preview [--profile P] [--characters N] [--time SEC] [--config INI]\n"
    "                 --out FILE.png\n"
    "  Writes DIR/seq.rawlog (+ seq_Images/), DIR/groundtruth.tum, DIR/groundtruth_biases.csv,\n"
    "  DIR/groundtruth_planes.yaml (the scene's planes, id = mask label, in the plane map's\n"
    "  schema; moving objects' faces at t = 0 with their motion), DIR/calib.ini,\n"
    "  DIR/dynamic_fraction.csv (per frame: the fraction of the image moving things cover) and\n"
    "  DIR/sequence.json (profile, seed, coverage figures).\n"
    "  --sequence NAME: static, C<N> (N characters), MP (two pallet trucks and two sliding "
    "panels,\n"
    "  moving planar objects), MP-C<N> (both). --suite writes DIR/{static,C1,C2,C4,C6,C8}/ with "
    "the\n"
    "  same seed, and with --profile hard also DIR/MP/ and DIR/MP-C4/.\n"
    "  --profile: paper (default; the paper's RPVIO-Sim warehouse), hard (a crowd that fills\n"
    "  the view, CNN-like masks), or a platform's motion: handheld (30 Hz, 1280x720, head\n"
    "  turns up to 3 rad/s), drone (5 m/s, yaw turns of 2 rad/s), ground-robot (30 Hz,\n"
    "  848x480, planar at 0.5-1 m/s) or car (10 Hz, 1241x376, 0-10 m/s and a 90 deg turn);\n"
    "  --config INI overrides keys of the profile (every key: config/sim/warehouse.ini and\n"
    "  docs/configuration.md).\n"
    "  Fault injection (off by default; times in s of the sequence, intervals START:DURATION,\n"
    "  each option may repeat):\n"
    "    --drop-frame T        the frame nearest to T is lost\n"
    "    --drop-frames I       every frame in the interval is lost\n"
    "    --imu-gap I           no IMU sample in the interval\n"
    "    --blackout I          black images, masks all 0\n"
    "    --blur I [--blur-px PX]  horizontal motion blur over PX pixels (default 15)\n"
    "    --no-planes I         masks all 0 (no static plane recognized), images unchanged\n"
    "    --accel-saturation A, --gyro-saturation G   IMU components clipped to +-A m/s2, +-G "
    "rad/s\n"
    "    --time-offset 0.03    (above) a camera-IMU offset the estimator does not know about\n";

const std::set<std::string> kFaultOptions = {
    "drop-frame", "drop-frames", "imu-gap",          "blackout",       "blur",
    "blur-px",    "no-planes",   "accel-saturation", "gyro-saturation"};

sim::FaultInjection faultOptions(const CommandLine& cli) {
  sim::FaultInjection f;
  auto intervals = [&](const char* name, std::vector<sim::TimeInterval>& out) {
    for (const std::string& v : cli.values(name)) {
      try {
        out.push_back(sim::parseTimeInterval(v, std::string("--") + name));
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    }
  };
  for (const std::string& v : cli.values("drop-frame")) {
    char* end = nullptr;
    const double t = std::strtod(v.c_str(), &end);
    if (end == v.c_str() || *end != '\0' || !(t >= 0))
      throw UsageError("--drop-frame expects a time in seconds, got '" + v + "'");
    f.dropped_frames.push_back(t);
  }
  intervals("drop-frames", f.dropped_bursts);
  intervals("imu-gap", f.imu_gaps);
  intervals("blackout", f.blackouts);
  intervals("blur", f.motion_blur);
  intervals("no-planes", f.no_planes);
  f.blur_px = cli.number("blur-px", f.blur_px);
  f.accel_saturation = cli.number("accel-saturation", 0);
  f.gyro_saturation = cli.number("gyro-saturation", 0);
  if (f.blur_px < 1 || f.accel_saturation < 0 || f.gyro_saturation < 0)
    throw UsageError("--blur-px must be >= 1 and saturations >= 0");
  return f;
}

sim::SimConfig loadConfig(const CommandLine& cli) {
  sim::SimConfig config;
  try {
    config = sim::SimConfig::profile(cli.valueOr("profile", "paper"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--profile: ") + e.what());
  }
  if (cli.has("config")) config = sim::SimConfig::load(cli.value("config"), config);
  config.seed = static_cast<uint64_t>(cli.number("seed", static_cast<double>(config.seed)));
  config.duration = cli.number("duration", config.duration);
  config.time_offset = cli.number("time-offset", config.time_offset);
  config.scene.characters = static_cast<int>(cli.number("characters", config.scene.characters));
  config.faults = faultOptions(cli);
  if (config.duration <= 0) throw UsageError("--duration must be positive");
  if (config.scene.characters < 0 || config.scene.characters > 50)
    throw UsageError("--characters must be between 0 and 50");
  return config;
}

/// groundtruth_planes.yaml of a sequence.
void writeTruePlanes(const sim::SimConfig& config, const std::string& dir) {
  const sim::Simulator simulator(config);
  writePlanesYaml((fs::path(dir) / "groundtruth_planes.yaml").string(),
                  truePlanes(simulator.scene(), config.duration));
}

void generate(const sim::SimConfig& config, const std::string& dir) {
  const bool terminal = isatty(STDERR_FILENO);
  const auto start = std::chrono::steady_clock::now();
  const auto stats = sim::writeSequence(config, dir, [&](size_t done, size_t total) {
    if (!terminal) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "\r%s: frame %zu/%zu  %.1f frames/s  ETA %.0f s   ", dir.c_str(), done,
                 total, done / elapsed, (total - done) * elapsed / done);
  });
  if (terminal) std::fprintf(stderr, "\n");
  writeTruePlanes(config, dir);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "%s: %zu frames, %zu IMU samples, path %.1f m, max speed %.2f m/s, moving things cover "
      "%.1f%% of the image (median; 90th percentile %.1f%%), %.1f s\n",
      dir.c_str(), stats.frames, stats.imu_samples, stats.path_length, stats.max_speed,
      100 * stats.coverage.median, 100 * stats.coverage.p90, elapsed);
}

}  // namespace

std::vector<Plane> truePlanes(const sim::WarehouseScene& scene, double duration) {
  std::vector<Plane> planes;
  for (const sim::ScenePlane& s : scene.planes()) {
    Plane p;
    p.id = s.id;
    p.normal = s.normal;
    p.distance = s.distance();
    p.covariance.setZero();
    const Eigen::Vector3d u = s.width * s.u_axis, v = s.height * s.v_axis;
    p.polygon = {s.origin, s.origin + u, s.origin + u + v, s.origin + v};
    p.mask_ids = {s.id};
    p.last_seen = duration;
    planes.push_back(p);
  }
  for (const sim::MovingPlanarObject& object : scene.movingObjects()) {
    for (const sim::PosedFace& face : object.faces(0)) {
      Plane p;
      p.id = face.id;
      p.normal = face.normal;
      p.distance = face.distance;
      p.covariance.setZero();
      p.polygon.assign(face.corners.begin(), face.corners.end());
      p.mask_ids = {face.id};
      p.last_seen = duration;
      p.moving = true;
      p.motion = object.motion();
      planes.push_back(p);
    }
  }
  return planes;
}

int simMain(int argc, char** argv) {
  return runApp("rpvio-sim", kUsage, [&] {
    std::set<std::string> options = {"characters", "seed", "duration", "time-offset", "config",
                                     "out",        "time", "profile",  "sequence"};
    options.insert(kFaultOptions.begin(), kFaultOptions.end());
    const CommandLine cli(argc, argv, options, {"suite", "preview"});
    const std::string out = cli.value("out");
    if (cli.has("preview")) {
      sim::SimConfig config = loadConfig(cli);
      if (!cli.has("characters")) config.scene.characters = 4;
      sim::writePreview(config, cli.number("time", 12.0), out);
      std::printf("preview: %s\n", out.c_str());
      return 0;
    }
    if (cli.has("suite")) {
      const sim::SimConfig config = loadConfig(cli);
      for (const std::string& name : sim::suiteSequences(config.profile_name))
        generate(sim::withSequenceContent(config, *sim::parseSequenceName(name)),
                 (fs::path(out) / name).string());
      return 0;
    }
    if (cli.has("sequence")) {
      const auto content = sim::parseSequenceName(cli.value("sequence"));
      if (!content || content->characters > 50)
        throw UsageError("unknown sequence '" + cli.value("sequence") +
                         "' (static, C<N>, MP or MP-C<N>; N <= 50)");
      generate(sim::withSequenceContent(loadConfig(cli), *content), out);
      return 0;
    }
    if (!cli.has("characters"))
      throw UsageError("missing required option --characters (or --sequence, --suite)");
    generate(loadConfig(cli), out);
    return 0;
  });
}

}  // namespace rpvio::apps
