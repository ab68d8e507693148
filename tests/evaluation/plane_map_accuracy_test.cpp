// Plane map against true planes (issue 8's measure): matching by mask label, the alignment's effect
// on (n, d), duplicates, wrong merges; and rpvio-eval --planes on a simulated scene's true planes.
#include <gtest/gtest.h>

#include "common/input_error.h"
#include "evaluation/plane_map_accuracy.h"
#include "evaluation/plane_visibility.h"
#include "planes_map/plane_map_exporters.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

Plane plane(int id, const Eigen::Vector3d& n, double d, std::set<int> masks,
            size_t observations = 1) {
  Plane p;
  p.id = id;
  p.normal = n.normalized();
  p.distance = d;
  p.mask_ids = std::move(masks);
  p.observations = observations;
  return p;
}

TEST(PlaneMapAccuracy, ExactMapInAnotherFrameHasNoError) {
  const std::vector<Plane> truth = {plane(1, {0, 0, 1}, 0, {1}), plane(2, {-1, 0, 0}, -20, {2}),
                                    plane(10, {0, 1, 1}, 3, {10})};
  // The estimate's world: X_est = R_e X_gt + t_e, so X_gt = R_eᵀ (X_est − t_e).
  const Eigen::Matrix3d R_e =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Eigen::Vector3d t_e(4, -2, 1);
  std::vector<Plane> map;
  for (const Plane& p : truth) {
    const Eigen::Vector3d n = R_e * p.normal;
    map.push_back(plane(p.id + 100, n, p.distance + n.dot(t_e), p.mask_ids));
  }
  eval::Similarity est_to_gt;
  est_to_gt.R = R_e.transpose();
  est_to_gt.t = -R_e.transpose() * t_e;
  const auto a = eval::evaluatePlaneMap(map, truth, est_to_gt);
  ASSERT_EQ(a.planes.size(), 3u);
  EXPECT_EQ(a.duplicates, 0u);
  EXPECT_EQ(a.mixed, 0u);
  EXPECT_EQ(a.unmatched, 0u);
  for (const auto& p : a.planes) {
    EXPECT_EQ(p.map_entries, 1u);
    EXPECT_LT(p.normal_error_deg, 1e-6);
    EXPECT_LT(p.distance_error_m, 1e-9);
  }
}

TEST(PlaneMapAccuracy, DiscoveredPlanesStandForTheNearestTruePlane) {
  const std::vector<Plane> truth = {plane(1, {0, 0, 1}, 0, {1}), plane(2, {1, 0, 0}, 5, {2}),
                                    plane(3, {1, 0, 0}, 8, {3})};
  const double tilt = 2 * M_PI / 180;
  const std::vector<Plane> map = {
      plane(1, {0, std::sin(tilt), std::cos(tilt)}, 0.05, {kFirstDiscoveredLabel}),  // floor
      plane(2, {-1, 0, 0}, -7.9, {kFirstDiscoveredLabel + 1}),  // the farther wall, 10 cm off
      plane(3, {0, 1, 0}, 2, {kFirstDiscoveredLabel + 2}),      // no true plane near it
      plane(4, {1, 0, 0}, 5, {2})};                             // a mask plane, as before
  const auto a = eval::evaluatePlaneMap(map, truth, eval::Similarity{});
  EXPECT_EQ(a.discovered, 3u);
  EXPECT_EQ(a.unmatched, 1u);
  ASSERT_EQ(a.planes.size(), 3u);
  EXPECT_EQ(a.planes[0].true_id, 1);
  EXPECT_NEAR(a.planes[0].normal_error_deg, 2.0, 1e-9);
  EXPECT_NEAR(a.planes[0].distance_error_m, 0.05, 1e-12);
  EXPECT_EQ(a.planes[2].true_id, 3);
  EXPECT_NEAR(a.planes[2].distance_error_m, 0.1, 1e-12);
}

TEST(PlaneMapAccuracy, CountsDuplicatesMergesAndMeasuresTheMostObservedEntry) {
  const std::vector<Plane> truth = {plane(1, {0, 0, 1}, 0, {1}), plane(2, {1, 0, 0}, 5, {2})};
  const double tilt = 3 * M_PI / 180;
  const std::vector<Plane> map = {
      plane(1, {0, std::sin(tilt), std::cos(tilt)}, 0.1, {1}, 40),  // floor: 3°, 10 cm off
      plane(2, {0, 0, 1}, 0.5, {1}, 2),                             // its duplicate
      plane(3, {-1, 0, 0}, -5.02, {2, 1}),  // opposite sign convention; also seen as the floor
      plane(4, {0, 1, 0}, 1, {77})};        // a label that is no true plane
  const auto a = eval::evaluatePlaneMap(map, truth, eval::Similarity{});
  ASSERT_EQ(a.planes.size(), 2u);
  EXPECT_EQ(a.map_planes, 4u);
  EXPECT_EQ(a.planes[0].map_entries, 3u);  // floor: 1, 2 and the mixed 3
  EXPECT_NEAR(a.planes[0].normal_error_deg, 3, 1e-9);
  EXPECT_NEAR(a.planes[0].distance_error_m, 0.1, 1e-12);
  EXPECT_EQ(a.planes[1].map_entries, 1u);
  EXPECT_NEAR(a.planes[1].normal_error_deg, 0, 1e-9);
  EXPECT_NEAR(a.planes[1].distance_error_m, 0.02, 1e-9);
  EXPECT_EQ(a.duplicates, 2u);
  EXPECT_EQ(a.mixed, 1u);
  EXPECT_EQ(a.unmatched, 1u);
}

TEST(PlaneMapAccuracy, ReportsWhatTheCovarianceClaimsInTheGroundTruthsFrame) {
  // A wall x = 5: tilts of 2 deg each way, d to 3 cm. An alignment moving it along its normal
  // leaves the offset's uncertainty as it is; one moving it along the wall adds the tilts' lever
  // arm (10 m x 2 deg).
  const std::vector<Plane> truth = {plane(1, {1, 0, 0}, 15, {1})};
  std::vector<Plane> map = {plane(1, {1, 0, 0}, 5, {1})};
  const double tilt = 2 * M_PI / 180;
  map[0].covariance = Eigen::Vector4d(0, tilt * tilt, tilt * tilt, 0.03 * 0.03).asDiagonal();
  eval::Similarity shift;
  shift.t = Eigen::Vector3d(10, 0, 0);
  const auto a = eval::evaluatePlaneMap(map, truth, shift);
  ASSERT_EQ(a.planes.size(), 1u);
  EXPECT_NEAR(a.planes[0].distance_error_m, 0, 1e-12);
  EXPECT_NEAR(a.planes[0].normal_sigma_deg, 2 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(a.planes[0].distance_sigma_m, 0.03, 1e-12);  // t along n: no lever arm
  shift.t = Eigen::Vector3d(0, 10, 0);                     // along the wall: the y-tilt's lever arm
  const auto b = eval::evaluatePlaneMap(map, {plane(1, {1, 0, 0}, 5, {1})}, shift);
  EXPECT_NEAR(b.planes[0].distance_sigma_m, std::hypot(0.03, 10 * tilt), 1e-12);
}

TEST(PlaneMapAccuracy, EvalAppReadsTheSimulatorsTruePlanes) {
  test::TempDir dir;
  std::string out;
  ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-sim --characters 0 --duration 0.3 --out " +
                                 dir.file("seq"),
                             out),
            0)
      << out;
  const auto truth = readPlanesYaml(dir.file("seq/groundtruth_planes.yaml"));
  ASSERT_GT(truth.size(), 10u);
  EXPECT_EQ(truth.front().id, 1);  // the floor: z = 0, normal up
  EXPECT_NEAR(truth.front().normal.z(), 1, 1e-12);
  EXPECT_NEAR(truth.front().distance, 0, 1e-12);
  // A map that is the truth itself, with a duplicated floor, evaluated against the ground truth
  // trajectory (identity alignment).
  std::vector<Plane> map = truth;
  map.push_back(truth.front());
  map.back().id = 999;
  writePlanesYaml(dir.file("map.yaml"), map);
  const std::string gt = dir.file("seq/groundtruth.tum");
  ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-eval --gt " + gt + " --est " + gt +
                                 " --planes " + dir.file("map.yaml") + " --gt-planes " +
                                 dir.file("seq/groundtruth_planes.yaml") + " --json " +
                                 dir.file("r.json"),
                             out),
            0)
      << out;
  EXPECT_NE(out.find("plane map: " + std::to_string(truth.size() + 1) + " entries for " +
                     std::to_string(truth.size()) + " true planes (duplicates 1, mixed 0"),
            std::string::npos)
      << out;
  const std::string json = test::readFile(dir.file("r.json"));
  EXPECT_EQ(test::jsonNumber(json, "duplicates"), 1) << json;
  EXPECT_EQ(test::jsonNumber(json, "normal_sigma_deg"), 0) << json;  // the truth's: certain
  EXPECT_EQ(test::runCommand(test::binDir() + "/rpvio-eval --gt " + gt + " --est " + gt +
                                 " --planes " + dir.file("map.yaml"),
                             out),
            2)
      << out;
}

TEST(PlaneMapAccuracy, MovingTruePlanesAreReadButNotScored) {
  test::TempDir dir;
  test::writeText(dir.file("scene.ini"), "[scene]\npallet_trucks = 1\nsliding_panels = 1\n");
  std::string out;
  ASSERT_EQ(test::runCommand(test::binDir() + "/rpvio-sim --characters 0 --duration 0.1 --config " +
                                 dir.file("scene.ini") + " --out " + dir.file("seq"),
                             out),
            0)
      << out;
  const auto truth = readPlanesYaml(dir.file("seq/groundtruth_planes.yaml"));
  std::vector<Plane> moving;
  for (const Plane& p : truth)
    if (p.moving) moving.push_back(p);
  ASSERT_EQ(moving.size(), 12u);  // a truck's 10 faces, a panel's 2
  for (const Plane& p : moving) {
    EXPECT_GE(p.id, 200);
    EXPECT_LE(p.id, 239);
    EXPECT_NEAR(p.motion.axis.norm(), 1, 1e-9);
    EXPECT_GT(p.motion.amplitude, 1);
    // Peak speed 2π A / T: the default 1.5 m/s.
    EXPECT_NEAR(2 * M_PI * p.motion.amplitude / p.motion.period, 1.5, 1e-6);
  }
  // The truth as a map, every plane observed: the static ones scored, the moving ones counted
  // apart, and none missing, though all were visible for long.
  const auto a = eval::evaluatePlaneMap(truth, truth, eval::Similarity{});
  EXPECT_EQ(a.planes.size(), truth.size() - moving.size());
  EXPECT_EQ(a.on_moving, moving.size());
  EXPECT_EQ(a.unmatched, 0u);
  for (const auto& p : a.planes) EXPECT_LT(p.true_id, 200);
  std::map<int, eval::LabelVisibility> visible;
  for (const Plane& p : truth) visible[p.id] = {10, 10};
  const std::vector<Plane> statics(truth.begin(), truth.end() - moving.size());
  const auto missing =
      eval::missingPlanes(eval::evaluatePlaneMap(statics, truth, {}), truth, visible);
  EXPECT_TRUE(missing.missing.empty());
  EXPECT_TRUE(missing.untrackable.empty());
}

TEST(PlaneMapAccuracy, PlaneMotionSurvivesTheYamlRoundTrip) {
  test::TempDir dir;
  Plane p = plane(205, {0, 1, 0}, 2, {205});
  p.polygon = {{0, 2, 0}, {1, 2, 0}, {1, 2, 1}};
  p.moving = true;
  p.motion.axis = Eigen::Vector3d(0.6, 0, 0.8);
  p.motion.amplitude = 3.5;
  p.motion.period = 14.25;
  p.motion.phase = -0.75;
  writePlanesYaml(dir.file("p.yaml"), {plane(1, {0, 0, 1}, 0, {1}), p});
  const auto back = readPlanesYaml(dir.file("p.yaml"));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_FALSE(back[0].moving);
  const std::string text = test::readFile(dir.file("p.yaml"));
  EXPECT_EQ(text.find("moving"), text.rfind("moving"));  // the static plane has no such key
  ASSERT_TRUE(back[1].moving);
  for (double t : {0.0, 1.3, 9.0})
    EXPECT_LT((back[1].motion.offset(t) - p.motion.offset(t)).norm(), 1e-9);
  EXPECT_EQ(back[1].polygon.size(), 3u);
  test::writeText(dir.file("bad.yaml"), "planes:\n  - id: 3\n    moving: perhaps\n");
  EXPECT_THROW(readPlanesYaml(dir.file("bad.yaml")), InputError);
}

}  // namespace
}  // namespace rpvio
