#pragma once
// Pipeline module around MapBuilder: owns the planes map, the keyframe archive and the batch
// refinement, fed by what the estimator module publishes as keyframes leave its window
// (map_sink.h); announces its map (MapReady) when set up and publishes the finished map
// (MapSummary) at the end. Listed after the estimator, before the outputs. Options: section
// [MapBuilderModule] (MapBuilderOptions) and [PlanesMap] (PlanesMapOptions).
#include <memory>

#include "mrpt_modules/core/module.h"
#include "mrpt_modules/estimator/map_builder.h"

namespace rpvio {

class MapBuilderModule : public Module {
  DEFINE_MRPT_OBJECT(MapBuilderModule, rpvio)

 public:
  void initialize(const IniFile& config, const std::string& section,
                  PipelineContext& context) override;
  void finish() override;

 private:
  std::unique_ptr<MapBuilder> builder_;
  const Bus* bus_ = nullptr;
};

}  // namespace rpvio
