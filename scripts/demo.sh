#!/bin/sh
# The main job: simulate a short dynamic sequence, run RP-VIO on it, print the accuracy.
# Not available until the estimator pipeline runs end to end (issue 7).
echo "demo: the RP-VIO pipeline is not complete yet (see issue 7); nothing to run." >&2
exit 1
