#!/usr/bin/env bash
# The default optimizer against the engine baseline (screensize) on every view of every
# built-in scene, at the same budget (docs/optimizer.md, "Against screensize"):
#   scripts/versus_screensize.sh [FRACTION] [SIZE]
# FRACTION (default 0.4) places the budget between the all-coarsest prediction (0) and the
# all-finest one (1). Prints one CSV row per view: scene, view, searched objects, budget,
# default optimizer's fitness and predicted time, screensize's, margin, seconds.
# Environment: LODOPT (default build/cli/lodopt), LODOPT_OUT (default out/versus_screensize),
# LODOPT_SCENES (default "harbor forest city"), LODOPT_ARGS (extra optimize options).
set -euo pipefail
cd "$(dirname "$0")/.."
fraction=${1:-0.4}
size=${2:-512x512}
lodopt=${LODOPT:-build/cli/lodopt}
out=${LODOPT_OUT:-out/versus_screensize}
mkdir -p "$out"

field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$@"; }

echo "scene,view,searched,budget_ms,default_fitness,default_ms,screensize_fitness,screensize_ms,margin,default_seconds"
for scene in ${LODOPT_SCENES:-harbor forest city}; do
  views=$("$lodopt" scene info "$scene" --json | python3 -c "import json,sys; print(' '.join(v['name'] for v in json.load(sys.stdin)['views']))")
  for view in $views; do
    dir="$out/$scene-$view"
    # The cheapest combination's prediction is in the budget error; the finest's in an unlimited run.
    low=$( ("$lodopt" optimize --scene "$scene" --view "$view" --size "$size" --budget-ms 1e-9 --algo screensize \
            --out "$dir/probe" --quiet 2>&1 || true) | sed -n 's/.*which is predicted at \([0-9.e+-]*\) ms.*/\1/p')
    [ -n "$low" ] || { echo "versus_screensize: no minimum for $scene/$view" >&2; exit 1; }
    "$lodopt" optimize --scene "$scene" --view "$view" --size "$size" --budget-ms 1e9 --algo screensize \
      --out "$dir/finest" --quiet >/dev/null
    high=$(field "$dir/finest/result.json" "d['predicted_ms']")
    budget=$(python3 -c "print($low + $fraction * ($high - $low))")
    # shellcheck disable=SC2086
    "$lodopt" optimize --scene "$scene" --view "$view" --size "$size" --budget-ms "$budget" \
      --out "$dir/default" --quiet ${LODOPT_ARGS:-} >/dev/null
    "$lodopt" optimize --scene "$scene" --view "$view" --size "$size" --budget-ms "$budget" --algo screensize \
      --out "$dir/screensize" --quiet >/dev/null
    python3 - "$scene" "$view" "$budget" "$dir" <<'EOF'
import json, sys
scene, view, budget, folder = sys.argv[1:]
a = json.load(open(folder + "/default/result.json"))
b = json.load(open(folder + "/screensize/result.json"))
print(f"{scene},{view},{a['skipped_objects']['searched_objects']},{float(budget):.3f},{a['fitness']:.5f},"
      f"{a['predicted_ms']:.3f},{b['fitness']:.5f},{b['predicted_ms']:.3f},{a['fitness'] - b['fitness']:+.5f},"
      f"{a['wall_seconds']:.1f}")
EOF
  done
done
