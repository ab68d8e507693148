#pragma once
namespace rpvio::apps {
/// rpvio-slam: plays a rawlog through the modules of a mode's config and writes the trajectory.
int slamMain(int argc, char** argv);
}  // namespace rpvio::apps
