// rpvio-slam: headless batch SLAM over a rawlog (see apps/lib/slam_app.h).
#include "apps/lib/slam_app.h"

int main(int argc, char** argv) { return rpvio::apps::slamMain(argc, argv); }
