#!/bin/sh
# Long run (issue 10): simulate a long sequence (default 600 s, about 16 laps) and a reference one
# (default 80 s), run a mode on both under /usr/bin/time -v and report what must stay flat: peak
# RSS of the long run against the reference, and the median per-frame time of the long run's last
# minute against its first minute.
# Usage: scripts/long-run.sh [BUILD_DIR] [MODE] [LONG_S] [REFERENCE_S] [CHARACTERS]
set -eu
BUILD=${1:-build}
MODE=${2:-rpvio-single}
LONG_S=${3:-600}
REFERENCE_S=${4:-80}
CHARACTERS=${5:-4}
OUT=${RPVIO_LONG_RUN_DIR:-/tmp/rpvio-long-run}
mkdir -p "$OUT"

run() {  # run DURATION: simulates (once) and processes a sequence, prints the peak RSS in MB
  seq="$OUT/C$CHARACTERS-$1s"
  [ -f "$seq/seq.rawlog" ] ||
    "$BUILD/bin/rpvio-sim" --characters "$CHARACTERS" --duration "$1" --out "$seq" >/dev/null
  /usr/bin/time -v -o "$OUT/$MODE-$1s.time" "$BUILD/bin/rpvio-slam" --config "config/$MODE.ini" \
    --calib "$seq/calib.ini" --rawlog "$seq/seq.rawlog" --out "$OUT/$MODE-$1s" --quiet \
    >"$OUT/$MODE-$1s.log" 2>&1
  awk -F: '/Maximum resident set size/ { printf "%.1f\n", $2 / 1024 }' "$OUT/$MODE-$1s.time"
}

median_total_ms() {  # median_total_ms STATS FROM_S TO_S: median total_ms of frames in [FROM, TO)
  awk -F, -v a="$2" -v b="$3" 'NR > 1 && $1 >= a && $1 < b { print $5 }' "$1" | sort -g |
    awk '{ v[NR] = $1 } END { if (NR == 0) print "nan"; else if (NR % 2) print v[(NR + 1) / 2];
                              else printf "%.3f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

reference_mb=$(run "$REFERENCE_S")
long_mb=$(run "$LONG_S")
stats="$OUT/$MODE-${LONG_S}s/stats.csv"
first=$(median_total_ms "$stats" 0 60)
last=$(median_total_ms "$stats" $((LONG_S - 60)) "$LONG_S")
resets=$(grep -o '"resets": [0-9]*' "$OUT/$MODE-${LONG_S}s/summary.json" | grep -o '[0-9]*$')
echo "mode $MODE, C$CHARACTERS: peak RSS ${REFERENCE_S} s run $reference_mb MB, ${LONG_S} s run" \
  "$long_mb MB (ratio $(echo "$long_mb $reference_mb" | awk '{ printf "%.3f", $1 / $2 }'));" \
  "median ms/frame first minute $first, last minute $last" \
  "(ratio $(echo "$last $first" | awk '{ printf "%.3f", $1 / $2 }')); resets $resets"
echo "outputs in $OUT"
