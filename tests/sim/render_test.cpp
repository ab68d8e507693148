// Rendering geometry and masks against the simulator's own analytic ground truth.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "sim/simulator.h"

namespace rpvio::sim {
namespace {

SimConfig cleanConfig(int characters) {
  SimConfig c;
  c.render.noise_sigma = 0;
  c.render.vignetting = 0;
  c.scene.characters = characters;
  c.scene.texel_size = 0.05;  // coarser textures: faster scene construction in tests
  return c;
}

TEST(Render, LandmarkOnPlaneDrawnAtItsAnalyticProjection) {
  const double t = 12.3;
  SimConfig config = cleanConfig(0);
  config.render.supersampling = 8;
  // Landmarks: the surface points seen at a few pixels, painted as discs about 5 px in radius.
  Simulator probe(config);
  std::vector<Eigen::Vector3d> landmarks;
  for (const auto& px : {Eigen::Vector2d(200.3, 150.7), Eigen::Vector2d(451.6, 302.2),
                         Eigen::Vector2d(320.0, 420.4)}) {
    const SceneHit hit = probe.castPixel(t, px.x(), px.y());
    ASSERT_NE(hit.label, kMaskNothing);
    landmarks.push_back(hit.point);
    config.scene.markers.push_back({hit.point, 0.015 * hit.t, 255});
  }
  const cv::Mat without = probe.render(t, 0).image;
  Simulator sim(config);
  const cv::Mat with = sim.render(t, 0).image;
  cv::Mat diff;
  cv::absdiff(with, without, diff);
  for (const Eigen::Vector3d& X : landmarks) {
    const auto expected = sim.project(t, X);
    ASSERT_TRUE(expected);
    // Centroid of the disc's footprint in a window around the analytic projection.
    const int x0 = static_cast<int>(expected->x()) - 12, y0 = static_cast<int>(expected->y()) - 12;
    double sum = 0, sx = 0, sy = 0;
    for (int r = y0; r <= y0 + 24; ++r)
      for (int c = x0; c <= x0 + 24; ++c) {
        const double w = diff.at<uint8_t>(r, c);
        sum += w, sx += w * c, sy += w * r;
      }
    ASSERT_GT(sum, 0);
    const double error = (Eigen::Vector2d(sx / sum, sy / sum) - *expected).norm();
    std::printf("landmark drawn %.4f px from its analytic projection\n", error);
    EXPECT_LT(error, 0.25) << "drawn at " << sx / sum << "," << sy / sum << " expected "
                           << expected->transpose();
  }
}

TEST(Render, CastAndProjectAreInverse) {
  Simulator sim(cleanConfig(0));
  for (double t : {0.0, 5.5, 40.0}) {
    const SceneHit hit = sim.castPixel(t, 123.25, 377.5);
    const auto px = sim.project(t, hit.point);
    ASSERT_TRUE(px);
    EXPECT_LT((*px - Eigen::Vector2d(123.25, 377.5)).norm(), 1e-6);
  }
}

TEST(Render, MaskLabelsPlanesAndCharacters) {
  Simulator sim(cleanConfig(4));
  int character_pixels = 0, plane_pixels = 0;
  for (double t : {2.0, 21.0, 47.5}) {
    const RenderedFrame frame = sim.render(t, 0);
    for (int r = 0; r < 480; r += 4)
      for (int c = 0; c < 640; c += 4) {
        const SceneHit hit = sim.castPixel(t, c, r);
        const int label = frame.mask.at<uint8_t>(r, c);
        ASSERT_EQ(label, hit.label);
        if (label == kMaskCharacter) {
          // Points on characters are 0 in the mask and lie on a character's surface.
          EXPECT_LT(std::abs(sim.distanceToCharacters(t, hit.point)), 1e-6);
          ++character_pixels;
        } else {
          // Points on planes carry that plane's id: they satisfy its equation n·X = d.
          const ScenePlane* plane = sim.scene().plane(label);
          ASSERT_NE(plane, nullptr) << "label " << label;
          EXPECT_NEAR(plane->normal.dot(hit.point), plane->distance(), 1e-6);
          ++plane_pixels;
        }
      }
  }
  EXPECT_GT(character_pixels, 20);
  EXPECT_GT(plane_pixels, 10000);
}

TEST(Render, WallsCarryTheirOwnIds) {
  Simulator sim(cleanConfig(0));
  // From the start (x = 15, looking at −x), the image centre ray goes to the far wall x = −20 (id
  // 4) unless a crate is in the way; the top of the image sees the ceiling (id 6).
  const SceneHit top = sim.castPixel(0.0, 320, 5);
  EXPECT_EQ(top.label, 6);
  const SceneHit floor = sim.castPixel(0.0, 320, 475);
  EXPECT_EQ(floor.label, 1);
  EXPECT_NEAR(floor.point.z(), 0.0, 1e-9);
  const SceneHit left = sim.castPixel(0.0, 2, 200);
  EXPECT_NE(left.label, kMaskCharacter);
}

}  // namespace
}  // namespace rpvio::sim
