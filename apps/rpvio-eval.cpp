// rpvio-eval: trajectory accuracy (see apps/lib/eval_app.h).
#include "apps/lib/eval_app.h"

int main(int argc, char** argv) { return rpvio::apps::evalMain(argc, argv); }
