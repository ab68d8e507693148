// PlaneDiscovery on exact geometry with tracker-like noise: the 3-point known-rotation plane
// solver against exact data; one check separating a wall and a floor (static) from a panel
// driving towards the camera; relief just off the wall kept off it; over a run, a parked panel
// accepted as a static plane and rejected once it starts moving; ended tracks keep their labels;
// young tracks join their plane before a check's span, static points off it do not; nothing
// labelled while the camera only turns; with static_points, static points off the planes passed on
// without a plane and the moving panel not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <set>

#include "mrpt_modules/estimator/plane_discovery.h"
#include "tests/estimator/wall_floor_panel_scene.h"

namespace rpvio {
namespace {

using namespace test;         // the scene
constexpr double kRate = 20;  // Hz

/// A slower turn than the verifier's (2 s in view) and a panel at 4.25 m, where no floor point
/// is (points on both planes could go either way), with more points.
WallFloorPanel scene() {
  WallFloorPanel s;
  s.yaw_rate = 0.2;
  s.panel_z = 4.25;
  s.panel_step_x = s.panel_step_y = 0.2;
  return s;
}

/// The frame at time t (ids = scene point ids, no plane labels); the panel moves with
/// `panel_velocity` (world, m/s) from `panel_starts` on.
FeatureFrame frameAt(double t, const Eigen::Vector3d& panel_velocity, double panel_starts,
                     double noise_px, std::mt19937& rng) {
  std::normal_distribution<double> noise(0, noise_px / 460);
  FeatureFrame frame;
  frame.t = t;
  for (const ScenePoint& p : scene().points()) {
    Eigen::Vector3d X = p.at_t0;
    if (p.plane == kPanel && t > panel_starts) X += panel_velocity * (t - panel_starts);
    const auto u = scene().project(t, X);
    if (!u) continue;
    TrackedFeature f;
    f.id = p.id;
    f.normalized = *u + Eigen::Vector2d(noise(rng), noise(rng));
    frame.features.push_back(f);
  }
  return frame;
}

int planeOf(int id) {
  for (const ScenePoint& p : scene().points())
    if (p.id == id) return p.plane;
  return 0;
}

TEST(PlaneThroughPairs, ThreeExactPointsGiveThePlanesInverseDepthMap) {
  // Camera j at the origin; k = R_kj X_j + T. Plane n·X_j = d.
  const Eigen::Matrix3d R_kj =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1, -0.4).normalized()).toRotationMatrix();
  const Eigen::Vector3d T(0.4, -0.1, 0.25), n = Eigen::Vector3d(0.1, -0.9, -0.3).normalized();
  const double d = -1.7;
  std::vector<BearingPair> pairs;
  for (const Eigen::Vector2d& u :
       {Eigen::Vector2d(0.1, 0.4), Eigen::Vector2d(-0.3, 0.2), Eigen::Vector2d(0.25, -0.1),
        Eigen::Vector2d(-0.2, -0.3), Eigen::Vector2d(0.05, 0.05)}) {
    const Eigen::Vector3d b = u.homogeneous(), X_j = b * d / n.dot(b);
    pairs.push_back({R_kj * b, (R_kj * X_j + T).hnormalized().homogeneous()});
  }
  const Eigen::Vector3d t = T.normalized();
  const Eigen::Vector3d expected = T.norm() * R_kj * n / d;  // H = R + T nᵀ/d, in k's orientation
  const auto three = planeThroughPairs(pairs, {0, 1, 2}, t);
  ASSERT_TRUE(three.has_value());
  EXPECT_LT((*three - expected).norm(), 1e-9 * expected.norm());
  const auto all = planeThroughPairs(pairs, {0, 1, 2, 3, 4}, t);
  ASSERT_TRUE(all.has_value());
  EXPECT_LT((*all - expected).norm(), 1e-9 * expected.norm());
  // Two pairs leave m undetermined along one direction.
  EXPECT_FALSE(planeThroughPairs(pairs, {0, 1}, t).has_value());
}

TEST(PlaneDiscovery, OneCheckFindsTheWallAndTheFloorAndSetsTheDrivingPanelAside) {
  std::mt19937 rng(5);
  const Eigen::Vector3d towards_camera(0, 0, -1.0);
  const FeatureFrame j = frameAt(0.0, towards_camera, 0, 0.1, rng);
  const FeatureFrame k = frameAt(0.3, towards_camera, 0, 0.1, rng);
  const Eigen::Matrix3d R_kj =
      scene().cameraRotation(0.3).transpose() * scene().cameraRotation(0.0);
  PlaneDiscoveryOptions options;
  const PlaneDiscovery discovery(options);
  const PlaneDiscovery::CheckResult result = discovery.check(j, k, R_kj);
  ASSERT_TRUE(result.judged);
  const Eigen::Vector3d T_kj = scene().cameraRotation(0.3).transpose() *
                               (scene().cameraPosition(0) - scene().cameraPosition(0.3));
  EXPECT_GT(result.t.dot(T_kj.normalized()), std::cos(1.0 * M_PI / 180));  // within 1°, sign too
  // Most panel points are set aside (those whose extra motion runs along their epipolar line
  // cannot be: the limit of any two-view test); no wall or floor point is.
  std::map<int, int> moving_by_plane, seen_by_plane;
  for (const int id : result.moving) ++moving_by_plane[planeOf(id)];
  for (const TrackedFeature& f : k.features) ++seen_by_plane[planeOf(f.id)];
  EXPECT_GE(moving_by_plane[kPanel], 0.75 * seen_by_plane[kPanel]);
  EXPECT_EQ(moving_by_plane[kWall] + moving_by_plane[kFloor], 0);
  // Two planes, each at least 90 % one scene plane and holding at least 90 % of its points.
  ASSERT_EQ(result.planes.size(), 2u);
  std::set<int> found;
  for (const auto& plane : result.planes) {
    std::map<int, int> members;
    for (const int id : plane.features) ++members[planeOf(id)];
    const auto [scene_plane, count] = *std::max_element(
        members.begin(), members.end(), [](auto& a, auto& b) { return a.second < b.second; });
    EXPECT_GE(count, 0.9 * plane.features.size());
    EXPECT_GE(count, 0.9 * seen_by_plane[scene_plane]);
    found.insert(scene_plane);
  }
  EXPECT_EQ(found, (std::set<int>{kWall, kFloor}));
}

TEST(PlaneDiscovery, PointsJustOffAPlaneStayOffItWhenTheTracksArePrecise) {
  // Relief 10 cm in front of the wall (6 m away): its transfer error under the wall's homography
  // is ~0.4 px over the check's 0.3 s, within plane_px but ~6 sigmas of 0.05 px tracks.
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.05 / 460);
  const auto frame = [&](double t) {
    FeatureFrame f = frameAt(t, Eigen::Vector3d::Zero(), 10, 0.05, rng);
    int id = 10000;
    for (double x = -2; x <= 3; x += 0.5)
      for (const double y : {-1.25, 0.75})
        if (const auto u = scene().project(t, {x, y, 5.9})) {
          TrackedFeature relief;
          relief.id = id++;
          relief.normalized = *u + Eigen::Vector2d(noise(rng), noise(rng));
          f.features.push_back(relief);
        }
    return f;
  };
  const FeatureFrame j = frame(0.0), k = frame(0.3);
  const Eigen::Matrix3d R_kj =
      scene().cameraRotation(0.3).transpose() * scene().cameraRotation(0.0);
  int relief_points = 0, wall_points = 0;
  for (const TrackedFeature& f : k.features) {
    relief_points += f.id >= 10000;
    wall_points += planeOf(f.id) == kWall;
  }
  const auto reliefOnTheWall = [&](const PlaneDiscoveryOptions& options) {
    const PlaneDiscovery::CheckResult result = PlaneDiscovery(options).check(j, k, R_kj);
    EXPECT_TRUE(result.judged);
    for (const auto& plane : result.planes) {
      int wall = 0, relief = 0;
      for (const int id : plane.features) {
        relief += id >= 10000;
        wall += planeOf(id) == kWall;
      }
      if (2 * wall <= static_cast<int>(plane.features.size())) continue;
      EXPECT_GE(wall, 0.85 * wall_points);  // the wall itself stays on it
      return relief;
    }
    ADD_FAILURE() << "the wall was not found";
    return -1;
  };
  ASSERT_GE(relief_points, 10);
  PlaneDiscoveryOptions transfer_limit_only;
  transfer_limit_only.plane_sigmas = 0;
  EXPECT_GE(reliefOnTheWall(transfer_limit_only), relief_points / 2);  // plane_px alone: on it
  EXPECT_LE(reliefOnTheWall(PlaneDiscoveryOptions{}), relief_points / 10);
}

/// 2 s at 20 Hz; the panel is parked until `panel_starts` then drives towards the camera.
struct DiscoveryRun {
  PlaneDiscovery discovery{PlaneDiscoveryOptions{}};
  std::vector<FeatureFrame> outputs;
};
DiscoveryRun run(double panel_starts, double duration = 2.0, bool translate = true,
                 const std::set<int>& tracks_ending_at_1s = {},
                 const std::vector<ScenePoint>& tracks_starting_at_1s = {}, bool adopt_young = true,
                 bool static_points = false) {
  DiscoveryRun r;
  PlaneDiscoveryOptions options;
  options.enabled = true;
  options.adopt_young = adopt_young;
  options.static_points = static_points;
  r.discovery = PlaneDiscovery(options);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.1 / 460);
  for (int k = 0; k <= duration * kRate; ++k) {
    const double t = k / kRate;
    FeatureFrame frame =
        frameAt(translate ? t : 0, Eigen::Vector3d(0, 0, -1.0), panel_starts, 0.1, rng);
    frame.t = t;
    if (t >= 1.0 - 1e-9)
      for (const ScenePoint& p : tracks_starting_at_1s)
        if (const auto u = scene().project(t, p.at_t0)) {
          TrackedFeature f;
          f.id = p.id;
          f.normalized = *u + Eigen::Vector2d(noise(rng), noise(rng));
          frame.features.push_back(f);
        }
    if (t >= 1.0)
      frame.features.erase(std::remove_if(frame.features.begin(), frame.features.end(),
                                          [&](const TrackedFeature& f) {
                                            return tracks_ending_at_1s.count(f.id) > 0;
                                          }),
                           frame.features.end());
    if (!translate) {  // the same position, turning only
      for (TrackedFeature& f : frame.features)
        f.normalized = (scene().cameraRotation(t).transpose() * scene().cameraRotation(0) *
                        f.normalized.homogeneous())
                           .hnormalized();
    }
    const Eigen::Quaterniond R_previous_current(
        scene().cameraRotation(std::max(0.0, t - 1 / kRate)).transpose() *
        scene().cameraRotation(t));
    r.outputs.push_back(r.discovery.label(frame, R_previous_current));
  }
  return r;
}

TEST(PlaneDiscovery, AParkedPanelIsAcceptedAndRejectedOnceItDrivesOff) {
  const DiscoveryRun r = run(/*panel_starts=*/1.0);
  std::map<int, int> accepted_as;  // scene plane → segment
  double panel_rejected_at = -1;
  for (const PlaneDiscoveryEvent& e : r.discovery.events()) {
    EXPECT_GE(e.plane_id, kFirstDiscoveredLabel);
    if (!e.accepted) {
      EXPECT_LT(panel_rejected_at, 0) << "one rejection";
      panel_rejected_at = e.t;
      continue;
    }
    // The scene plane of the segment: from the first output holding it.
    for (const FeatureFrame& f : r.outputs)
      for (const TrackedFeature& x : f.features)
        if (x.plane_id == e.plane_id && !accepted_as.count(planeOf(x.id)))
          accepted_as[planeOf(x.id)] = e.plane_id;
  }
  // All three accepted once found in three checks (the first at 0.3 s): by 0.45 s.
  ASSERT_EQ(accepted_as.size(), 3u);
  for (const PlaneDiscoveryEvent& e : r.discovery.events())
    EXPECT_TRUE(!e.accepted || e.t <= 0.45 + 1e-9) << "accepted at " << e.t;
  // Rejected after three checks with it moving: within 0.3 s of driving off.
  ASSERT_GT(panel_rejected_at, 1.0);
  EXPECT_LE(panel_rejected_at, 1.3 + 1e-9);
  for (const FeatureFrame& f : r.outputs) {
    for (const TrackedFeature& x : f.features) {
      // A label stands for one scene plane; after the rejection no panel point is output.
      const auto it = accepted_as.find(planeOf(x.id));
      ASSERT_NE(it, accepted_as.end());
      EXPECT_EQ(x.plane_id, it->second);
      if (f.t >= panel_rejected_at) {
        EXPECT_NE(planeOf(x.id), kPanel);
      }
    }
    if (f.t < 0.4 - 1e-9) {
      EXPECT_TRUE(f.features.empty()) << "output before confirmation";
    }
  }
  // The wall and floor stay: the last frame still holds both.
  std::set<int> last;
  for (const TrackedFeature& x : r.outputs.back().features) last.insert(planeOf(x.id));
  EXPECT_EQ(last, (std::set<int>{kWall, kFloor}));
}

TEST(PlaneDiscovery, EndedTracksKeepTheirLabelsWhileTheirPlaneIsFoundAgain) {
  // A third of the wall's tracks end at 1 s; its segment is found again by every later check.
  std::set<int> ending;
  for (const ScenePoint& p : scene().points())
    if (p.plane == kWall && p.id % 3 == 0) ending.insert(p.id);
  const DiscoveryRun r = run(/*panel_starts=*/10, 2.0, true, ending);
  // Their last frame (0.95 s): the labels they ended with (a check may still drop a label of a
  // track it compares, before the track ends).
  const FeatureFrame& last_tracked = r.outputs[19];
  int ended_labelled_then = 0;
  for (const TrackedFeature& f : last_tracked.features) ended_labelled_then += ending.count(f.id);
  ASSERT_GE(ended_labelled_then, 5);
  // The initializer asks for that frame again 1 s later: the ended tracks keep their labels.
  FeatureFrame unlabelled = last_tracked;
  for (TrackedFeature& f : unlabelled.features) f.plane_id = 0;
  int ended_labelled_now = 0;
  for (const TrackedFeature& f : r.discovery.labelled(unlabelled).features)
    ended_labelled_now += ending.count(f.id);
  EXPECT_EQ(ended_labelled_now, ended_labelled_then);
}

TEST(PlaneDiscovery, YoungTracksJoinTheirPlaneBeforeACheckSpanAndPointsOffItDoNot) {
  // Tracks starting at 1 s: floor points between the floor's, and static clutter 2.6–3.4 m away
  // (depths in a cycle of three: no ten of them on one plane). Adopted over a span with the
  // plane's parallax p, a point whose inverse depth differs by δ from the plane's is p·δ/ρ off
  // its homography: the clutter's differ by at least 25 % from the panel's and the wall's, at
  // least 1 px at p = 4 px (min_parallax_px).
  std::vector<ScenePoint> starting;
  for (double x = -1.75; x <= 2.75; x += 0.5)
    for (const double z : {2.25, 2.75, 3.25, 3.75, 4.75})  // not 4.25: on the panel's plane too
      starting.push_back({20000 + int(starting.size()), kFloor, {x, 1.5, z}});
  const size_t floor_points = starting.size();
  for (double x = -2; x <= 3; x += 0.5)
    for (const double y : {-1.25, 0.75})
      starting.push_back(
          {20000 + int(starting.size()), 0, {x, y, 2.6 + 0.4 * (starting.size() % 3)}});
  const auto isStarting = [&](int id, int plane) {
    return id >= 20000 && starting[id - 20000].plane == plane;
  };
  for (const bool adopt : {true, false}) {
    SCOPED_TRACE(adopt ? "adopt_young" : "without adopt_young");
    const DiscoveryRun r = run(/*panel_starts=*/10, 2.0, true, {}, starting, adopt);
    std::map<int, int> votes;  // the floor's segment: the label most of its old points carry
    for (const TrackedFeature& f : r.outputs[20].features)
      if (f.id < 20000 && planeOf(f.id) == kFloor) ++votes[f.plane_id];
    ASSERT_FALSE(votes.empty());
    const int floor_segment = std::max_element(votes.begin(), votes.end(), [](auto& a, auto& b) {
                                return a.second < b.second;
                              })->first;
    for (const FeatureFrame& f : r.outputs) {
      for (const TrackedFeature& x : f.features)
        EXPECT_FALSE(isStarting(x.id, 0)) << "clutter labelled at " << f.t;
      if (f.t < 1.05 - 1e-9 || f.t > 1.25 + 1e-9) continue;
      // Without adoption no check judges them before 1.3 s; with it they join the floor one
      // frame in.
      int visible = 0, joined = 0;
      for (size_t i = 0; i < floor_points; ++i)
        visible += scene().project(f.t, starting[i].at_t0).has_value();
      for (const TrackedFeature& x : f.features)
        if (isStarting(x.id, kFloor)) {
          EXPECT_EQ(x.plane_id, floor_segment) << "at " << f.t;
          ++joined;
        }
      if (adopt) {
        EXPECT_GE(joined, 0.8 * visible) << "at " << f.t;
      } else {
        EXPECT_EQ(joined, 0) << "at " << f.t;
      }
    }
  }
}

TEST(PlaneDiscovery, StaticPointsOffThePlanesArePassedOnAndMostOfTheDrivingPanelIsNot) {
  // Static clutter 2.6–3.4 m away from 1 s on (no ten of it on one plane), the panel driving off
  // at 1 s: with static_points the clutter comes out with plane id 0 once compared; of the
  // driving panel's points only those moving along their epipolar lines, which no two-view test
  // sees, may (a quarter at most here), none on a plane.
  std::vector<ScenePoint> clutter;
  for (double x = -2; x <= 3; x += 0.5)
    for (const double y : {-1.25, 0.75})
      clutter.push_back({20000 + int(clutter.size()), 0, {x, y, 2.6 + 0.4 * (clutter.size() % 3)}});
  const DiscoveryRun r = run(/*panel_starts=*/1.0, 2.0, true, {}, clutter, true, true);
  for (const FeatureFrame& f : r.outputs) {
    int clutter_out = 0, clutter_visible = 0, panel_out = 0, panel_visible = 0;
    for (const ScenePoint& p : clutter)
      clutter_visible += scene().project(f.t, p.at_t0).has_value();
    for (const ScenePoint& p : scene().points())
      if (p.plane == kPanel)
        panel_visible += scene()
                             .project(f.t, p.at_t0 + Eigen::Vector3d(0, 0, -std::max(0.0, f.t - 1)))
                             .has_value();
    for (const TrackedFeature& x : f.features) {
      if (x.id >= 20000) {
        EXPECT_EQ(x.plane_id, 0) << "clutter on a plane at " << f.t;
        ++clutter_out;
      } else if (planeOf(x.id) == kPanel && f.t > 1.1) {
        EXPECT_EQ(x.plane_id, 0) << "the driving panel on a plane at " << f.t;
        ++panel_out;
      }
    }
    if (f.t > 1.1) {
      EXPECT_LE(4 * panel_out, panel_visible) << "at " << f.t;
    }
    if (f.t >= 1.5) {
      EXPECT_GE(clutter_out, 0.8 * clutter_visible) << "at " << f.t;
    }
  }
  // Without static_points none of the clutter is passed on.
  const DiscoveryRun without = run(1.0, 2.0, true, {}, clutter, true, false);
  for (const FeatureFrame& f : without.outputs)
    for (const TrackedFeature& x : f.features) EXPECT_LT(x.id, 20000);
}

TEST(PlaneDiscovery, NothingIsLabelledWhileTheCameraOnlyTurns) {
  const DiscoveryRun r = run(/*panel_starts=*/10, 1.0, /*translate=*/false);
  EXPECT_TRUE(r.discovery.events().empty());
  for (const FeatureFrame& f : r.outputs) EXPECT_TRUE(f.features.empty());
}

}  // namespace
}  // namespace rpvio
