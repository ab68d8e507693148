// The planes map on the simulator's warehouse, whose planes are known exactly: noisy observations
// over two laps, association, merging and the exporters.
#include <gtest/gtest.h>

#include <mrpt/opengl/COpenGLScene.h>
#include <octomap/OcTree.h>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "common/input_error.h"
#include "planes_map/plane_map_exporters.h"
#include "planes_map/planes_map.h"
#include "sim/warehouse_scene.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

const sim::WarehouseScene& scene() {
  static const sim::WarehouseScene s = [] {
    sim::SceneParams p;
    p.texel_size = 0.2;  // textures are not used here
    return sim::WarehouseScene(p);
  }();
  return s;
}

/// A noisy observation of part of a true plane, as an estimator would report it.
PlaneObservation observe(const sim::ScenePlane& truth, int mask_id, double t,
                         std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  PlaneObservation o;
  o.mask_id = mask_id;
  o.time = t;
  const Eigen::Vector3d tilt = 0.5 * M_PI / 180 * Eigen::Vector3d(g(rng), g(rng), g(rng));
  o.normal = (truth.normal + tilt - truth.normal * truth.normal.dot(tilt)).normalized();
  o.distance = truth.distance() + 0.02 * g(rng);
  o.covariance = Eigen::Matrix4d::Identity() * 1e-4;
  // A random patch covering a third of the rectangle in each direction.
  const double u0 = u(rng) * 0.66, v0 = u(rng) * 0.66;
  for (int k = 0; k < 60; ++k) {
    const double a = (u0 + 0.33 * u(rng)) * truth.width, b = (v0 + 0.33 * u(rng)) * truth.height;
    o.points.push_back(truth.origin + a * truth.u_axis + b * truth.v_axis +
                       0.01 * truth.normal * g(rng));
  }
  return o;
}

PlanesMap twoLaps(size_t* observed) {
  PlanesMap map;
  std::mt19937_64 rng(11);
  *observed = 0;
  for (int lap = 0; lap < 2; ++lap)
    for (const auto& truth : scene().planes()) {
      // Mask ids are not stable between laps (like a CNN's instance ids): lap 2 uses others.
      for (int seen = 0; seen < 3; ++seen)
        map.update(observe(truth, truth.id + 100 * lap, 40.0 * lap + seen, rng));
      *observed += lap == 0;
    }
  map.mergeDuplicates();
  return map;
}

TEST(PlanesMap, TwoLapsGiveEveryPlaneOnceAndAccurately) {
  size_t distinct = 0;
  const PlanesMap map = twoLaps(&distinct);
  EXPECT_EQ(map.planes().size(), distinct);
  double worst_angle = 0, worst_distance = 0;
  for (const auto& truth : scene().planes()) {
    // The map plane that holds this truth's lap-1 mask id must also hold its lap-2 id.
    const Plane* p = map.planeOfMask(truth.id);
    ASSERT_NE(p, nullptr);
    EXPECT_TRUE(p->mask_ids.count(truth.id + 100)) << "plane " << truth.id << " duplicated";
    worst_angle =
        std::max(worst_angle, std::acos(std::min(1.0, p->normal.dot(truth.normal))) * 180 / M_PI);
    worst_distance = std::max(worst_distance, std::abs(p->distance - truth.distance()));
  }
  std::printf("%zu planes; worst normal error %.2f deg, worst distance error %.3f m\n",
              map.planes().size(), worst_angle, worst_distance);
  EXPECT_LT(worst_angle, 2.0);
  EXPECT_LT(worst_distance, 0.05);
}

TEST(PlanesMap, TheSavedMapOfAnotherRunMergesPlaneByPlane) {
  // Two runs' maps of the warehouse (their own labels, the same numbers for other planes: a label
  // says nothing across runs); the second's planes added to the first's: every plane once, its
  // counts summed and both runs' labels kept.
  std::mt19937_64 rng(5);
  PlanesMap first, second;
  const auto& planes = scene().planes();
  for (size_t k = 0; k < planes.size(); ++k)
    for (int seen = 0; seen < 3; ++seen) {
      first.update(observe(planes[k], 1000 + static_cast<int>(k), seen, rng));
      second.update(
          observe(planes[k], 1000 + static_cast<int>((k + 1) % planes.size()), seen, rng));
    }
  const size_t before = first.planes().size();
  ASSERT_EQ(second.planes().size(), before);
  for (const Plane& p : second.planes()) first.addPlane(p);
  EXPECT_EQ(first.planes().size(), before);
  for (const Plane& p : first.planes()) {
    EXPECT_EQ(p.observations, 6u) << p.id;
    EXPECT_EQ(p.mask_ids.size(), 2u) << p.id;
  }
  // A plane of nowhere in this map is kept as a new entry, with what it was.
  const Plane far = second.planes().front().transformed(
      Eigen::Isometry3d(Eigen::Translation3d(second.planes().front().normal * 5)));
  const int id = first.addPlane(far);
  ASSERT_NE(first.plane(id), nullptr);
  EXPECT_EQ(first.planes().size(), before + 1);
  EXPECT_EQ(first.plane(id)->observations, 3u);
}

TEST(PlanesMap, SameLabelSeenAgainWithDriftKeepsItsEntry) {
  PlanesMap map;
  PlaneObservation first;
  first.mask_id = 3;
  first.normal = -Eigen::Vector3d::UnitX();
  first.distance = 20.0;
  for (int k = 0; k < 10; ++k) first.points.emplace_back(-20.0, k * 0.3, 1.0);
  const int id = map.update(first);
  // A lap later the window's estimate of the far wall has drifted by 0.6 m and 10 deg: under its
  // label it is the same entry; under an unknown label the geometric thresholds (8 deg, 0.25 m)
  // apply and it is a new one.
  PlaneObservation again = first;
  again.normal = Eigen::Vector3d(-std::cos(0.1745), std::sin(0.1745), 0);
  again.distance = 20.6;
  again.mask_id = 4;
  EXPECT_NE(map.update(again), id);
  again.mask_id = 3;
  EXPECT_EQ(map.update(again), id);
  // Beyond the label's thresholds (points 1.5 m off, more than 1 m) the label does not hold
  // either.
  PlaneObservation moved = first;
  moved.distance = 21.5;
  for (auto& p : moved.points) p.x() = -21.5;
  EXPECT_NE(map.update(moved), id);
}

TEST(PlanesMap, OneBadWindowEstimateStaysTentative) {
  PlanesMap map;  // min_observations 3
  PlaneObservation wall;
  wall.mask_id = 5;
  wall.normal = Eigen::Vector3d::UnitY();
  wall.distance = 20.0;
  for (int k = 0; k < 10; ++k) wall.points.emplace_back(k * 0.3, 20.0, 1.0);
  for (int k = 0; k < 3; ++k) map.update(wall);
  // One window's estimate of the same wall, 5.5 m and 12 deg off, its points with it (few points,
  // far away): beyond the label's thresholds, so an entry of its own, but not confirmed.
  PlaneObservation bad = wall;
  bad.normal = Eigen::Vector3d(std::sin(0.21), std::cos(0.21), 0);
  bad.distance = 25.5;
  for (auto& p : bad.points) p.y() = 25.5;
  const int bad_id = map.update(bad);
  ASSERT_EQ(map.planes().size(), 2u);
  ASSERT_EQ(map.confirmedPlanes().size(), 1u);
  EXPECT_NE(map.confirmedPlanes()[0].id, bad_id);
  // The label now stands for the tentative entry: the estimator gets no plane to start from.
  EXPECT_EQ(map.planeOfMask(5), nullptr);
  // A surface seen in three optimizations is confirmed.
  map.update(bad);
  EXPECT_EQ(map.confirmedPlanes().size(), 1u);
  map.update(bad);
  EXPECT_EQ(map.confirmedPlanes().size(), 2u);
  ASSERT_NE(map.planeOfMask(5), nullptr);
  EXPECT_EQ(map.planeOfMask(5)->id, bad_id);
}

TEST(PlanesMap, MinObservationsBelowOneIsABadConfig) {
  test::TempDir dir;
  test::writeText(dir.file("map.ini"), "[PlanesMap]\nvoxel_size_m = 0.1\nmin_observations = 0\n");
  try {
    PlanesMapOptions::load(IniFile(dir.file("map.ini")), "PlanesMap");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("map.ini") + ":line 3"), std::string::npos)
        << e.what();
  }
}

TEST(PlanesMap, EstimatesOfOneVisitReplaceEachOtherAndVisitsAreFused) {
  PlanesMap map;
  PlaneObservation o;
  o.mask_id = 2;
  o.normal = Eigen::Vector3d::UnitX();
  o.covariance = Eigen::Matrix4d::Identity() * 1e-4;
  for (int k = 0; k < 10; ++k) o.points.emplace_back(20.0, k * 0.3, 1.0);
  // Visit 1: the window's estimate improves (20.3 -> 20.1 -> 20.0); the map follows its newest.
  o.visit = 1;
  for (double d : {20.3, 20.1, 20.0}) {
    o.distance = d;
    map.update(o);
  }
  ASSERT_EQ(map.planes().size(), 1u);
  EXPECT_DOUBLE_EQ(map.planes()[0].distance, 20.0);
  EXPECT_EQ(map.planes()[0].observations, 3u);
  // Visit 2 (equal covariance) says 20.2 then 20.1: fused with visit 1's 20.0 each time.
  o.visit = 2;
  o.distance = 20.2;
  map.update(o);
  EXPECT_NEAR(map.planes()[0].distance, 20.1, 1e-9);
  o.distance = 20.1;
  map.update(o);
  EXPECT_NEAR(map.planes()[0].distance, 20.05, 1e-9);
  EXPECT_NEAR(map.planes()[0].covariance(3, 3), 0.5e-4, 1e-12);
  // Without a visit, every observation is fused as independent (the information adds up).
  o.visit = 0;
  map.update(o);
  EXPECT_NEAR(map.planes()[0].covariance(3, 3), 1e-4 / 3, 1e-12);
}

/// A wall x = d tilted by `tilt_deg` about the y axis, with a covariance as the estimator reports
/// it: tilts of standard deviation sigma_tilt_deg, offset sigma_d, nothing along n itself.
PlaneObservation tiltedWall(double tilt_deg, double d, double sigma_tilt_deg, double sigma_d,
                            uint64_t visit) {
  PlaneObservation o;
  o.mask_id = 7;
  o.visit = visit;
  o.normal =
      Eigen::AngleAxisd(tilt_deg * M_PI / 180, Eigen::Vector3d::UnitY()) * Eigen::Vector3d::UnitX();
  o.distance = d;
  Eigen::Matrix<double, 4, 3> E = Eigen::Matrix<double, 4, 3>::Zero();
  E.block<3, 1>(0, 0) = o.normal.cross(Eigen::Vector3d::UnitY()).normalized();
  E.block<3, 1>(0, 1) = Eigen::Vector3d::UnitY();
  E(3, 2) = 1;
  const double s = sigma_tilt_deg * M_PI / 180;
  o.covariance = E * Eigen::Vector3d(s * s, s * s, sigma_d * sigma_d).asDiagonal() * E.transpose();
  for (int k = 0; k < 10; ++k) o.points.push_back(o.normal * d + Eigen::Vector3d(0, k * 0.3, 0));
  return o;
}

TEST(PlanesMap, VisitsAreFusedOnTheSphereByTheirInformation) {
  // A far wall's short visit (tilt +4 deg, uncertain to 10 deg) and a long one (-1 deg, to 1 deg);
  // equal offset uncertainty. The covariances have no information along n (the unit constraint).
  PlanesMap map;
  map.update(tiltedWall(4.0, 20.00, 10.0, 0.05, 1));
  map.update(tiltedWall(-1.0, 20.04, 1.0, 0.05, 2));
  ASSERT_EQ(map.planes().size(), 1u);
  const Plane& p = map.planes()[0];
  // Information-weighted tilt: (4/10² − 1/1²) / (1/10² + 1/1²) = −0.95 deg.
  const double tilt_deg = std::atan2(-p.normal.z(), p.normal.x()) * 180 / M_PI;
  EXPECT_NEAR(tilt_deg, -0.95, 0.01);
  EXPECT_NEAR(p.normal.y(), 0, 1e-9);
  EXPECT_NEAR(p.normal.norm(), 1, 1e-12);
  // The offsets are averaged, not rescaled by the fused normal's length (20 m x 1% would be 20 cm).
  EXPECT_NEAR(p.distance, 20.02, 1e-4);
  EXPECT_NEAR(p.covariance(3, 3), 0.05 * 0.05 / 2, 1e-8);
  EXPECT_NEAR((p.covariance * (Eigen::Vector4d() << p.normal, 0).finished()).norm(), 0, 1e-12);
}

TEST(PlanesMap, ASignFlippedEstimateIsTheSamePlane) {
  // (n, d) and (−n, −d) are one plane n·X = d; the homography residual cannot tell them apart, and
  // a window's estimate came back flipped after a bad stretch (seed 2, C1: a crate face, then a
  // second map entry).
  PlanesMap map;
  PlaneObservation o = tiltedWall(0.0, 17.0, 1.0, 0.05, 1);
  const int id = map.update(o);
  // The same visit, flipped: the visit's newest estimate, in the entry's orientation.
  PlaneObservation flipped = tiltedWall(0.5, 17.02, 1.0, 0.05, 1);
  flipped.normal = -flipped.normal;
  flipped.distance = -flipped.distance;
  EXPECT_EQ(map.update(flipped), id);
  ASSERT_EQ(map.planes().size(), 1u);
  EXPECT_NEAR(map.planes()[0].distance, 17.02, 1e-12);
  EXPECT_GT(map.planes()[0].normal.x(), 0.99);
  // Another visit under another label, flipped: associated by geometry and fused, not cancelled.
  flipped.visit = 2;
  flipped.mask_id = 8;
  flipped.distance = -17.04;
  EXPECT_EQ(map.update(flipped), id);
  ASSERT_EQ(map.planes().size(), 1u);
  EXPECT_NEAR(map.planes()[0].distance, 17.03, 1e-3);
  EXPECT_NEAR(map.planes()[0].normal.norm(), 1, 1e-12);
  EXPECT_GT(map.planes()[0].normal.x(), 0.99);
}

/// A crate top at z = 1 m seen under mask 1: 10 points along x over 0.9 m.
PlaneObservation crateTop() {
  PlaneObservation o;
  o.mask_id = 1;
  o.normal = Eigen::Vector3d::UnitZ();
  o.distance = 1.0;
  for (int k = 0; k < 10; ++k) o.points.emplace_back(k * 0.1, 0, 1.0);
  return o;
}

TEST(PlanesMap, FlippedTwinsMerge) {
  // Two entries of one crate top, one of them flipped, kept apart until a bridging observation.
  PlanesMap map;
  const PlaneObservation a = crateTop();
  PlaneObservation far = a;
  far.mask_id = 2;
  far.normal = -far.normal;
  far.distance = -1.02;
  for (auto& p : far.points) p.x() += 3;
  map.update(a);
  map.update(far);
  ASSERT_EQ(map.planes().size(), 2u);
  PlaneObservation bridge = a;
  bridge.mask_id = 3;
  for (int k = 0; k < 40; ++k) bridge.points.emplace_back(k * 0.1, 0, 1.0);
  map.update(bridge);
  EXPECT_EQ(map.mergeDuplicates(), 1u);
  ASSERT_EQ(map.planes().size(), 1u);
  EXPECT_NEAR(map.planes()[0].normal.z(), 1, 1e-9);
  EXPECT_GT(map.planes()[0].distance, 1.0);
  EXPECT_LT(map.planes()[0].distance, 1.02);
}

TEST(PlanesMap, AFarTiltedEstimateIsComparedWhereItsPointsAre) {
  // A crate face 19 m from the origin (seed 3): one window's estimate 15 deg off, through the same
  // points. Its d differs by 3.4 m at the origin, but its points lie on the entry.
  PlanesMap map;
  const Eigen::Vector3d n(0.565, -0.825, 0), along(0.825, 0.565, 0);
  const Eigen::Vector3d centre(18.87, -2.96, 1.0);
  PlaneObservation o;
  o.mask_id = 25;
  o.normal = n.normalized();
  o.distance = o.normal.dot(centre);
  for (int k = 0; k < 20; ++k)
    o.points.push_back(centre + (k % 5 - 2) * 0.25 * along +
                       (k / 5 - 2) * 0.4 * Eigen::Vector3d::UnitZ());
  PlanesMap other_label_map;
  const int id = map.update(o);
  PlaneObservation tilted = o;
  tilted.normal = Eigen::AngleAxisd(15 * M_PI / 180, Eigen::Vector3d::UnitZ()) * o.normal;
  tilted.distance = tilted.normal.dot(centre);
  ASSERT_GT(std::abs(tilted.distance - o.distance), 3.0);
  EXPECT_EQ(map.update(tilted), id);  // under its label (20 deg)
  // Under another label the normals must agree to 8 deg.
  other_label_map.update(o);
  tilted.mask_id = 26;
  EXPECT_NE(other_label_map.update(tilted), id);
  // Points 0.5 m off the entry, under its label: within 1 m, the same; 1.5 m off, another.
  PlaneObservation off = o;
  for (auto& p : off.points) p += 0.5 * o.normal;
  off.distance += 0.5;
  EXPECT_EQ(map.update(off), id);
  for (auto& p : off.points) p += 1.0 * o.normal;
  off.distance += 1.0;
  EXPECT_NE(map.update(off), id);
}

TEST(PlanesMap, ParallelPlanesOneMetreApartStaySeparate) {
  PlanesMap map;
  PlaneObservation a;
  a.mask_id = 1;
  a.normal = Eigen::Vector3d::UnitX();
  a.distance = 5.0;
  for (int k = 0; k < 10; ++k) a.points.emplace_back(5.0, k * 0.3, 1.0);
  PlaneObservation b = a;
  b.mask_id = 2;
  b.distance = 6.0;
  for (auto& p : b.points) p.x() = 6.0;
  EXPECT_NE(map.update(a), map.update(b));
  EXPECT_EQ(map.mergeDuplicates(), 0u);
  EXPECT_EQ(map.planes().size(), 2u);
}

TEST(PlanesMap, CoplanarButFarApartStaySeparateAndDuplicatesMerge) {
  PlanesMap map;
  const PlaneObservation a = crateTop();
  PlaneObservation far = a;
  far.mask_id = 2;
  for (auto& p : far.points) p.x() += 10;  // another crate top at the same height
  map.update(a);
  map.update(far);
  EXPECT_EQ(map.planes().size(), 2u);
  // A third observation bridging both: the two become one surface.
  PlaneObservation bridge = a;
  bridge.mask_id = 3;
  bridge.points.clear();
  for (int k = 0; k < 100; ++k) bridge.points.emplace_back(k * 0.11, 0, 1.0);
  map.update(bridge);
  EXPECT_EQ(map.mergeDuplicates(), 1u);
  EXPECT_EQ(map.planes().size(), 1u);
}

TEST(PlaneMapExporters, DiscoveredPlanesSaySoAndParseBack) {
  Plane mask, discovered;
  mask.id = 1;
  mask.mask_ids = {4};
  discovered.id = 2;
  discovered.mask_ids = {kFirstDiscoveredLabel, kFirstDiscoveredLabel + 3};
  EXPECT_FALSE(mask.discovered());
  EXPECT_TRUE(discovered.discovered());
  test::TempDir dir;
  writePlanesYaml(dir.file("planes.yaml"), {mask, discovered});
  std::ifstream in(dir.file("planes.yaml"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NE(text.find("source: discovery"), std::string::npos);
  EXPECT_EQ(text.find("source: discovery"), text.rfind("source: discovery"));  // once
  EXPECT_GT(text.find("source: discovery"), text.find("id: 2"));               // on plane 2
  const auto back = readPlanesYaml(dir.file("planes.yaml"));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_FALSE(back[0].discovered());
  EXPECT_TRUE(back[1].discovered());
  EXPECT_EQ(back[1].mask_ids, discovered.mask_ids);
}

// Found by tests/fuzz/planes_yaml_fuzz.cpp: an infinite mask id was cast to int (undefined).
TEST(PlaneMapExporters, PlanesYamlRefusesNumbersNotFiniteOrNotWhole) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"    mask_ids: [1e999]", "line 4: not a finite number: '1e999'"},
      {"    normal: [nan, 0, 1]", "line 4: not a finite number: 'nan'"},
      {"    id: 3.5", "line 4: 'id' needs whole numbers from"},
      {"    observations: -1", "line 4: 'observations' needs whole numbers from 0 to"},
      {"    mask_ids: [3, 2147483648]",
       "line 4: 'mask_ids' needs whole numbers from 0 to 2147483647"},
  };
  for (const auto& [text, expected] : cases) {
    test::TempDir dir;
    test::writeText(dir.file("planes.yaml"), "planes:\n  - id: 3\n    d: 1\n" + text + "\n");
    try {
      readPlanesYaml(dir.file("planes.yaml"));
      ADD_FAILURE() << text << ": read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(dir.file("planes.yaml") + ":" + expected),
                std::string::npos)
          << text << ": " << e.what();
    }
  }
}

TEST(PlaneMapExporters, FilesParseBackAndLoad) {
  size_t distinct = 0;
  const PlanesMap map = twoLaps(&distinct);
  test::TempDir dir;
  writePlanesYaml(dir.file("planes.yaml"), map.planes());
  const auto back = readPlanesYaml(dir.file("planes.yaml"));
  ASSERT_EQ(back.size(), map.planes().size());
  for (size_t k = 0; k < back.size(); ++k) {
    const Plane& a = map.planes()[k];
    EXPECT_EQ(back[k].id, a.id);
    EXPECT_LT((back[k].normal - a.normal).norm(), 1e-8);
    EXPECT_NEAR(back[k].distance, a.distance, 1e-8);
    EXPECT_EQ(back[k].polygon.size(), a.polygon.size());
    EXPECT_EQ(back[k].mask_ids, a.mask_ids);
    EXPECT_EQ(back[k].observations, a.observations);
  }

  writePlanesPly(dir.file("planes.ply"), map.planes());
  std::ifstream ply(dir.file("planes.ply"));
  std::string line;
  size_t vertices = 0, faces = 0, header_lines = 0;
  while (std::getline(ply, line) && line != "end_header") {
    ++header_lines;
    std::sscanf(line.c_str(), "element vertex %zu", &vertices);
    std::sscanf(line.c_str(), "element face %zu", &faces);
  }
  size_t expected_faces = 0, v_rows = 0, f_rows = 0;
  for (const auto& p : map.planes())
    expected_faces += p.polygon.size() >= 3 ? p.polygon.size() - 2 : 0;
  EXPECT_EQ(faces, expected_faces);
  for (size_t k = 0; k < vertices && std::getline(ply, line); ++k) {
    double x, y, z;
    int r, g, b;
    v_rows += std::sscanf(line.c_str(), "%lf %lf %lf %d %d %d", &x, &y, &z, &r, &g, &b) == 6;
  }
  for (size_t k = 0; k < faces && std::getline(ply, line); ++k) {
    size_t n, a, b, c;
    f_rows +=
        std::sscanf(line.c_str(), "%zu %zu %zu %zu", &n, &a, &b, &c) == 4 && n == 3 && c < vertices;
  }
  EXPECT_EQ(v_rows, vertices);
  EXPECT_EQ(f_rows, faces);

  const double resolution = 0.1;
  writePlanesOctomap(dir.file("planes.bt"), map.planes(), resolution);
  octomap::OcTree tree(dir.file("planes.bt"));
  size_t occupied = 0, near_a_plane = 0;
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    ++occupied;
    const Eigen::Vector3d c(it.getX(), it.getY(), it.getZ());
    double best = 1e9;
    for (const auto& truth : scene().planes())
      best = std::min(best, std::abs(truth.normal.dot(c) - truth.distance()));
    near_a_plane += best <= 2 * resolution;
  }
  EXPECT_GT(occupied, 100u);
  EXPECT_EQ(near_a_plane, occupied);

  writePlanesScene(dir.file("planes.3Dscene"), map.planes());
  mrpt::opengl::COpenGLScene loaded;
  EXPECT_TRUE(loaded.loadFromFile(dir.file("planes.3Dscene")));
  EXPECT_GE(loaded.viewportsCount(), 1u);

  writePlanesTopView(dir.file("top.png"), map.planes());
  EXPECT_EQ(cv::imread(dir.file("top.png")).cols, 900);
  if (const char* keep = std::getenv("RPVIO_KEEP_TOPVIEW")) writePlanesTopView(keep, map.planes());
}

}  // namespace
}  // namespace rpvio
