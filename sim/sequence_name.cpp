#include "sim/sequence_name.h"

namespace rpvio::sim {
namespace {

std::optional<int> characterCount(const std::string& text) {  // "C<N>"
  if (text.size() < 2 || text[0] != 'C' ||
      text.find_first_not_of("0123456789", 1) != std::string::npos || text.size() > 4)
    return std::nullopt;
  return std::stoi(text.substr(1));
}

}  // namespace

std::optional<SequenceContent> parseSequenceName(const std::string& name) {
  SequenceContent content;
  if (name == "static") return content;
  std::string people = name;
  if (name.rfind("MP", 0) == 0) {
    content.moving_objects = true;
    if (name == "MP") return content;
    if (name.rfind("MP-", 0) != 0) return std::nullopt;
    people = name.substr(3);
  }
  const auto n = characterCount(people);
  if (!n) return std::nullopt;
  content.characters = *n;
  return content;
}

SimConfig withSequenceContent(SimConfig config, const SequenceContent& content) {
  config.scene.characters = content.characters;
  if (content.moving_objects) {
    config.scene.pallet_trucks = kSuitePalletTrucks;
    config.scene.sliding_panels = kSuiteSlidingPanels;
  }
  return config;
}

std::vector<std::string> suiteSequences(const std::string& profile) {
  std::vector<std::string> names = {"static", "C1", "C2", "C4", "C6", "C8"};
  if (profile == "hard") names.insert(names.end(), {"MP", "MP-C4"});
  return names;
}

}  // namespace rpvio::sim
