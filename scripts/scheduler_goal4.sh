#!/usr/bin/env bash
# The scheduler's Goal 4 as docs/scheduler.md states it: switches per frame with switch control
# (hysteresis, the default, and vmi20) against none, at equal mean fitness. Deterministic: the
# shipped profiles, --no-feedback (decisions equal a run without rendering), --repeats 1.
#   scripts/scheduler_goal4.sh [OUT]        (default out/scheduler-goal4)
# Per scene and rule: the first N frames rendered for fitness (city 60 ms, N = 300; forest 30 ms,
# N = 360; harbor 8 ms along the spiral approach of scripts/scheduler_goal1.sh, N = 300), then the
# whole path without rendering. Prints one table row per scene. Environment: LODOPT (default
# build/cli/lodopt).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/scheduler-goal4}
lodopt=${LODOPT:-build/cli/lodopt}
python=${PYTHON:-/usr/bin/python3}
mkdir -p "$out"
"$python" scripts/harbor_approach.py "$out/harbor_approach.json"
for entry in "city:60:300:" "forest:30:360:" "harbor:8:300:--path $out/harbor_approach.json"; do
  IFS=: read -r scene budget frames path <<< "$entry"
  for rule in none hysteresis vmi20; do
    case "$rule" in
      none) control=--no-switch-control ;;
      *) control="--switch-rule $rule" ;;
    esac
    # shellcheck disable=SC2086
    "$lodopt" schedule --scene "$scene" $path --budget-ms "$budget" $control --render --no-feedback \
      --frames "$frames" --no-baseline --repeats 1 --noise-probe 0 --out "$out/$scene-$rule-rendered" --quiet \
      --json > "$out/$scene-$rule-rendered.json"
    # shellcheck disable=SC2086
    "$lodopt" schedule --scene "$scene" $path --budget-ms "$budget" $control --no-baseline \
      --out "$out/$scene-$rule-path" --quiet --json > "$out/$scene-$rule-path.json"
  done
  "$python" - "$out" "$scene" "$frames" <<'PY'
import json, sys
out, scene, frames = sys.argv[1:4]
load = lambda rule, kind: json.load(open(f"{out}/{scene}-{rule}-{kind}.json"))
rendered = {r: load(r, "rendered") for r in ("none", "hysteresis", "vmi20")}
path = {r: load(r, "path") for r in ("none", "hysteresis", "vmi20")}
per = lambda s: s["switches"]["per_frame"]
fit = lambda s: s["fitness"]["mean"]
n, h, v = (rendered[r] for r in ("none", "hysteresis", "vmi20"))
pn, ph, pv = (path[r] for r in ("none", "hysteresis", "vmi20"))
print(f"| {scene}, 0–{int(frames) - 1} | {per(n):.2f} | **{per(h):.2f} ({per(h) / per(n):.2f})** | {per(v):.2f} ({per(v) / per(n):.2f}) "
      f"| {fit(n):.4f} / **{fit(h):.4f} ({100 * (fit(h) / fit(n) - 1):+.1f}%)** / {fit(v):.4f} ({100 * (fit(v) / fit(n) - 1):+.1f}%) "
      f"| {per(pn):.2f} / **{per(ph):.2f} ({per(ph) / per(pn):.2f})** / {per(pv):.2f} ({per(pv) / per(pn):.2f}) |")
PY
done
