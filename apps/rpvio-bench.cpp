// rpvio-bench: the paper's Table I side by side, with timing and plots (see apps/lib/bench_app.h).
#include "apps/lib/bench_app.h"

int main(int argc, char** argv) { return rpvio::apps::benchMain(argc, argv); }
