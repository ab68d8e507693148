#!/bin/sh
# The dependency rule (docs/architecture.md): a folder includes only its own headers and those of
# the layers below it. Lowest first: common → rawlog_io → rosbag_io, sim → planes_map → mrpt_modules →
# evaluation → apps. Prints every violation as file:line and exits 1 if there is one.
# Usage: scripts/check-layers.sh [repository root]
set -eu
cd "${1:-$(dirname "$0")/..}"

# folder: the include prefixes it may use (a more specific folder is listed before its parent).
RULES="
common: common/
rawlog_io: common/ rawlog_io/
rosbag_io: common/ rawlog_io/ rosbag_io/
sim: common/ rawlog_io/ sim/
planes_map: common/ planes_map/
mrpt_modules/imu: common/ mrpt_modules/imu/
mrpt_modules/factors: common/ mrpt_modules/imu/ mrpt_modules/factors/
mrpt_modules/outputs: common/ rawlog_io/trajectory_io.h planes_map/ mrpt_modules/
mrpt_modules: common/ rawlog_io/rawlog_labels.h rawlog_io/rawlog_reader.h rawlog_io/mrpt_conversions.h rawlog_io/uniform_plane_region.h planes_map/ mrpt_modules/
evaluation: common/ rawlog_io/uniform_plane_region.h rawlog_io/rawlog_labels.h planes_map/ evaluation/
"

report=$(mktemp)
files=$(git ls-files '*.h' '*.cpp' 2>/dev/null || find . -name '*.h' -o -name '*.cpp' | sed 's|^\./||')
for file in $files; do
  allowed=""
  for folder in $(echo "$RULES" | sed -n 's/^\([a-z_/]*\):.*/\1/p'); do
    case "$file" in
      "$folder"/*)
        allowed=$(echo "$RULES" | sed -n "s|^$folder: ||p")
        break
        ;;
    esac
  done
  [ -n "$allowed" ] || continue
  grep -n '^#include "' "$file" | while IFS= read -r line; do
    header=$(echo "$line" | sed 's/^[0-9]*:#include "\([^"]*\)".*/\1/')
    ok=no
    for prefix in $allowed; do
      case "$header" in "$prefix"*) ok=yes ;; esac
    done
    if [ "$ok" = no ]; then
      echo "$file:${line%%:*}: includes $header (may include only: $allowed)"
    fi
  done
done >"$report"
if [ -s "$report" ]; then
  cat "$report"
  rm -f "$report"
  exit 1
fi
rm -f "$report"
echo "check-layers: every include follows the dependency rule"
