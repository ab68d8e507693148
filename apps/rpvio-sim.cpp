// rpvio-sim: simulated dynamic warehouse sequences (see apps/lib/sim_app.h).
#include "apps/lib/sim_app.h"

int main(int argc, char** argv) { return rpvio::apps::simMain(argc, argv); }
