#pragma once
namespace rpvio::apps {
/// rpvio-bench: every mode on every sequence of a simulator suite, side by side (issue 9).
int benchMain(int argc, char** argv);
}  // namespace rpvio::apps
