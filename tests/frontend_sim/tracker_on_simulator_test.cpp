// The front-end against the simulator's ground truth: sub-pixel tracking accuracy on a static
// sequence, and features that stay on static planes while characters dance in front of them;
// tracks that follow a hand-held camera's fast turns with the gyroscope's prediction.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "mrpt_modules/frontend/feature_tracker.h"
#include "mrpt_modules/imu/gyro_rotation.h"
#include "sim/simulator.h"

namespace rpvio {
namespace {

sim::SimConfig config(int characters) {
  sim::SimConfig c;
  c.scene.characters = characters;
  c.duration = 5.0;
  return c;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * (v.size() - 1))];
}

struct TrackingAccuracy {
  double median_px, p95_px;
  double births;  // new features per tracked feature and frame
  size_t positions;
};

/// The tracked pixels of 5 s of the static sequence against the analytic projections of the
/// points each track was born on.
TrackingAccuracy staticSequenceAccuracy(const TrackerOptions& options) {
  sim::Simulator sim(config(0));
  FeatureTracker tracker(sim.calibration().camera, options);
  std::map<int, Eigen::Vector3d> landmark;  // feature id → 3D point seen at its detection
  std::vector<double> errors;
  size_t observations = 0, births = 0;  // after the first frame (reported: track survival)
  const auto times = sim.frameTimes();
  for (size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    const sim::RenderedFrame frame = sim.render(t, static_cast<int>(k));
    const FeatureFrame features = tracker.track(t, frame.image, frame.mask);
    for (const auto& f : features.features) {
      if (k > 0) {
        ++observations;
        births += f.track_length == 1;
      }
      if (f.track_length == 1) {
        const sim::SceneHit hit = sim.castPixel(t, f.pixel.x(), f.pixel.y());
        EXPECT_NE(hit.label, sim::kMaskCharacter);
        landmark[f.id] = hit.point;
        continue;
      }
      const auto expected = sim.project(t, landmark.at(f.id));
      EXPECT_TRUE(expected);
      if (expected) errors.push_back((f.pixel - *expected).norm());
    }
  }
  EXPECT_GT(errors.size(), 5000u);
  if (errors.empty()) return {0, 0, 0, 0};
  return {percentile(errors, 0.5), percentile(errors, 0.95),
          static_cast<double>(births) / observations, errors.size()};
}

TEST(TrackerOnSimulator, StaticSequenceTracksAtAnalyticProjections) {
  const TrackingAccuracy a = staticSequenceAccuracy(TrackerOptions{});
  std::printf(
      "static 5 s: %zu tracked positions, error median %.3f px, p95 %.3f px, %.1f%% new "
      "features per frame\n",
      a.positions, a.median_px, a.p95_px, 100.0 * a.births);
  // Issue 5: median < 0.15 px, p95 < 0.5 px (measured 0.04 and 0.14 px with the birth patches
  // warped by their plane's homographies; 0.21 and 2.3 px with a translational re-alignment).
  EXPECT_LT(a.median_px, 0.15);
  EXPECT_LT(a.p95_px, 0.5);
}

TEST(TrackerOnSimulator, WithoutMasksTheNeighboursWarpKeepsTracksAlive) {
  TrackerOptions options;
  options.use_masks = false;
  const TrackingAccuracy warped = staticSequenceAccuracy(options);
  options.local_warps = false;
  const TrackingAccuracy unwarped = staticSequenceAccuracy(options);
  std::printf(
      "static 5 s, no masks: local warps median %.3f px, p95 %.3f px, %.1f%% new per frame; "
      "without %.3f px, %.3f px, %.1f%%\n",
      warped.median_px, warped.p95_px, 100 * warped.births, unwarped.median_px, unwarped.p95_px,
      100 * unwarped.births);
  // Measured: 0.073 / 0.56 px and 5.3 % new per frame with the neighbours' warp, 0.135 / 0.75 px
  // and 9.6 % without (masks: 0.044 / 0.16 px, 4.5 %; the tail is features at depth edges,
  // whose neighbours lie on another surface). Issue 5's median bar holds; both the error and the
  // track endings fall.
  EXPECT_LT(warped.median_px, 0.15);
  EXPECT_LT(warped.median_px, unwarped.median_px);
  EXPECT_LT(warped.p95_px, unwarped.p95_px);
  EXPECT_LT(warped.births, 0.7 * unwarped.births);
}

struct FastTurnTracking {
  double kept;  // of the previous frame's features still in view, the share still tracked
  double median_px, p95_px;      // tracked pixel against the analytic projection
  double largest_turn_px = 0;    // largest image motion of a frame's centre by the turn alone
  double even_births = 0;        // share of the new features born on even pixel coordinates
  double tracked_per_frame = 0;  // features continued from the previous frame, per frame
};

/// `duration` s of a simulator profile from `start` s, at `size` (the profile's when empty):
/// tracks from frame to frame with `options`.
FastTurnTracking platformTracking(const TrackerOptions& options, const char* profile, cv::Size size,
                                  double duration, double start = 0) {
  sim::SimConfig c = sim::SimConfig::profile(profile);
  if (!size.empty()) {
    c.camera.width = size.width;
    c.camera.height = size.height;
  }
  c.duration = start + duration;
  sim::Simulator sim(c);
  const std::vector<ImuSample> imu = sim.imuStream();
  const CameraIntrinsics camera = sim.calibration().camera;
  FeatureTracker tracker(camera, options);
  const Eigen::Matrix3d R_BC = sim.calibration().T_BC.linear();
  std::map<int, Eigen::Vector3d> landmark;
  std::vector<double> errors;
  std::vector<int> previous;  // the previous frame's feature ids
  size_t continued = 0, offered = 0, births = 0, even = 0;
  FastTurnTracking out;
  std::vector<double> times;
  for (const double t : sim.frameTimes())
    if (t >= start) times.push_back(t);
  for (size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    // What FeatureTrackerModule hands the tracker: the gyroscope (noise and bias as simulated)
    // between the two images, turned into the camera's frame.
    Eigen::Matrix3d R_cur_prev = Eigen::Matrix3d::Identity();
    if (k > 0) {
      std::vector<ImuSample> before;
      for (const ImuSample& s : imu)
        if (s.t < t) before.push_back(s);
      R_cur_prev = cameraRotationBetween(before, times[k - 1], t, R_BC);
      const Eigen::Vector3d centre = R_cur_prev * Eigen::Vector3d::UnitZ();
      out.largest_turn_px =
          std::max(out.largest_turn_px,
                   camera.fx * Eigen::Vector2d(centre.x(), centre.y()).norm() / centre.z());
    }
    const sim::RenderedFrame frame = sim.render(t, static_cast<int>(k));
    const FeatureFrame features =
        tracker.track(t, frame.image, frame.mask, k > 0 ? &R_cur_prev : nullptr);
    std::set<int> tracked;
    for (const auto& f : features.features) {
      if (f.track_length == 1) {
        landmark[f.id] = sim.castPixel(t, f.pixel.x(), f.pixel.y()).point;
        ++births;
        even += std::fmod(f.pixel.x(), 2.0) == 0 && std::fmod(f.pixel.y(), 2.0) == 0;
        continue;
      }
      tracked.insert(f.id);
      const auto expected = sim.project(t, landmark.at(f.id));
      if (expected) errors.push_back((f.pixel - *expected).norm());
    }
    // Offered: the previous frame's features whose point is still in view, a KLT half-window
    // inside the image.
    const double margin = 0.5 * options.klt_window;
    for (int id : previous) {
      const auto at = sim.project(t, landmark.at(id));
      if (!at || at->x() < margin || at->y() < margin || at->x() > c.camera.width - margin ||
          at->y() > c.camera.height - margin)
        continue;
      ++offered;
      continued += tracked.count(id);
    }
    previous.clear();
    for (const auto& f : features.features) previous.push_back(f.id);
  }
  out.kept = offered ? static_cast<double>(continued) / offered : 0;
  out.tracked_per_frame = static_cast<double>(continued) / std::max<size_t>(1, times.size() - 1);
  out.even_births = births ? static_cast<double>(even) / births : 0;
  if (!errors.empty()) {
    out.median_px = percentile(errors, 0.5);
    out.p95_px = percentile(errors, 0.95);
  }
  return out;
}

/// The first `duration` s of the handheld profile (head turns peaking at 3 rad/s from the start),
/// at `size` (640x360 unless given), with the gyroscope's rotation prediction or without, corners
/// on `detection_level`.
FastTurnTracking handheldTracking(bool predict_rotation, const char* profile = "handheld",
                                  cv::Size size = {640, 360},
                                  int detection_level = TrackerOptions{}.detection_level,
                                  double duration = 3) {
  TrackerOptions options;
  options.predict_rotation = predict_rotation;
  options.detection_level = detection_level;
  return platformTracking(options, profile, size, duration);
}

TEST(TrackerOnSimulator, TheGyroscopesPredictionFollowsFastTurns) {
  const FastTurnTracking predicted = handheldTracking(true);
  const FastTurnTracking unpredicted = handheldTracking(false);
  const FastTurnTracking slow = handheldTracking(true, "paper");  // the paper flight, same size
  std::printf(
      "handheld 3 s at 640x360 (turns up to %.0f px per frame): predicted %.1f%% kept, error "
      "median %.3f px, p95 %.3f px; without %.1f%% kept, %.3f px, %.3f px; paper flight %.1f%%\n",
      predicted.largest_turn_px, 100 * predicted.kept, predicted.median_px, predicted.p95_px,
      100 * unpredicted.kept, unpredicted.median_px, unpredicted.p95_px, 100 * slow.kept);
  // Measured: 89.7 % kept (0.044 / 0.363 px) against 70.2 % without; the slow paper flight
  // keeps 92.8 % (tracks end at mask edges and in the checks whatever the motion).
  EXPECT_GT(predicted.largest_turn_px, 40);  // beyond what a 21 px window reaches on 3 levels
  EXPECT_LT(unpredicted.kept, slow.kept - 0.1);
  EXPECT_GT(predicted.kept, slow.kept - 0.05);
  EXPECT_LT(predicted.median_px, 0.15);  // the static sequence's bar
}

TEST(TrackerOnSimulator, At1280PixelsWideCornersOnTheHalfResolutionImageTrackAsWell) {
  // The default detection level at 1280x720 is 1 (0.81x the front-end's time, bench_frontend);
  // the corners born there must track as well as full-resolution ones.
  const cv::Size hd(1280, 720);
  const FastTurnTracking half = handheldTracking(true, "handheld", hd, -1, 1.5);
  const FastTurnTracking full = handheldTracking(true, "handheld", hd, 0, 1.5);
  std::printf(
      "handheld 1.5 s at 1280x720: corners at half resolution %.1f%% kept, error median "
      "%.3f px, p95 %.3f px (%.0f%% born on even pixels); at full resolution %.1f%%, "
      "%.3f px, %.3f px (%.0f%%)\n",
      100 * half.kept, half.median_px, half.p95_px, 100 * half.even_births, 100 * full.kept,
      full.median_px, full.p95_px, 100 * full.even_births);
  EXPECT_EQ(half.even_births, 1.0);  // level-1 pixels are the even full-resolution ones
  EXPECT_LT(full.even_births, 0.5);
  EXPECT_GT(half.kept, full.kept - 0.02);
  EXPECT_LT(half.median_px, 0.15);  // the static sequence's bar
  EXPECT_LT(half.p95_px, 1.5 * full.p95_px);
}

TEST(TrackerOnSimulator, ThePlanesHomographyFollowsACarsRoadWithOnePyramidLevelLess) {
  // The car profile at full speed (10 m/s, 10 Hz, the road 1.6 m below the camera: its nearest
  // visible points move ~40 px per frame), 3 s after the 6 s ramp. With each plane's homography
  // at constant velocity as the prediction, two pyramid levels keep the road's tracks as the
  // default three do; with the rotation alone they lose some.
  TrackerOptions options;  // the default: three levels, the rotation alone
  const FastTurnTracking three_levels = platformTracking(options, "car", {}, 3.0, 7.0);
  options.klt_levels = 1;
  const FastTurnTracking rotation = platformTracking(options, "car", {}, 3.0, 7.0);
  options.predict_plane_motion = true;
  const FastTurnTracking planes = platformTracking(options, "car", {}, 3.0, 7.0);
  std::printf(
      "car at 10 m/s, 3 s, two pyramid levels: plane prediction %.1f%% kept, error median %.3f "
      "px, p95 %.3f px; rotation only %.1f%%, %.3f px, %.3f px; three levels %.1f%%\n",
      100 * planes.kept, planes.median_px, planes.p95_px, 100 * rotation.kept, rotation.median_px,
      rotation.p95_px, 100 * three_levels.kept);
  // Measured: 47.4 % (0.069 / 0.550 px) against 41.3 % with the rotation alone; three levels
  // 47.8 %. Most of the road's tracks that end are born on its far, aliased texture and fail
  // the anchored correlation on their second frame, whatever the prediction.
  EXPECT_GT(planes.kept, rotation.kept + 0.03);
  EXPECT_GT(planes.kept, three_levels.kept - 0.01);
  EXPECT_LT(planes.median_px, 0.15);  // the static sequence's bar
}

/// Fraction of (feature, frame) pairs whose tracked pixel lies on a character.
double fractionOnCharacters(bool use_masks, size_t* samples) {
  sim::Simulator sim(config(4));
  TrackerOptions options;
  options.use_masks = use_masks;
  FeatureTracker tracker(sim.calibration().camera, options);
  size_t total = 0, on_characters = 0;
  const auto times = sim.frameTimes();
  for (size_t k = 0; k < times.size(); ++k) {
    const sim::RenderedFrame frame = sim.render(times[k], static_cast<int>(k));
    for (const auto& f : tracker.track(times[k], frame.image, frame.mask).features) {
      ++total;
      on_characters +=
          sim.castPixel(times[k], f.pixel.x(), f.pixel.y()).label == sim::kMaskCharacter;
    }
  }
  *samples = total;
  return static_cast<double>(on_characters) / total;
}

TEST(TrackerOnSimulator, RpvioModeKeepsFeaturesOnStaticPlanes) {
  size_t samples = 0;
  const double masked = fractionOnCharacters(true, &samples);
  std::printf("C4, rpvio mode: %.3f%% of %zu feature observations on characters\n", 100 * masked,
              samples);
  EXPECT_GT(samples, 5000u);
  EXPECT_LE(masked, 0.01);
}

TEST(TrackerOnSimulator, VinsModeTracksCharactersToo) {
  size_t samples = 0;
  const double unmasked = fractionOnCharacters(false, &samples);
  std::printf("C4, vins-mono mode: %.3f%% of %zu feature observations on characters\n",
              100 * unmasked, samples);
  EXPECT_GT(unmasked, 0.0);
}

}  // namespace
}  // namespace rpvio
