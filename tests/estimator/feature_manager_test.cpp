// FeatureManager on exact synthetic geometry: triangulation recovers the depths, re-anchoring
// keeps the world points, too little parallax leaves tracks untriangulated.
#include <gtest/gtest.h>

#include <map>

#include "mrpt_modules/estimator/feature_manager.h"

namespace rpvio {
namespace {

struct Scene {
  std::map<uint64_t, Eigen::Isometry3d> cameras;  // camera in world
  std::vector<Eigen::Vector3d> points;
  CameraPoseLookup lookup() const {
    return [this](uint64_t id) { return cameras.at(id); };
  }
  FeatureFrame observe(uint64_t frame) const {
    FeatureFrame f;
    for (size_t k = 0; k < points.size(); ++k) {
      const Eigen::Vector3d c = cameras.at(frame).inverse() * points[k];
      TrackedFeature t;
      t.id = static_cast<int>(k);
      t.plane_id = 1;
      t.normalized = c.head<2>() / c.z();
      f.features.push_back(t);
    }
    return f;
  }
};

Scene makeScene(double baseline) {
  Scene s;
  for (uint64_t k = 0; k < 3; ++k) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(0.05 * k, Eigen::Vector3d::UnitY()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(baseline * k, 0.1 * k, 0);
    s.cameras[k] = T;
  }
  for (int k = 0; k < 20; ++k)
    s.points.emplace_back(-2 + 0.2 * k, 1.0 - 0.1 * k, 4 + 0.3 * (k % 5));
  return s;
}

TEST(FeatureManager, TriangulatesAndReanchorsExactly) {
  const Scene s = makeScene(0.5);
  FeatureManager m;
  for (uint64_t k = 0; k < 3; ++k) m.addFrame(k, s.observe(k));
  m.triangulate(s.lookup(), 1.0 * M_PI / 180, 0.1, 100);
  ASSERT_EQ(m.tracks().size(), s.points.size());
  for (const auto& [id, track] : m.tracks()) {
    ASSERT_TRUE(track.triangulated) << id;
    EXPECT_LT((m.worldPoint(track, s.lookup()) - s.points[id]).norm(), 1e-9) << id;
  }
  // Frame 0 leaves the window: tracks are anchored at frame 1 with the same world points.
  m.removeFrame(0, s.lookup());
  for (const auto& [id, track] : m.tracks()) {
    EXPECT_EQ(track.observations.front().frame, 1u);
    EXPECT_EQ(track.observations.size(), 2u);
    EXPECT_LT((m.worldPoint(track, s.lookup()) - s.points[id]).norm(), 1e-9) << id;
  }
  m.removeFrame(1, s.lookup());
  m.removeFrame(2, s.lookup());
  EXPECT_TRUE(m.tracks().empty());
}

TEST(FeatureManager, NoTriangulationWithoutParallax) {
  const Scene s = makeScene(0.0);  // rotation about the camera centre plus 0.1 m sideways
  FeatureManager m;
  for (uint64_t k = 0; k < 2; ++k) m.addFrame(k, s.observe(k));
  m.triangulate(s.lookup(), 5.0 * M_PI / 180, 0.1, 100);
  for (const auto& [id, track] : m.tracks()) EXPECT_FALSE(track.triangulated) << id;
}

}  // namespace
}  // namespace rpvio
