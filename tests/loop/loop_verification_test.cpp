// The geometric check of a revisit and the loop detector, on the simulator's warehouse flight
// (a circle: every place is seen again one lap later).
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "mrpt_modules/loop/loop_detector.h"
#include "mrpt_modules/loop/loop_verification.h"
#include "sim/simulator.h"

namespace rpvio {
namespace {

sim::SimConfig staticWarehouse() {
  sim::SimConfig c;
  c.scene.characters = 0;
  return c;
}

double yawOf(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

/// The time after `t` + 20 s when the body is nearest to where it was at `t`, heading alike.
double revisitOf(const sim::Simulator& sim, double t) {
  const Eigen::Isometry3d then = sim.bodyPose(t);
  double best = 0, best_cost = 1e9;
  for (double s = t + 20; s < t + 60; s += 0.05) {
    const Eigen::Isometry3d now = sim.bodyPose(s);
    const double yaw = std::remainder(yawOf(now) - yawOf(then), 2 * M_PI);
    const double cost = (now.translation() - then.translation()).norm() + 5 * std::abs(yaw);
    if (cost < best_cost) best = s, best_cost = cost;
  }
  return best;
}

/// The keyframe at `t`: its image described at 150 tracked corners (as the front-end picks them)
/// whose world points (in the true world moved by `drift`) and planes (the scene's) are known.
KeyframeAppearance keyframeAt(sim::Simulator& sim, double t, const Eigen::Isometry3d& drift) {
  const CameraIntrinsics camera = sim.calibration().camera;
  const cv::Mat image = sim.render(t, 0).image;
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(image, corners, 150, 0.01, 30);
  std::vector<AppearancePoint> tracked;
  for (const cv::Point2f& c : corners) {
    const sim::SceneHit hit = sim.castPixel(t, c.x, c.y);
    if (hit.label == sim::kMaskNothing) continue;
    tracked.push_back(
        {Eigen::Vector2d((c.x - camera.cx) / camera.fx, (c.y - camera.cy) / camera.fy),
         drift * hit.point, hit.label});
  }
  return describeKeyframe(image, tracked, camera, 500);
}

Eigen::Isometry3d fourDofDrift() {
  Eigen::Isometry3d drift = Eigen::Isometry3d::Identity();
  drift.linear() = Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  drift.translation() = Eigen::Vector3d(1.0, -0.5, 0.2);
  return drift;
}

TEST(LoopVerification, ARevisitPlacesTheOldCameraInTheDriftedWorld) {
  sim::Simulator sim(staticWarehouse());
  const double t_old = 5.0;
  const double t_query = revisitOf(sim, t_old);
  ASSERT_LT((sim.bodyPose(t_query).translation() - sim.bodyPose(t_old).translation()).norm(), 1.0);
  const Eigen::Isometry3d drift = fourDofDrift();
  const KeyframeAppearance old = keyframeAt(sim, t_old, Eigen::Isometry3d::Identity());
  const KeyframeAppearance query = keyframeAt(sim, t_query, drift);
  const Eigen::Isometry3d T_BC = sim.calibration().T_BC;
  const LoopCheck check = verifyLoop(query, old, sim.bodyPose(t_old), T_BC, {});
  ASSERT_TRUE(check.accepted) << check.why;
  EXPECT_GE(check.inliers, 25);
  const Eigen::Isometry3d expected = drift * sim.bodyPose(t_old);
  EXPECT_LT((check.old_body.translation() - expected.translation()).norm(), 0.05);
  EXPECT_LT(Eigen::AngleAxisd(check.old_body.linear().transpose() * expected.linear()).angle(),
            0.5 * M_PI / 180);
}

TEST(LoopVerification, MatchesOnDifferentPersistentPlanesAreRejected) {
  // The true revisit above: its inliers on planes are on the same planes in both keyframes. The
  // same images with the old keyframe's planes known under other ids (as after a false match of
  // a repeated texture onto another surface): rejected by the plane check alone.
  sim::Simulator sim(staticWarehouse());
  const double t_old = 5.0;
  const double t_query = revisitOf(sim, t_old);
  KeyframeAppearance old = keyframeAt(sim, t_old, Eigen::Isometry3d::Identity());
  const KeyframeAppearance query = keyframeAt(sim, t_query, fourDofDrift());
  const Eigen::Isometry3d T_BC = sim.calibration().T_BC;
  const LoopCheck check = verifyLoop(query, old, sim.bodyPose(t_old), T_BC, {});
  ASSERT_TRUE(check.accepted) << check.why;
  EXPECT_GE(check.plane_pairs, 10);
  EXPECT_EQ(check.same_plane_pairs, check.plane_pairs);
  for (AppearancePoint& p : old.points)
    if (p.plane != 0) p.plane += 1000;
  const LoopCheck moved = verifyLoop(query, old, sim.bodyPose(t_old), T_BC, {});
  EXPECT_FALSE(moved.accepted);
  EXPECT_NE(moved.why.find("on another plane"), std::string::npos) << moved.why;
  LoopCheckOptions without;
  without.loop_plane_pairs = 0;
  EXPECT_TRUE(verifyLoop(query, old, sim.bodyPose(t_old), T_BC, without).accepted);
}

TEST(LoopVerification, ATiltThatDisagreesWithTheOdometryIsRejected) {
  sim::Simulator sim(staticWarehouse());
  const double t_old = 5.0;
  const double t_query = revisitOf(sim, t_old);
  const KeyframeAppearance old = keyframeAt(sim, t_old, Eigen::Isometry3d::Identity());
  const KeyframeAppearance query = keyframeAt(sim, t_query, Eigen::Isometry3d::Identity());
  Eigen::Isometry3d rolled = sim.bodyPose(t_old);
  rolled.linear() = rolled.linear() * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()).matrix();
  const LoopCheck check = verifyLoop(query, old, rolled, sim.calibration().T_BC, {});
  EXPECT_FALSE(check.accepted);
  EXPECT_NE(check.why.find("tilt"), std::string::npos) << check.why;
}

TEST(LoopVerification, TwoDifferentPlacesAreRejected) {
  sim::Simulator sim(staticWarehouse());
  // Half a lap apart: the other side of the warehouse.
  const double t_old = 5.0;
  const double t_query = t_old + (revisitOf(sim, t_old) - t_old) / 2;
  const KeyframeAppearance old = keyframeAt(sim, t_old, Eigen::Isometry3d::Identity());
  const KeyframeAppearance query = keyframeAt(sim, t_query, Eigen::Isometry3d::Identity());
  const LoopCheck check = verifyLoop(query, old, sim.bodyPose(t_old), sim.calibration().T_BC, {});
  EXPECT_FALSE(check.accepted) << check.inliers << " inliers";
}

TEST(LoopDetector, FindsTheRevisitsOfALapAndNoFalseOne) {
  // Keyframes every 0.5 s over 1.3 laps; positions drift by 1 % of the distance flown (a yaw
  // drift would move them too).
  sim::Simulator sim(staticWarehouse());
  const double lap = revisitOf(sim, 5.0) - 5.0;
  LoopDetectorOptions options;
  options.loop_vocabulary_keyframes = 20;
  LoopDetector detector(options, sim.calibration().T_BC);
  std::vector<LoopEvent> events;
  for (double t = 0; t < 1.3 * lap; t += 0.5) {
    Eigen::Isometry3d drift = Eigen::Isometry3d::Identity();
    drift.translation() = Eigen::Vector3d(0.01 * 2.5 * t, 0, 0);
    Eigen::Isometry3d body = drift * sim.bodyPose(t);
    if (auto e = detector.add(t, body, keyframeAt(sim, t, drift))) events.push_back(*e);
  }
  int accepted = 0;
  for (const LoopEvent& e : events) {
    if (!e.check.accepted) continue;
    ++accepted;
    const double apart =
        (sim.bodyPose(e.t).translation() - sim.bodyPose(e.t_old).translation()).norm();
    EXPECT_LT(apart, 3.0) << "false loop " << e.t << " -> " << e.t_old;
    EXPECT_GE(e.t - e.t_old, options.loop_min_age_s);
  }
  // The last 0.3 lap revisits the first: most of its keyframes should be recognized.
  EXPECT_GE(accepted, static_cast<int>(0.3 * lap / 0.5 / 2)) << events.size() << " found";
}

/// The revisits accepted and the reasons of those rejected over 1.3 laps (keyframes every 0.5 s)
/// whose odometry drifts along x by `drift_per_m` of the distance flown.
std::vector<LoopEvent> lapWithDrift(double drift_per_m, const LoopDetectorOptions& options) {
  sim::Simulator sim(staticWarehouse());
  const double lap = revisitOf(sim, 5.0) - 5.0;
  LoopDetector detector(options, sim.calibration().T_BC);
  std::vector<LoopEvent> events;
  double flown = 0;
  for (double t = 0; t < 1.3 * lap; t += 0.5) {
    if (t > 0)
      flown += (sim.bodyPose(t).translation() - sim.bodyPose(t - 0.5).translation()).norm();
    Eigen::Isometry3d drift = Eigen::Isometry3d::Identity();
    drift.translation() = Eigen::Vector3d(drift_per_m * flown, 0, 0);
    if (auto e = detector.add(t, drift * sim.bodyPose(t), keyframeAt(sim, t, drift)))
      events.push_back(*e);
  }
  return events;
}

TEST(LoopDetector, ARevisitFartherThanTheOdometryCanDriftOrTooFarAwayIsRejected) {
  LoopDetectorOptions options;
  options.loop_vocabulary_keyframes = 20;
  // Odometry off by 30 % of the distance flown: a revisit a lap later would move the old keyframe
  // by metres more than loop_max_drift_ratio allows.
  int rejected_for_drift = 0;
  for (const LoopEvent& e : lapWithDrift(0.3, options)) {
    EXPECT_FALSE(e.check.accepted) << e.t << " -> " << e.t_old;
    rejected_for_drift += e.check.why.rfind("drift ", 0) == 0;
  }
  EXPECT_GE(rejected_for_drift, 5);
  // The same with a bound the drift fits in: accepted.
  options.loop_max_drift_ratio = 0.5;
  int accepted = 0;
  for (const LoopEvent& e : lapWithDrift(0.3, options)) accepted += e.check.accepted;
  EXPECT_GE(accepted, 5);
  // Revisits farther apart than loop_max_baseline_m are not used.
  options.loop_max_baseline_m = 0.05;
  int rejected_for_baseline = 0;
  for (const LoopEvent& e : lapWithDrift(0.3, options)) {
    EXPECT_FALSE(e.check.accepted);
    rejected_for_baseline += e.check.why.rfind("baseline ", 0) == 0;
  }
  EXPECT_GE(rejected_for_baseline, 5);
}

TEST(LoopDetector, AMapsKeyframesAreCandidatesFromTheRunsFirstKeyframe) {
  // A map of the first lap (a keyframe a second, at the true poses); a run over the second lap in
  // another world (turned and moved, as a run that started elsewhere has it) and stamped on the
  // map's clock as if it had flown first (a map keyframe is a candidate whatever its age). The
  // run's first keyframe is already recognized in the map, and every revisit is true.
  sim::Simulator sim(staticWarehouse());
  const double lap = revisitOf(sim, 5.0) - 5.0;
  const LoopDetectorOptions options;
  std::vector<StoredKeyframe> map;
  for (double t = 0; t < lap; t += 1.0)
    map.push_back({t, sim.bodyPose(t), keyframeAt(sim, t, Eigen::Isometry3d::Identity())});
  LoopDetector detector(options, sim.calibration().T_BC);
  detector.addMapKeyframes(map);
  ASSERT_GT(detector.vocabularyWords(), 0);
  std::vector<LoopEvent> events;
  for (double t = lap + 2; t < lap + 8; t += 0.5) {
    const Eigen::Isometry3d world_to_run = fourDofDrift();
    const auto e =
        detector.add(t - lap, world_to_run * sim.bodyPose(t), keyframeAt(sim, t, world_to_run));
    if (t == lap + 2) {
      ASSERT_TRUE(e && e->check.accepted) << "the run's first keyframe";
    }
    if (e) events.push_back(*e);
  }
  int accepted = 0;
  for (const LoopEvent& e : events) {
    if (!e.check.accepted) continue;
    ++accepted;
    EXPECT_TRUE(e.old_from_map);
    EXPECT_LT(e.old_index, map.size());
    EXPECT_LT((sim.bodyPose(e.t + lap).translation() - sim.bodyPose(e.t_old).translation()).norm(),
              3.0)
        << "false loop " << e.t << " -> " << e.t_old;
  }
  EXPECT_GE(accepted, 8) << events.size() << " found";
  // A new world forgets the run's keyframes, not the map's.
  detector.clearSession();
  EXPECT_EQ(detector.keyframes(), map.size());
}

}  // namespace
}  // namespace rpvio
