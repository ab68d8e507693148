#pragma once
// ../shared/data/vamr_checkerboard (real hand-held frames over a checkerboard, every camera pose
// known; its README): the poses, for the tests on real images (test helper).
#include <Eigen/Geometry>
#include <fstream>
#include <string>
#include <vector>

#include "tests/test_util.h"

namespace rpvio::test {

inline std::string vamrDir() { return dataDir() + "/vamr_checkerboard"; }

/// cam_T_w of every frame (poses.txt: axis-angle, translation); the board is the plane Z = 0.
inline std::vector<Eigen::Isometry3d> vamrCameraFromWorld() {
  std::ifstream in(vamrDir() + "/poses.txt");
  std::vector<Eigen::Isometry3d> poses;
  double w[3], t[3];
  while (in >> w[0] >> w[1] >> w[2] >> t[0] >> t[1] >> t[2]) {
    const Eigen::Vector3d axis(w[0], w[1], w[2]);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    if (axis.norm() > 0) T.linear() = Eigen::AngleAxisd(axis.norm(), axis.normalized()).matrix();
    T.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
    poses.push_back(T);
  }
  return poses;
}

}  // namespace rpvio::test
