#!/bin/bash
# A stand-in for the conefeti program, for the classifier of scripts/fuzz-scenes.py --solver-options. STANDIN says
# what it does with every run:
#   refuse-drawn  exit 1 with an error line naming the last solver option drawn (the second-to-last word of its
#                 command line): a combination the program says it does not take, OK-refused
#   refuse-other  exit 1 with an error line naming -scene_refine, which no draw gives: a valid scene refused, FAIL-crash
#   polygon       exit 0, converged, every residual of the verdict within the acceptance but "approximation" (the
#                 distance of a friction polygon's solution from the disk law, reported beside the verdict) far above
#                 it: OK-converged
case "$STANDIN" in
  refuse-drawn)
    echo "conefeti: error: ${@: -2:1}: not taken in this combination (stand-in)"
    exit 1 ;;
  refuse-other)
    echo "conefeti: error: -scene_refine: not taken in this combination (stand-in)"
    exit 1 ;;
  polygon)
    echo '{"conefeti":"stand-in","converged":true,"acceptance":1e-05,"residuals":{"equilibrium":1e-07,"gluing":1e-07,"max":1e-07,"approximation":0.05}}'
    exit 0 ;;
esac
echo "STANDIN must be refuse-drawn, refuse-other or polygon" >&2
exit 3
