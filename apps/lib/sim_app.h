#pragma once
namespace rpvio::apps {
/// rpvio-sim: renders simulated warehouse sequences (see rawlog_io/sim/).
int simMain(int argc, char** argv);
}  // namespace rpvio::apps
