#!/usr/bin/env bash
# The sweep measurements of docs/sweep.md "Measured": one city sweep at 1 rank and at 2 ranks
# (mpirun, one evaluation thread per rank), peak memory per rank, the merged output's size, and
# the work queue modelled at 1-64 ranks over 10,000 views from the one-rank run's view times.
#   scripts/sweep_measure.sh [GRID] [OUT]      (default 10x10x2@80/-30, out/sweep-measure)
# 200 views over the city's core (--grid-box -400,-400,400,400) 80 m up, looking 30 degrees down,
# under 40 ms: some views see few buildings, some hundreds; the budget binds on some, a few are
# over it even at the coarsest levels.
# Environment: LODOPT (default build/cli/lodopt), LODOPT_SCENE (default city), LODOPT_BUDGET_MS
# (default 40), LODOPT_GRID_BOX (default -400,-400,400,400).
set -euo pipefail
cd "$(dirname "$0")/.."
grid=${1:-10x10x2@80/-30}
out=${2:-out/sweep-measure}
lodopt=${LODOPT:-build/cli/lodopt}
scene=${LODOPT_SCENE:-city}
budget=${LODOPT_BUDGET_MS:-40}
box=${LODOPT_GRID_BOX:--400,-400,400,400}
command -v mpirun >/dev/null || { echo "sweep_measure: mpirun not found (openmpi-bin)" >&2; exit 1; }
if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
rm -rf "$out"
mkdir -p "$out"
args=(sweep --scene "$scene" --grid "$grid" --grid-box="$box" --budget-ms "$budget" --threads 1 --quiet)
for ranks in 1 2; do
  dir="$out/ranks$ranks"
  launcher=()
  [ "$ranks" -gt 1 ] && launcher=(mpirun --oversubscribe -np "$ranks")
  # %M: the largest resident set of any one process (a rank) in KiB; %e: wall seconds.
  /usr/bin/time -f "ranks $ranks: wall %e s, peak RSS %M KiB" -o "$out/time$ranks.txt" \
    "${launcher[@]}" "$lodopt" "${args[@]}" --out "$dir" --json > "$out/summary$ranks.json"
  cat "$out/time$ranks.txt"
done
cmp "$out/ranks1/sweep.json" "$out/ranks2/sweep.json" && echo "sweep.json: the same bytes at 1 and 2 ranks"
python3 - "$out" <<'PY'
import csv, json, os, sys
out = sys.argv[1]
views = json.load(open(os.path.join(out, "ranks1", "sweep.json")))["views"]
size = os.path.getsize(os.path.join(out, "ranks1", "sweep.json"))
csv_size = os.path.getsize(os.path.join(out, "ranks1", "sweep.csv"))
print(f"merged output: {len(views)} views, sweep.json {size} B ({size / len(views):.0f} B/view), "
      f"sweep.csv {csv_size} B; at 10,000 views about {size / len(views) * 1e4 / 1e6:.0f} MB + "
      f"{csv_size / len(views) * 1e4 / 1e6:.0f} MB")
for ranks in (1, 2):
    run = json.load(open(os.path.join(out, f"ranks{ranks}", "sweep_run.json")))
    busy = {}
    for row in csv.DictReader(open(os.path.join(out, f"ranks{ranks}", "sweep_timing.csv"))):
        rank = int(row["rank"])
        busy.setdefault(rank, [0, 0.0])
        busy[rank][0] += 1
        busy[rank][1] += float(row["setup_seconds"]) + float(row["search_seconds"])
    wall = run["wall_seconds"]
    print(f"{ranks} rank(s): wall {wall:.1f} s (scene {run['scene_seconds']:.1f} s, merge {run['merge_seconds']:.2f} s); " +
          "; ".join(f"rank {r}: {n} views, busy {b:.1f} s, idle {wall - b:.1f} s" for r, (n, b) in sorted(busy.items())))
PY
"$lodopt" sweep --scaling "$out/ranks1" --scaling-views 10000
"$lodopt" sweep --scaling "$out/ranks1" --scaling-ranks 2
