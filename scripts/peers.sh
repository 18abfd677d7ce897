#!/usr/bin/env bash
# lodopt's searches against pagmo2's optimizers at equal evaluation budgets (docs/optimizer.md,
# "Peers: pagmo2"; docs/results.md §11):
#   scripts/peers.sh [SEEDS] [EVALS]
# On the harbor's overview (against its exhaustive optimum), the forest's four views and the
# city's aerial view, one `lodopt bench` per view with every pagmo algorithm, gapso and mckp from
# a random start, then one with gapso as `optimize` runs it (--seed-from screensize,mckp), all at
# the budget bench picks (midway between the all-coarsest and all-finest prediction). Prints the
# table of scripts/peers_table.py. Each bench resumes where an interrupted one stopped.
# Environment: LODOPT (default build/cli/lodopt), LODOPT_OUT (default out/peers),
# LODOPT_VIEWS (default "harbor:overview forest:0 forest:1 forest:2 forest:3 city:aerial").
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-10}
evals=${2:-100,300,1000,3000}
lodopt=${LODOPT:-build/cli/lodopt}
out=${LODOPT_OUT:-out/peers}
pagmo=$("$lodopt" optimize --help | tr ' ,' '\n\n' | grep '^pagmo:' | sort -u | paste -sd, -)
[ -n "$pagmo" ] || { echo "peers: $lodopt was built without pagmo2 (libpagmo-dev)" >&2; exit 1; }
for entry in ${LODOPT_VIEWS:-harbor:overview forest:0 forest:1 forest:2 forest:3 city:aerial}; do
  scene=${entry%%:*} view=${entry#*:}
  for start in random seeded; do
    dir="$out/$scene-$view-$start"
    if [ "$start" = random ]; then algos="gapso,mckp,$pagmo" from=none; else algos=gapso from=screensize,mckp; fi
    resume=""
    [ -f "$dir/bench.checkpoint.json" ] && resume=--resume
    [ -f "$dir/bench.json" ] && continue
    echo "peers: $scene / $view, $start start" >&2
    "$lodopt" bench --scene "$scene" --view "$view" --algos "$algos" --seed-from "$from" --evals "$evals" \
      --seeds "$seeds" --quiet --out "$dir" $resume >/dev/null
  done
done
python3 scripts/peers_table.py "$out"
