#!/usr/bin/env bash
# What a profile predicts against what `render --time` measures (docs/timemodel.md "Measured
# agreement"): per scene and calibration seed, one default `lodopt calibrate`, then COMBOS random
# combinations (every object at a uniform level, a uniform named view; Python's random, seeded)
# predicted by `lodopt estimate --profile` and timed by `lodopt render --time --repeats 40`, in
# RENDER_PASSES passes over the combinations (default 3; pass 1 in the combinations' order, later
# passes shuffled), so that one slow spell of the machine does not decide a frame.
#   scripts/timing_agreement.sh [SCENES] [SEEDS] [COMBOS] [OUT]
#   defaults: "harbor forest city", "1 2 3", 24, out/timing-agreement
# Prints one line per calibration and writes OUT/agreement.md: what the calibration reported
# (held-out error, drift between its passes), then |estimate - render| / render (mean and p90)
# against the first pass's render --time (what one run of it gives) and against the median of
# the passes, the signed mean, how far render --time disagrees with itself (median over the
# combinations of (greatest - least) / median of its passes), `estimate --speed-probe` (made just
# before each render of the first pass) against that render with the probes' ratios, and the
# error against the median once one offset per calibration is divided out
# (scripts/timing_agreement_row.py makes each row). Run on a quiet machine.
# Environment: LODOPT (default build/cli/lodopt), LODOPT_CALIBRATE_ARGS (more calibrate options).
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=${1:-harbor forest city}
seeds=${2:-1 2 3}
combos=${3:-24}
render_passes=${RENDER_PASSES:-3}
out=${4:-out/timing-agreement}
lodopt=${LODOPT:-build/cli/lodopt}
python=${PYTHON:-/usr/bin/python3}
mkdir -p "$out"
table="$out/agreement.md"
{
  echo "| scene | seed | learned from | calibration held-out mean / p90 | every viewpoint out mean / p90 | pass drift | vs one render --time mean / p90 | vs median of the passes mean / p90 | --speed-probe vs one render --time mean / p90 | probe now / then, median (range) | signed mean | render --time spread | one offset removed mean / p90 (offset) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} > "$table"
for scene in $scenes; do
  "$lodopt" scene info --scene "$scene" --json > "$out/$scene-info.json"
  for seed in $seeds; do
    profile="$out/$scene-$seed.json"
    # shellcheck disable=SC2086
    "$lodopt" calibrate --scene "$scene" --seed "$seed" --out "$profile" --quiet --json \
      ${LODOPT_CALIBRATE_ARGS:-} > "$out/$scene-$seed-calibration.json"
    rows="$out/$scene-$seed-frames.tsv"
    : > "$rows"
    "$python" - "$out/$scene-info.json" "$seed" "$combos" > "$out/$scene-$seed-combos.txt" <<'PY'
import json, random, sys
info = json.load(open(sys.argv[1]))
rng = random.Random(1000 + int(sys.argv[2]))
views = [v["name"] for v in info["views"]]
counts = [len(o["levels"]) for o in info["objects"]]
for _ in range(int(sys.argv[3])):
    print(rng.choice(views), ",".join(str(rng.randrange(n)) for n in counts))
PY
    while read -r view levels; do
      predicted=$("$lodopt" estimate --profile "$profile" --scene "$scene" --view "$view" --levels "$levels" --json |
        "$python" -c 'import json,sys; print(json.load(sys.stdin)["predicted_ms"])')
      printf '%s\t%s\t%s\n' "$view" "$levels" "$predicted" >> "$rows"
    done < "$out/$scene-$seed-combos.txt"
    # One file per pass: line k is combination k's render --time.
    for pass in $(seq 1 "$render_passes"); do
      timed="$out/$scene-$seed-render-$pass.txt"
      rm -f "$timed.tmp" "$out/$scene-$seed-probed.tmp"
      "$python" -c 'import random,sys; n=int(sys.argv[1]); p=int(sys.argv[2]); o=list(range(n))
if p > 1: random.Random(p).shuffle(o)
print("\n".join(map(str, o)))' "$(wc -l < "$rows")" "$pass" |
        while read -r index; do
          IFS=$'\t' read -r view levels _ < <(sed -n "$((index + 1))p" "$rows")
          if [ "$pass" = 1 ]; then  # the same estimate with the machine's speed probed just before the render
            "$lodopt" estimate --profile "$profile" --scene "$scene" --view "$view" --levels "$levels" --speed-probe \
              --json < /dev/null | "$python" -c 'import json,sys; print(json.load(sys.stdin)["predicted_ms"])' \
              >> "$out/$scene-$seed-probed.tmp"
          fi
          measured=$("$lodopt" render --scene "$scene" --view "$view" --levels "$levels" --time --repeats 40 \
            --out "$out/frame.png" --json < /dev/null | "$python" -c 'import json,sys; print(json.load(sys.stdin)["render_ms"])')
          printf '%s\t%s\n' "$index" "$measured" >> "$timed.tmp"
        done
      if [ "$pass" = 1 ]; then mv "$out/$scene-$seed-probed.tmp" "$out/$scene-$seed-probed.txt"; fi
      sort -n "$timed.tmp" | cut -f2 > "$timed"
      rm -f "$timed.tmp"
    done
    "$python" scripts/timing_agreement_row.py "$scene" "$seed" "$out/$scene-$seed-calibration.json" "$rows" \
      "$out/$scene-$seed-probed.txt" "$out/$scene-$seed-render-"*.txt >> "$table"
    tail -1 "$table"
  done
done
echo "wrote $table"
