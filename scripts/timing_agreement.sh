#!/usr/bin/env bash
# What a profile predicts against what `render --time` measures (docs/timemodel.md "Measured
# agreement"): per scene and calibration seed, one default `lodopt calibrate`, then COMBOS random
# combinations (every object at a uniform level, a uniform named view; Python's random, seeded)
# predicted by `lodopt estimate --profile` and timed by `lodopt render --time --repeats 40`.
#   scripts/timing_agreement.sh [SCENES] [SEEDS] [COMBOS] [OUT]
#   defaults: "harbor forest city", "1 2 3", 24, out/timing-agreement
# Prints one line per calibration (mean and p90 of |estimate - render| / render, the signed
# mean, and what the calibration reported) and writes OUT/agreement.md. Run on a quiet machine.
# Environment: LODOPT (default build/cli/lodopt), LODOPT_CALIBRATE_ARGS (more calibrate options).
set -euo pipefail
cd "$(dirname "$0")/.."
scenes=${1:-harbor forest city}
seeds=${2:-1 2 3}
combos=${3:-24}
out=${4:-out/timing-agreement}
lodopt=${LODOPT:-build/cli/lodopt}
python=${PYTHON:-/usr/bin/python3}
mkdir -p "$out"
table="$out/agreement.md"
{
  echo "| scene | seed | learned from | calibration held-out mean / p90 | every viewpoint out mean / p90 | estimate vs render --time mean / p90 | signed mean |"
  echo "|---|---|---|---|---|---|---|"
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
      measured=$("$lodopt" render --scene "$scene" --view "$view" --levels "$levels" --time --repeats 40 \
        --out "$out/frame.png" --json | "$python" -c 'import json,sys; print(json.load(sys.stdin)["render_ms"])')
      printf '%s\t%s\t%s\t%s\n' "$view" "$levels" "$predicted" "$measured" >> "$rows"
    done < "$out/$scene-$seed-combos.txt"
    "$python" - "$scene" "$seed" "$out/$scene-$seed-calibration.json" "$rows" >> "$table" <<'PY'
import json, sys
scene, seed, calibration, rows = sys.argv[1:5]
c = json.load(open(calibration))
linear = next(m for m in c["models"] if m["name"] == "linear")
errors, signed = [], []
for line in open(rows):
    view, levels, predicted, measured = line.split("\t")
    p, m = float(predicted), float(measured)
    errors.append(abs(p - m) / m)
    signed.append((p - m) / m)
errors.sort()
def q(values, f):
    x = f * (len(values) - 1)
    i = int(x)
    return values[i] if i + 1 >= len(values) else values[i] + (x - i) * (values[i + 1] - values[i])
h, r = linear["held_out_errors"], linear["rotated_held_out_errors"]
pct = lambda v: f"{100 * v:.1f}"
print(f"| {scene} | {seed} | {c['learned_from']} x {c['learned_scale']:.3f} | {pct(h['mean'])} / {pct(h['p90'])} | "
      f"{pct(r['mean'])} / {pct(r['p90'])} | **{pct(sum(errors) / len(errors))} / {pct(q(errors, 0.9))}** | "
      f"{pct(sum(signed) / len(signed))} |")
PY
    tail -1 "$table"
  done
done
echo "wrote $table"
