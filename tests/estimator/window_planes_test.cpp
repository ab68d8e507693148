// WindowPlanes::choose: the labels whose features get homography factors, among every plane or
// among those a verification found static. WindowPlanes::initialize: a chosen plane's parameters
// from its tracks, the ground's seen twice. WindowPlanes::fittedObservations: the planes without
// parameters in the window, fitted to their points for the map.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>
#include <utility>

#include "mrpt_modules/estimator/window_planes.h"

namespace rpvio {
namespace {

/// One frame with 5 tracks on plane 1, 20 on plane 2 and 10 on plane 3.
FeatureManager threePlanes() {
  FeatureFrame frame;
  int id = 0;
  for (const auto& [plane, tracks] : {std::pair{1, 5}, {2, 20}, {3, 10}})
    for (int i = 0; i < tracks; ++i) {
      TrackedFeature f;
      f.id = id++;
      f.plane_id = plane;
      frame.features.push_back(f);
    }
  FeatureManager features;
  features.addFrame(0, frame);
  return features;
}

TEST(WindowPlanes, OnlyEligiblePlanesAreChosen) {
  const FeatureManager features = threePlanes();
  const std::set<int> eligible{1, 3};  // plane 2 never judged static

  WindowPlanes all(HomographyPlanes::kAll);
  all.choose(features);
  EXPECT_EQ(all.chosen(), (std::set<int>{1, 2, 3}));
  all.choose(features, &eligible);
  EXPECT_EQ(all.chosen(), eligible);

  WindowPlanes largest(HomographyPlanes::kLargest);
  largest.choose(features);
  EXPECT_EQ(largest.chosen(), std::set<int>{2});
  // The current plane is no longer eligible: the largest eligible one takes over.
  largest.choose(features, &eligible);
  EXPECT_EQ(largest.chosen(), std::set<int>{3});

  const std::set<int> none;
  largest.choose(features, &none);
  EXPECT_TRUE(largest.chosen().empty());
}

/// `frames` frames (3 unless set) of a camera at the world's origin looking along z, 30 tracks per
/// plane over a grid of rays, each on its plane n·X = d (depth d / n·ray) or, for a label in
/// `scattered`, at depths 2–5 m that no plane fits.
struct PlanarTracks {
  std::map<int, std::pair<Eigen::Vector3d, double>> planes;
  std::set<int> scattered;
  uint64_t frames = 3;
  FeatureManager features;
  CameraPoseLookup cameras = [](uint64_t) { return Eigen::Isometry3d::Identity(); };

  void build() {
    FeatureFrame frame;
    int id = 0;
    std::map<int, double> depth;
    for (const auto& [label, plane] : planes)
      for (int i = 0; i < 30; ++i) {
        TrackedFeature f;
        f.id = id++;
        f.plane_id = label;
        f.normalized = {-0.3 + 0.1 * (i % 7), -0.25 + 0.1 * (i / 7)};
        const Eigen::Vector3d ray(f.normalized.x(), f.normalized.y(), 1);
        depth[f.id] = scattered.count(label) ? 2.0 + 3.0 * std::fmod(0.37 * i * i, 1.0)
                                             : plane.second / plane.first.dot(ray);
        frame.features.push_back(f);
      }
    for (uint64_t k = 0; k < frames; ++k) features.addFrame(k, frame);
    for (auto& [track_id, track] : features.tracks()) {
      track.inv_depth[0] = 1.0 / depth.at(track_id);
      track.triangulated = true;
    }
  }
};

TEST(WindowPlanes, TheGroundGetsParametersFromTracksSeenTwiceOtherPlanesNeedThree) {
  // The ground's tracks live a few images (GroundTracks): seen twice, a plane of them is fitted;
  // a wall's tracks seen twice are too young.
  PlanarTracks scene;
  scene.planes[kGroundLabel] = {Eigen::Vector3d(0, 0.8, 0.6), 1.6};  // the road ahead
  scene.planes[2] = {Eigen::Vector3d(0, 0, 1), 8.0};                 // a facade ahead
  scene.frames = 2;
  scene.build();
  WindowPlanes planes(HomographyPlanes::kAll);
  planes.choose(scene.features);
  ASSERT_EQ(planes.chosen(), (std::set<int>{2, kGroundLabel}));
  planes.initialize(scene.features, scene.cameras, Eigen::Vector3d::Zero(), PlanesMap{});
  ASSERT_EQ(planes.estimates().size(), 1u);
  const PlaneEstimate& ground = planes.estimates().begin()->second;
  EXPECT_EQ(planes.estimates().begin()->first, kGroundLabel);
  EXPECT_LT((Eigen::Vector3d(ground.normal) - Eigen::Vector3d(0, 0.8, 0.6)).norm(), 1e-9);
  EXPECT_NEAR(ground.distance[0], 1.6, 1e-9);
  // A third frame: the facade too.
  PlanarTracks older;
  older.planes = scene.planes;
  older.build();
  planes.initialize(older.features, older.cameras, Eigen::Vector3d::Zero(), PlanesMap{});
  EXPECT_EQ(planes.estimates().size(), 2u);
}

TEST(WindowPlanes, PlanesWithoutParametersAreFittedForTheMapOneVisitPerStay) {
  PlanarTracks scene;
  scene.planes[1] = {Eigen::Vector3d(0, 0, 1), 5.0};                   // a wall ahead
  scene.planes[2] = {Eigen::Vector3d(0, 0.8, 0.6), 3.0};               // a tilted floor
  scene.planes[3] = {Eigen::Vector3d(0.6, 0, 0.8).normalized(), 4.0};  // not planar:
  scene.scattered = {3};
  scene.build();
  WindowPlanes planes(HomographyPlanes::kLargest);
  // Plane 1 has parameters in the window: only the others are fitted, and plane 3 is no plane.
  planes.start({{1, WorldPlane{Eigen::Vector3d(0, 0, 1), 5.0}}});
  const Eigen::Vector3d camera = Eigen::Vector3d::Zero();
  const auto first = planes.fittedObservations(scene.features, scene.cameras, 1.0, camera, nullptr);
  ASSERT_EQ(first.size(), 1u);
  const PlaneObservation& floor = first[0];
  EXPECT_EQ(floor.mask_id, 2);
  EXPECT_LT((floor.normal - Eigen::Vector3d(0, 0.8, 0.6)).norm(), 1e-9);
  EXPECT_NEAR(floor.distance, 3.0, 1e-9);
  EXPECT_EQ(floor.points.size(), 30u);
  EXPECT_EQ(floor.time, 1.0);
  EXPECT_NEAR(floor.covariance(0, 0), 0.05 * 0.05 / 30, 1e-12);
  EXPECT_NE(floor.visit, 0u);
  // Still in the window: the same visit. Not eligible: nothing.
  const auto again = planes.fittedObservations(scene.features, scene.cameras, 1.5, camera, nullptr);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].visit, floor.visit);
  const std::set<int> judged_static{1};
  EXPECT_TRUE(planes.fittedObservations(scene.features, scene.cameras, 2.0, camera, &judged_static)
                  .empty());
  // Seen again after a stay away: a new visit.
  const auto back = planes.fittedObservations(scene.features, scene.cameras, 3.0, camera, nullptr);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_NE(back[0].visit, floor.visit);
  // Once it has parameters in the window, the window's own observations carry it.
  planes.start({{1, WorldPlane{Eigen::Vector3d(0, 0, 1), 5.0}},
                {2, WorldPlane{Eigen::Vector3d(0, 0.8, 0.6), 3.0}}});
  EXPECT_TRUE(
      planes.fittedObservations(scene.features, scene.cameras, 4.0, camera, nullptr).empty());
  EXPECT_EQ(planes.observations(scene.features, scene.cameras, 4.0).size(), 2u);
}

}  // namespace
}  // namespace rpvio
