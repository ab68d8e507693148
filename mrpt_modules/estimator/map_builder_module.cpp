#include "mrpt_modules/estimator/map_builder_module.h"

#include <mrpt/core/initializer.h>

IMPLEMENTS_MRPT_OBJECT(MapBuilderModule, rpvio::Module, rpvio)

// Registered with MRPT RTTI when the program loads, so a config can name it.
MRPT_INITIALIZER(register_MapBuilderModule) {
  mrpt::rtti::registerClass(CLASS_ID(rpvio::MapBuilderModule));
}

namespace rpvio {

void MapBuilderModule::initialize(const IniFile& ini, const std::string& section,
                                  PipelineContext& context) {
  const auto options = loadOptions<MapBuilderOptions>(ini, section);
  const auto map_options = PlanesMapOptions::load(ini, "PlanesMap");
  builder_ = std::make_unique<MapBuilder>(map_options, options);
  bus_ = &context.bus;
  context.bus.subscribe<PlanesSeen>([this](const PlanesSeen& p) { builder_->planesSeen(p); });
  context.bus.subscribe<KeyframeLeft>([this](const KeyframeLeft& k) { builder_->keyframeLeft(k); });
  context.bus.subscribe<KeyframeChainBroken>(
      [this](const KeyframeChainBroken&) { builder_->chainBroken(); });
  context.bus.subscribe<NewWorld>([this](const NewWorld&) { builder_->newWorld(); });
  context.bus.subscribe<WindowFinished>(
      [this](const WindowFinished& end) { builder_->windowFinished(end); });
  context.bus.publishRetained(MapReady{&builder_->planesMap()});
  setOptionsText("[" + section + "]\n" + describeOptions(options) + "\n[PlanesMap]\n" +
                 map_options.describe());
}

void MapBuilderModule::finish() {
  if (!builder_->refinementReport().empty()) MRPT_LOG_INFO_STREAM(builder_->refinementReport());
  bus_->publish(MapSummary{&builder_->planesMap(), builder_->refinedTrajectory(),
                           builder_->refinementReport(), builder_->refinementSeconds()});
}

}  // namespace rpvio
