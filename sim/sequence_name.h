#pragma once
// The names of a suite's sequences and what they contain: "static" (no moving thing), "C<N>" (N
// characters), "MP" (moving planar objects: two pallet trucks and two sliding panels, no people)
// and "MP-C<N>" (both).
#include <optional>
#include <string>
#include <vector>

#include "sim/sim_config.h"

namespace rpvio::sim {

struct SequenceContent {
  int characters = 0;
  bool moving_objects = false;
};

constexpr int kSuitePalletTrucks = 2, kSuiteSlidingPanels = 2;  // in the MP sequences

/// nullopt for a name that is none of the above.
std::optional<SequenceContent> parseSequenceName(const std::string& name);
/// `config` with the content of the named sequence (characters; the MP sequences' objects).
SimConfig withSequenceContent(SimConfig config, const SequenceContent& content);
/// The sequences `rpvio-sim --suite` writes: static, C1, C2, C4, C6, C8; the hard profile adds MP
/// and MP-C4.
std::vector<std::string> suiteSequences(const std::string& profile);

}  // namespace rpvio::sim
