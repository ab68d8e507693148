// The top view (planes_topview.png): floors are filled and ceilings outlined, whichever way an
// estimate's normal faces.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "planes_map/plane_map_exporters.h"
#include "tests/test_util.h"

namespace rpvio {
namespace {

/// A horizontal 4 m x 4 m square at height z centred at (x, 0), normal up or down.
Plane horizontalSquare(int id, double x, double z, double normal_z) {
  Plane p;
  p.id = id;
  p.normal = Eigen::Vector3d(0, 0, normal_z);
  p.distance = normal_z * z;
  p.polygon = {{x - 2, -2, z}, {x + 2, -2, z}, {x + 2, 2, z}, {x - 2, 2, z}};
  return p;
}

/// The image spans x in [-5, 5] m and y in [-2, 2] m at 80 px/m from a 50 px margin: the point
/// (x, 0) is at column 50 + 80 (x + 5), row 900 − 50 − 80 · 2.
cv::Vec3b colourAt(const cv::Mat& image, double x) {
  return image.at<cv::Vec3b>(690, static_cast<int>(50 + 80 * (x + 5)));
}

TEST(PlanesTopView, FloorsAreFilledAndCeilingsOutlinedWhateverTheNormalsSign) {
  test::TempDir dir;
  for (double floor_normal_z : {1.0, -1.0})
    for (double ceiling_normal_z : {1.0, -1.0})
      for (bool with_trajectory : {true, false}) {
        // Floor centred at x = -3, ceiling at x = +3: side by side, 2 m apart.
        const std::vector<Plane> planes = {horizontalSquare(1, -3, 0, floor_normal_z),
                                           horizontalSquare(2, 3, 4, ceiling_normal_z)};
        Trajectory trajectory;
        if (with_trajectory)
          for (double x : {-1.0, 1.0}) {
            StampedPose pose;
            pose.p = Eigen::Vector3d(x, 0, 1.5);
            trajectory.push_back(pose);
          }
        const std::string png = dir.file("top.png");
        writePlanesTopView(png, planes, trajectory);
        const cv::Mat image = cv::imread(png);
        ASSERT_EQ(image.cols, 900);
        const auto floor = planeColour(1);
        const cv::Vec3b floor_bgr(floor[2], floor[1], floor[0]), white(255, 255, 255);
        SCOPED_TRACE(testing::Message() << "floor n_z " << floor_normal_z << ", ceiling n_z "
                                        << ceiling_normal_z << ", trajectory " << with_trajectory);
        EXPECT_EQ(colourAt(image, -3), floor_bgr);
        EXPECT_EQ(colourAt(image, 3), white);
      }
}

}  // namespace
}  // namespace rpvio
