// The batch refinement alone, on the simulator's ground truth: keyframes with the noise-free IMU
// between them, exact projections of plane points, and a start that is wrong the way a causal
// estimate is (tilted, moved, planes off). The refinement must bring it back to the truth.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "mrpt_modules/estimator/batch_refinement.h"
#include "mrpt_modules/factors/parameter_blocks.h"
#include "sim/simulator.h"

namespace rpvio {
namespace {

constexpr double kKeyframeStep = 0.25;  // s
constexpr double kDuration = 8.0;       // s

struct Scenario {
  KeyframeArchive archive;
  std::vector<Eigen::Isometry3d> truth;  // body poses of the keyframes
  std::map<int, PlaneEstimate> planes;   // by label (the map id here), started off the truth
  std::map<int, sim::ScenePlane> true_planes;
  double mount[7];
  double camera_height = 0;  // the calibration's (level_flight)
  int floor = -1;            // the label of the lowest upward-facing plane
};

/// Keyframes every 0.25 s from 0.5 s; a 12x10 grid of plane points born every second, seen 3 s.
/// The keyframes start from the truth tilted by `tilt_deg` about the first keyframe (a causal
/// estimate whose gravity direction was off, everything else consistent with it), the planes
/// tilted by 1 deg more and moved by 5 cm. With `break_after`, the IMU chain breaks after the
/// keyframe at that time (as at a reset). `noise`: the observations' Gaussian noise (normalized
/// image units, a fixed seed). `level_flight`: at a constant height (no wave, no take-off push),
/// every keyframe held over the floor at the calibration's camera_height (ground_label).
void build(Scenario& s, double tilt_deg, double break_after = -1, double noise = 0,
           bool level_flight = false) {
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0, noise);
  sim::SimConfig config;
  config.duration = kDuration;
  config.imu_noise = false;
  if (level_flight) config.flight.height_amplitude = config.flight.start_push = 0;
  sim::Simulator sim(config);
  const auto imu = sim.imuStream();
  const Eigen::Vector3d center = sim.bodyPose(0.5).translation();
  Eigen::Isometry3d start_error = Eigen::Isometry3d::Identity();
  start_error.linear() =
      Eigen::AngleAxisd(tilt_deg * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix();
  start_error.translation() = center - start_error.linear() * center;
  const Calibration calib = sim.calibration();
  setPoseBlock(calib.T_BC, s.mount);
  s.camera_height = calib.camera_height;
  double floor_height = 0;
  for (const auto& p : sim.scene().planes())
    if (p.normal.z() > 0.99 && (s.floor < 0 || p.distance() < floor_height)) {
      s.floor = p.id;
      floor_height = p.distance();
    }
  FeatureManager features;
  struct Landmark {
    Eigen::Vector3d point;
    int label;
    double born;
  };
  std::vector<Landmark> landmarks;
  uint64_t id = 0;
  for (double t = 0.5; t <= kDuration + 1e-9; t += kKeyframeStep, ++id) {
    if (std::fmod(t - 0.5, 1.0) < 1e-9)
      for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 10; ++j) {
          const sim::SceneHit hit = sim.castPixel(t, 30 + 50.0 * i, 30 + 45.0 * j);
          if (hit.label > 0) landmarks.push_back({hit.point, hit.label, t});
        }
    FeatureFrame frame;
    frame.t = t;
    const Eigen::Isometry3d C = sim.cameraPose(t).inverse();
    for (size_t k = 0; k < landmarks.size(); ++k) {
      const Eigen::Vector3d c = C * landmarks[k].point;
      if (t - landmarks[k].born > 3.0 || c.z() < 0.2) continue;
      const Eigen::Vector2d u = c.head<2>() / c.z();
      if (std::abs(u.x()) > 1 || std::abs(u.y()) > 0.75) continue;
      TrackedFeature f;
      f.id = static_cast<int>(k);
      f.plane_id = landmarks[k].label;
      f.normalized = noise > 0 ? Eigen::Vector2d(u.x() + gauss(rng), u.y() + gauss(rng)) : u;
      frame.features.push_back(f);
    }
    features.addFrame(id, frame);
    for (auto& [track_id, track] : features.tracks()) track.triangulated = true;

    const sim::FlightState state = sim.state(t);
    ArchivedKeyframe k;
    k.id = id;
    k.t = t;
    if (level_flight) k.ground_label = s.floor;
    s.truth.push_back(sim.bodyPose(t));
    setPoseBlock(start_error * s.truth.back(), k.pose);
    const Eigen::Vector3d v = start_error.linear() * state.v;
    std::copy(v.data(), v.data() + 3, k.speed_bias);
    if (t + kKeyframeStep <= kDuration + 1e-9) {
      const size_t first = static_cast<size_t>(std::llround(t * config.imu.rate_hz));
      const size_t last =
          static_cast<size_t>(std::llround((t + kKeyframeStep) * config.imu.rate_hz));
      auto pre = std::make_shared<ImuPreintegration>(imu[first].accel, imu[first].gyro,
                                                     Eigen::Vector3d::Zero(),
                                                     Eigen::Vector3d::Zero(), calib.imu);
      for (size_t i = first + 1; i <= last; ++i)
        pre->push(imu[i].t - imu[i - 1].t, imu[i].accel, imu[i].gyro);
      k.to_next = pre;
    }
    s.archive.add(k, keyframeObservations(
                         k.id, features, [](const FeatureTrack&) { return true; },
                         [](uint64_t) { return Eigen::Isometry3d::Identity(); }));
    if (std::abs(t - break_after) < 1e-9) s.archive.breakChain();
  }
  // The planes with enough tracks for homography factors (the others keep their start).
  std::map<int, size_t> tracks_of_label;
  for (const auto& l : landmarks) ++tracks_of_label[l.label];
  for (const auto& p : sim.scene().planes()) {
    if (tracks_of_label[p.id] < BatchRefinementOptions{}.min_plane_tracks) continue;
    s.true_planes[p.id] = p;
    const Eigen::Vector3d n =
        start_error.linear() *
        (Eigen::AngleAxisd(1.0 * M_PI / 180, p.normal.unitOrthogonal()) * p.normal);
    PlaneEstimate e;
    std::copy(n.data(), n.data() + 3, e.normal);
    e.distance[0] = p.distance() + n.dot(start_error.translation()) + 0.05;
    s.planes[p.id] = e;
  }
}

struct Errors {
  double position_m = 0, rotation_deg = 0, normal_deg = 0, offset_m = 0;
  size_t long_tracks = 0;  // inverse depths not eliminated
};

Errors solveAndCompare(Scenario& s, size_t segments, BatchRefinementOptions options = {}) {
  options.weight = 320;  // exact features: any weight
  BatchRefinement batch(
      s.archive, s.mount, [](int label) { return label; }, s.planes, options);
  EXPECT_TRUE(batch.solve());
  EXPECT_EQ(batch.segments(), segments);
  std::printf("%s\n", batch.report().c_str());
  Errors e;
  e.long_tracks = batch.longTracks();
  const auto refined = s.archive.trajectory();
  for (size_t k = 0; k < refined.size(); ++k) {
    const Eigen::Isometry3d T = poseIsometry(refined[k].pose);
    e.position_m = std::max(e.position_m, (T.translation() - s.truth[k].translation()).norm());
    e.rotation_deg = std::max(
        e.rotation_deg,
        Eigen::AngleAxisd(T.linear().transpose() * s.truth[k].linear()).angle() * 180 / M_PI);
  }
  for (const auto& [label, p] : s.planes) {
    const sim::ScenePlane& truth = s.true_planes.at(label);
    const Eigen::Vector3d n = Eigen::Vector3d(p.normal).normalized();
    e.normal_deg =
        std::max(e.normal_deg, std::acos(std::min(1.0, n.dot(truth.normal))) * 180 / M_PI);
    e.offset_m = std::max(e.offset_m, std::abs(p.distance[0] - truth.distance()));
  }
  return e;
}

/// Keyframes within 5 mm and 0.02 deg, planes within 0.05 deg and 5 mm of the truth.
void expectTruth(const Errors& e) {
  std::printf("refined keyframes within %.4f m, %.4f deg; planes within %.3f deg, %.4f m\n",
              e.position_m, e.rotation_deg, e.normal_deg, e.offset_m);
  EXPECT_LT(e.position_m, 0.005);
  EXPECT_LT(e.rotation_deg, 0.02);
  EXPECT_LT(e.normal_deg, 0.05);
  EXPECT_LT(e.offset_m, 0.005);
}

TEST(BatchRefinement, BringsATiltedStartBackToTheTruth) {
  Scenario s;
  build(s, 0.5);
  expectTruth(solveAndCompare(s, 1));
}

// A reset leaves two IMU-chained segments, each holding its first keyframe's position and yaw:
// they stay where they are, the planes (shared) come back.
TEST(BatchRefinement, TwoSegmentsAfterABrokenChain) {
  Scenario s;
  build(s, 0.0, 4.0);
  expectTruth(solveAndCompare(s, 2));
}

// Which inverse depths the Schur complement eliminates changes the cost of a step, not the step:
// with every track (seen over 12 keyframes) kept in the reduced system, the solution is the same.
// The observations carry 1 px of noise, so the solution is not the truth both would find anyway.
TEST(BatchRefinement, LongTracksKeptInTheReducedSystemGiveTheSameSolution) {
  Scenario eliminated, kept;
  const double one_pixel = 1.0 / 460;
  build(eliminated, 0.5, -1, one_pixel);
  build(kept, 0.5, -1, one_pixel);
  const Errors all_eliminated = solveAndCompare(eliminated, 1);
  EXPECT_EQ(all_eliminated.long_tracks, 0u);
  EXPECT_GT(all_eliminated.position_m, 1e-4);
  BatchRefinementOptions keep_all;
  keep_all.max_eliminated_track_span = 4;
  const Errors all_kept = solveAndCompare(kept, 1, keep_all);
  EXPECT_GT(all_kept.long_tracks, 100u);
  const auto a = eliminated.archive.trajectory(), b = kept.archive.trajectory();
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k)
    EXPECT_LT(
        (poseIsometry(a[k].pose).translation() - poseIsometry(b[k].pose).translation()).norm(),
        1e-6);
  for (const auto& [label, p] : eliminated.planes)
    EXPECT_NEAR(p.distance[0], kept.planes.at(label).distance[0], 1e-6);
}

// The keyframes the window held over its ground keep calib.ini's camera height over the ground's
// map plane: given 10 cm more than the truth with a 1 mm sigma, the refined cameras stand that
// high over the refined floor; without the marks, at the truth.
TEST(BatchRefinement, KeyframesHeldOverTheGroundKeepTheCameraHeight) {
  for (const bool given : {false, true}) {
    Scenario s;
    build(s, 0.0, -1, 0, true);
    ASSERT_GT(s.camera_height, 0);
    const int floor = s.floor;
    ASSERT_TRUE(s.true_planes.count(floor)) << "the floor has homography factors";
    BatchRefinementOptions options;
    options.weight = 320;
    if (given) {
      options.camera_height = s.camera_height + 0.10;
      options.camera_height_sigma = 0.001;
    }
    BatchRefinement batch(
        s.archive, s.mount, [](int label) { return label; }, s.planes, options);
    ASSERT_TRUE(batch.solve());
    std::printf("%s\n", batch.report().c_str());
    const Eigen::Vector3d n(s.planes.at(floor).normal);
    const double d = s.planes.at(floor).distance[0];
    const Eigen::Isometry3d T_BC = poseIsometry(s.mount);
    double sum = 0;
    const auto refined = s.archive.trajectory();
    for (const auto& k : refined)
      sum += std::abs(n.dot((poseIsometry(k.pose) * T_BC).translation()) - d);
    const double mean = sum / refined.size();
    EXPECT_NEAR(mean, s.camera_height + (given ? 0.10 : 0.0), 0.01) << "given " << given;
  }
}

}  // namespace
}  // namespace rpvio
