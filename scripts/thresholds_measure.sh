#!/usr/bin/env bash
# The held-out comparison of docs/thresholds.md "Measured": per built-in scene one sampled sweep
# (N views jittered around the scene's views, one evaluation thread), then `lodopt thresholds`
# on it (every 4th feasible view held out), and one table of the rules on the held-out views.
#   scripts/thresholds_measure.sh [VIEWS] [OUT]      (default 96, out/thresholds-measure)
# Budgets: harbor 7 ms, forest 20 ms, city 40 ms (each binds on most views; some views are over
# it even at the coarsest levels and are left out of the fit). --fov 45: the sampled views mix
# 45 and 60 degrees, the distances need one. Sweeps are resumed when OUT holds them already.
# Environment: LODOPT (default build/cli/lodopt), LODOPT_THRESHOLDS_ARGS (more thresholds options).
set -euo pipefail
cd "$(dirname "$0")/.."
views=${1:-96}
out=${2:-out/thresholds-measure}
lodopt=${LODOPT:-build/cli/lodopt}
mkdir -p "$out"
rm -f "$out/time.txt"
table="$out/held_out.md"
{
  echo "| scene | views (fit / held out) | rule | lod bias | mean fitness | gain fraction | over budget | mean ms |"
  echo "|---|---|---|---|---|---|---|---|"
} > "$table"
for entry in harbor:7 forest:20 city:40; do
  scene=${entry%%:*}
  budget=${entry##*:}
  "$lodopt" sweep --scene "$scene" --view-count "$views" --budget-ms "$budget" --threads 1 --quiet \
    --out "$out/$scene-sweep" --resume > /dev/null
  # shellcheck disable=SC2086
  /usr/bin/time -f "$scene thresholds: wall %e s, peak RSS %M KiB" -a -o "$out/time.txt" \
    "$lodopt" thresholds --from "$out/$scene-sweep" --out "$out/$scene" --fov 45 --quiet --json \
    ${LODOPT_THRESHOLDS_ARGS:-} > "$out/$scene.json"
  python3 - "$out/$scene.json" "$scene" >> "$table" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
ref = s["held_out_reference"]
fmt = lambda v, p: "n/a" if v is None else f"{v:.{p}f}"
views = f'{s["fitting_views"]} / {s["held_out_views"]}'
for row in s["held_out"]:
    print(f'| {sys.argv[2]} | {views} | {row["rule"]} | {row["lod_bias"]:.4g} | {fmt(row["mean_fitness"], 4)} | '
          f'{fmt(row["gain_fraction"], 3)} | {fmt(row["over_budget_share"], 2)} | {fmt(row["mean_predicted_ms"], 2)} |')
print(f'| {sys.argv[2]} | {views} | (optimizer) | | {fmt(ref["optimizer_mean_fitness"], 4)} | 1 | 0 | |')
print(f'| {sys.argv[2]} | {views} | (all coarsest) | | {fmt(ref["coarsest_mean_fitness"], 4)} | 0 | | |')
PY
done
cat "$table"
cat "$out/time.txt"
