// Moving planar objects (pallet trucks, sliding panels): labelled as planes, marked dynamic, drawn
// where their ground-truth motion puts them.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>
#include <set>

#include "common/input_error.h"
#include "sim/simulator.h"
#include "tests/test_util.h"

namespace rpvio::sim {
namespace {

SimConfig movingConfig() {
  SimConfig c;
  c.render.noise_sigma = 0;
  c.render.vignetting = 0;
  c.scene.texel_size = 0.05;  // coarser textures: faster scene construction in tests
  c.scene.pallet_trucks = 1;
  c.scene.sliding_panels = 1;
  return c;
}

/// Plane ids of every moving face.
std::set<int> movingFaceIds(const WarehouseScene& scene) {
  std::set<int> ids;
  for (const MovingPlanarObject& object : scene.movingObjects())
    for (const PosedFace& face : object.faces(0)) ids.insert(face.id);
  return ids;
}

/// Ids of the entries with `moving: true` in a groundtruth_planes.yaml text.
std::set<int> movingIdsInYaml(const std::string& yaml) {
  std::set<int> ids;
  const std::string entry = "\n  - id: ";
  for (size_t at = yaml.find(entry); at != std::string::npos;) {
    const size_t next = yaml.find(entry, at + 1);
    if (yaml.substr(at, next - at).find("\n    moving: true\n") != std::string::npos)
      ids.insert(std::stoi(yaml.substr(at + entry.size())));
    at = next;
  }
  return ids;
}

TEST(MovingObjects, LabelledAsPlanesMarkedDynamicAndMovingInTheGroundTruth) {
  const SimConfig config = movingConfig();
  Simulator sim(config);
  const std::set<int> ids = movingFaceIds(sim.scene());
  ASSERT_EQ(ids.size(), 12u);  // a truck's 10 faces, a panel's 2
  EXPECT_EQ(*ids.begin(), kMovingPlaneIdFirst);
  EXPECT_LE(*ids.rbegin(), kMovingPlaneIdLast);
  std::map<int, int> pixels;  // per moving face id, over the sequence
  int mislabelled = 0;
  for (double t = 8; t <= 22; t += 2) {
    const RenderedFrame frame = sim.render(t, 0);
    for (int r = 0; r < frame.mask.rows; ++r)
      for (int c = 0; c < frame.mask.cols; ++c) {
        const int label = frame.mask.at<uint8_t>(r, c);
        const bool moving = ids.count(label) > 0;
        if (moving) ++pixels[label];
        // No characters here: dynamic exactly where a moving face is seen.
        if (moving != (frame.dynamic.at<uint8_t>(r, c) == 255)) ++mislabelled;
      }
  }
  EXPECT_EQ(mislabelled, 0);
  int truck = 0, panel = 0;
  for (const auto& [id, n] : pixels)
    (id < kMovingPlaneIdFirst + kPalletTruckFaces ? truck : panel) += n;
  EXPECT_GT(truck, 5000);
  EXPECT_GT(panel, 5000);
  // groundtruth_planes.yaml of the same scene marks exactly these ids moving.
  test::TempDir dir;
  test::writeText(dir.file("scene.ini"), "[scene]\npallet_trucks = 1\nsliding_panels = 1\n");
  std::string out;
  ASSERT_EQ(test::runCommand(std::string(RPVIO_BIN_DIR) +
                                 "/rpvio-sim --characters 0 --duration 0.1 --config " +
                                 dir.file("scene.ini") + " --out " + dir.file("seq"),
                             out),
            0)
      << out;
  EXPECT_EQ(movingIdsInYaml(test::readFile(dir.file("seq/groundtruth_planes.yaml"))), ids);
}

TEST(MovingObjects, TooManyForTheirPlaneIdsIsABadConfig) {
  test::TempDir dir;
  test::writeText(dir.file("scene.ini"), "[scene]\npallet_trucks = 4\nsliding_panels = 1\n");
  EXPECT_THROW(SimConfig::load(dir.file("scene.ini")), InputError);
}

/// Signed distance (px) of x to the convex polygon's boundary, positive inside.
double insideDistance(const std::array<Eigen::Vector2d, 4>& polygon, const Eigen::Vector2d& x) {
  const Eigen::Vector2d centre = 0.25 * (polygon[0] + polygon[1] + polygon[2] + polygon[3]);
  double d = INFINITY;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d a = polygon[i], e = (polygon[(i + 1) % 4] - a).normalized();
    Eigen::Vector2d n(-e.y(), e.x());
    if (n.dot(centre - a) < 0) n = -n;
    d = std::min(d, n.dot(x - a));
  }
  return d;
}

/// Face `id` at t2 is drawn where its ground-truth motion since t1 puts it.
void expectDrawnWhereItsMotionPutsIt(Simulator& sim, int id, double t1, double t2) {
  PosedFace f1, f2;
  for (const MovingPlanarObject& object : sim.scene().movingObjects())
    for (size_t k = 0; k < object.faces(t1).size(); ++k)
      if (object.faces(t1)[k].id == id) f1 = object.faces(t1)[k], f2 = object.faces(t2)[k];
  ASSERT_EQ(f2.id, id);
  std::array<Eigen::Vector2d, 4> c1, c2;  // projected true corners at t1 and t2
  for (int i = 0; i < 4; ++i) {
    const auto p1 = sim.project(t1, f1.corners[i]), p2 = sim.project(t2, f2.corners[i]);
    ASSERT_TRUE(p1 && p2);
    c1[i] = *p1, c2[i] = *p2;
  }
  // The mask at t2: pixel centres more than 0.5 px inside the projected face carry its id, those
  // more than 0.5 px outside do not (a face's edges project to straight lines).
  const RenderedFrame frame = sim.render(t2, 0);
  int inside = 0, wrong = 0;
  for (int r = 0; r < frame.mask.rows; ++r)
    for (int c = 0; c < frame.mask.cols; ++c) {
      const double d = insideDistance(c2, Eigen::Vector2d(c, r));
      const bool labelled = frame.mask.at<uint8_t>(r, c) == id;
      if (d > 0.5) ++inside, wrong += !labelled;
      if (d < -0.5) wrong += labelled;
    }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(inside, 3000);
  // Half a pixel inside / outside each projected corner, towards / away from the face's centre.
  const Eigen::Vector2d centre = 0.25 * (c2[0] + c2[1] + c2[2] + c2[3]);
  for (const Eigen::Vector2d& corner : c2) {
    const Eigen::Vector2d towards = 0.5 * (centre - corner).normalized();
    EXPECT_EQ(sim.castPixel(t2, corner.x() + towards.x(), corner.y() + towards.y()).label, id);
    EXPECT_NE(sim.castPixel(t2, corner.x() - towards.x(), corner.y() - towards.y()).label, id);
  }
  // The homography of the face's t1 plane as if static, H = K (R21 + t21 n1ᵀ / d1) K⁻¹ (plane
  // n1·X = d1 in camera 1, X2 = R21 X1 + t21), maps the t1 corners far from the true t2 ones.
  const Eigen::Isometry3d T_WC1 = sim.cameraPose(t1), T_21 = sim.cameraPose(t2).inverse() * T_WC1;
  const Eigen::Vector3d n1 = T_WC1.linear().transpose() * f1.normal;
  const double d1 = f1.distance - f1.normal.dot(T_WC1.translation());
  const PinholeCamera& cam = sim.camera();
  Eigen::Matrix3d K;
  K << cam.fx, 0, cam.cx, 0, cam.fy, cam.cy, 0, 0, 1;
  const Eigen::Matrix3d H =
      K * (T_21.linear() + T_21.translation() * n1.transpose() / d1) * K.inverse();
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector2d h = (H * c1[i].homogeneous()).hnormalized();
    // H is the static plane's: it maps the t1 corner where a static corner would be at t2.
    EXPECT_LT((h - *sim.project(t2, f1.corners[i])).norm(), 1e-6);
    EXPECT_GT((h - c2[i]).norm(), 10.0) << "corner " << i;
  }
}

TEST(MovingObjects, DrawnWhereTheirMotionPutsThemNotWhereAStaticPlaneWould) {
  Simulator sim(movingConfig());
  {
    SCOPED_TRACE("truck: a side of its load");
    expectDrawnWhereItsMotionPutsIt(sim, 203, 12.0, 12.5);
  }
  {
    SCOPED_TRACE("panel: the side facing the flight circle");
    expectDrawnWhereItsMotionPutsIt(sim, 211, 21.0, 21.5);
  }
}

}  // namespace
}  // namespace rpvio::sim
