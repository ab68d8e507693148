#include "sim/sequence_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "common/atomic_file.h"
#include "common/json_text.h"
#include "rawlog_io/calibration.h"
#include "rawlog_io/rawlog_writer.h"
#include "rawlog_io/trajectory_io.h"
#include "sim/simulator.h"

namespace fs = std::filesystem;

namespace rpvio::sim {
namespace {

StampedPose stampedPose(const Simulator& sim, double t) {
  const FlightState s = sim.state(t);
  StampedPose p;
  p.t = t;
  p.p = s.p;
  p.q = Eigen::Quaterniond(s.R_wb);
  return p;
}

/// Labels as colours: planes get hashed hues, characters black, nothing white.
cv::Mat colourMask(const cv::Mat& mask) {
  cv::Mat out(mask.size(), CV_8UC3);
  for (int r = 0; r < mask.rows; ++r)
    for (int c = 0; c < mask.cols; ++c) {
      const int l = mask.at<uint8_t>(r, c);
      cv::Vec3b colour(255, 255, 255);
      if (l == 0) {
        colour = cv::Vec3b(0, 0, 0);
      } else if (l != 255) {
        colour = cv::Vec3b(static_cast<uint8_t>((l * 97) % 200 + 55),
                           static_cast<uint8_t>((l * 57) % 200 + 55),
                           static_cast<uint8_t>((l * 151) % 200 + 55));
      }
      out.at<cv::Vec3b>(r, c) = colour;
    }
  return out;
}

}  // namespace

SequenceStats writeSequence(const SimConfig& config, const std::string& out_dir,
                            const std::function<void(size_t, size_t)>& progress) {
  fs::create_directories(out_dir);
  Simulator sim(config);
  std::vector<ImuBiasState> biases;
  const std::vector<ImuSample> imu = sim.imuStream(&biases);
  const std::vector<double> frame_times = sim.frameTimes();
  SequenceStats stats;
  stats.imu_samples = imu.size();

  const std::string rawlog = (fs::path(out_dir) / "seq.rawlog").string();
  RawlogWriter writer(rawlog, sim.calibration());
  Trajectory groundtruth;
  // Frame k is encoded and written (PNG compression, the rawlog) on a second thread while frame
  // k+1 renders; the rawlog's order is the loop's, as each write waits for the previous one.
  std::future<void> writing;
  auto finishWriting = [&] {
    if (writing.valid()) writing.get();  // rethrows the writer's exception
  };
  size_t i_imu = 0;
  for (size_t k = 0; k <= frame_times.size(); ++k) {
    // Camera stamps are t_cam = τ − time_offset; IMU and ground truth up to that stamp go first.
    const bool has_frame = k < frame_times.size();
    const double stamp = has_frame ? frame_times[k] - config.time_offset : INFINITY;
    std::vector<std::pair<std::optional<ImuSample>, StampedPose>> imu_batch;
    for (; i_imu < imu.size() && imu[i_imu].t <= stamp; ++i_imu) {
      groundtruth.push_back(stampedPose(sim, imu[i_imu].t));
      imu_batch.emplace_back(std::nullopt, groundtruth.back());
      if (!config.faults.dropsImu(imu[i_imu].t))
        imu_batch.back().first = config.faults.saturate(imu[i_imu]);
    }
    std::optional<RenderedFrame> frame;
    if (has_frame && stamp >= 0 &&
        !config.faults.dropsFrame(frame_times[k], 1.0 / config.camera_rate)) {
      frame = sim.render(frame_times[k], static_cast<int>(k));
      config.faults.applyToFrame(frame_times[k], frame->image, frame->mask);
      ++stats.frames;
    }
    finishWriting();
    writing = std::async(std::launch::async, [&, imu_batch = std::move(imu_batch),
                                              frame = std::move(frame), stamp] {
      for (const auto& [sample, pose] : imu_batch) {
        if (sample) writer.addImu(*sample);
        writer.addGroundTruth(pose);
      }
      if (!frame) return;
      writer.addImage(stamp, frame->image);
      writer.addMask(stamp, frame->mask);
      stats.dynamic_coverage.push_back(
          {stamp, cv::countNonZero(frame->dynamic) / static_cast<double>(frame->dynamic.total())});
      if (progress) progress(stats.dynamic_coverage.size(), frame_times.size());
    });
  }
  finishWriting();
  for (size_t i = 1; i < groundtruth.size(); ++i)
    stats.path_length += (groundtruth[i].p - groundtruth[i - 1].p).norm();
  for (const auto& s : imu) stats.max_speed = std::max(stats.max_speed, sim.state(s.t).v.norm());
  stats.coverage = summarizeCoverage(stats.dynamic_coverage);

  writeTum((fs::path(out_dir) / "groundtruth.tum").string(), groundtruth);
  writeFileAtomically(
      (fs::path(out_dir) / "groundtruth_biases.csv").string(), [&](std::ostream& out) {
        out << "# t [s], gyro bias x y z [rad/s], accel bias x y z [m/s^2]\n";
        char line[256];
        for (size_t i = 0; i < imu.size(); ++i) {
          const auto& b = biases[i];
          std::snprintf(line, sizeof(line), "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", imu[i].t,
                        b.gyro.x(), b.gyro.y(), b.gyro.z(), b.accel.x(), b.accel.y(), b.accel.z());
          out << line;
        }
      });
  writeFileAtomically((fs::path(out_dir) / "dynamic_fraction.csv").string(),
                      [&](std::ostream& out) {
                        out << "# t [s] (camera), fraction of the image covered by moving things\n";
                        char line[64];
                        for (const CoverageSample& c : stats.dynamic_coverage) {
                          std::snprintf(line, sizeof(line), "%.6f,%.6f\n", c.t, c.fraction);
                          out << line;
                        }
                      });
  writeFileAtomically((fs::path(out_dir) / "sequence.json").string(), [&](std::ostream& out) {
    out << JsonObject()
               .text("profile", config.profile_name)
               .integer("seed", static_cast<long long>(config.seed))
               .integer("characters", config.scene.characters)
               .number("duration_s", config.duration)
               .integer("frames", static_cast<long long>(stats.frames))
               .number("path_length_m", stats.path_length)
               .number("dynamic_fraction_mean", stats.coverage.mean)
               .number("dynamic_fraction_median", stats.coverage.median)
               .number("dynamic_fraction_p90", stats.coverage.p90)
               .number("dynamic_fraction_peak", stats.coverage.peak)
               .number("dynamic_fraction_first_2s", stats.coverage.first_2s_mean)
               .str();
  });
  writeFileAtomically((fs::path(out_dir) / "scene_used.ini").string(), [&](std::ostream& out) {
    out << "# the scene of this sequence (profile " << config.profile_name
        << " and overrides): rpvio-sim --config reads it back\n"
        << config.describe();
  });
  saveCalibration((fs::path(out_dir) / "calib.ini").string(), sim.calibration());
  writer.close();
  return stats;
}

void writePreview(const SimConfig& config, double t, const std::string& png_path) {
  Simulator sim(config);
  const RenderedFrame frame = sim.render(t, 0);
  cv::Mat image_bgr, side_by_side;
  cv::cvtColor(frame.image, image_bgr, cv::COLOR_GRAY2BGR);
  cv::hconcat(image_bgr, colourMask(frame.mask), side_by_side);
  const std::string tmp = temporaryPathFor(png_path) + ".png";
  if (!cv::imwrite(tmp, side_by_side)) throw std::runtime_error(png_path + ": cannot write");
  fs::rename(tmp, png_path);
}

}  // namespace rpvio::sim
