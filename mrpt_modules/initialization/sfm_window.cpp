#include "mrpt_modules/initialization/sfm_window.h"

#include <unordered_map>

namespace rpvio {

SfmWindow SfmWindow::fromFrames(const std::vector<FeatureFrame>& frames) {
  SfmWindow window;
  window.cameras.resize(frames.size());
  std::unordered_map<int, size_t> track_of;
  for (size_t k = 0; k < frames.size(); ++k)
    for (const auto& f : frames[k].features) {
      auto [it, inserted] = track_of.try_emplace(f.id, window.tracks.size());
      if (inserted) window.tracks.push_back(SfmTrack{f.id, f.plane_id, {}, std::nullopt});
      window.tracks[it->second].observations.push_back({k, f.normalized});
    }
  return window;
}

}  // namespace rpvio
