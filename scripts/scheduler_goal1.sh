#!/usr/bin/env bash
# The scheduler's Goal 1 as docs/scheduler.md states it: per built-in scene a fresh default
# calibration, then `lodopt schedule --render` along the scene's path (the harbor: a spiral
# approach, written here) with the binding frames' share within ±10% of the budget divided by the
# run's measurement ceiling (summary.json `goal_1.of_ceiling`; goal >= 0.9).
#   scripts/scheduler_goal1.sh [OUT]        (default out/scheduler-goal1)
# Budgets (512², pbr): harbor 8 ms, forest 30 ms, city 60 ms; every 4th frame of the forest and
# the city. Run on a quiet machine. Environment: LODOPT (default build/cli/lodopt).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/scheduler-goal1}
lodopt=${LODOPT:-build/cli/lodopt}
python=${PYTHON:-/usr/bin/python3}
mkdir -p "$out"
"$python" scripts/harbor_approach.py "$out/harbor_approach.json"
for entry in "harbor:8:1:--path $out/harbor_approach.json" forest:30:4: city:60:4:; do
  IFS=: read -r scene budget stride path <<< "$entry"
  "$lodopt" calibrate --scene "$scene" --out "$out/$scene.json" --quiet --json > "$out/$scene-calibration.json"
  # shellcheck disable=SC2086
  "$lodopt" schedule --scene "$scene" $path --budget-ms "$budget" --stride "$stride" --render --no-fitness \
    --no-baseline --profile "$out/$scene.json" --out "$out/$scene-schedule" --quiet --json > "$out/$scene-summary.json"
  "$python" - "$scene" "$budget" "$out/$scene-summary.json" <<'PY'
import json, sys
scene, budget, path = sys.argv[1:4]
g = json.load(open(path))["goal_1"]
pct = lambda v: "n/a" if v is None else f"{100 * v:.1f}%"
ratio = "n/a" if g["of_ceiling"] is None else f"{g['of_ceiling']:.2f}"
print(f"{scene} {budget} ms: {pct(g['within_10_percent'])} of {g['binding_frames']} binding frames within ±10%, "
      f"ceiling {pct(g['ceiling'])}, {ratio} of the ceiling")
PY
done
