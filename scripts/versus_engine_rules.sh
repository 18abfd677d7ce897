#!/usr/bin/env bash
# The default optimizer against the rules an engine gives for free, at the same per-view budget,
# judged by butteraugli (docs/metrics.md "The judge"; docs/results.md "Against the engines' rules"):
#   scripts/versus_engine_rules.sh [FRACTIONS] [SIZE]
# FRACTIONS (default "0.4"; e.g. "0.3 0.4 0.5") place each view's budget between its all-coarsest
# prediction (0) and its all-finest one (1). Rules: screensize, distance, pixelerror (Godot's
# projected-error rule), unreal-auto (Unreal's auto screen size), each at the bias that meets the
# budget. Prints one CSV row per view, fraction and answer: the fused fitness, the predicted time
# and the judge's 3-norm (lower is better), then a summary per scene and over all: views where the
# default looks at least as good as the best rule to the judge (wins, ties within 0.001, losses),
# the mean margin (best rule's judge minus the default's; positive favours the default) with a
# seeded 95 % bootstrap interval, and how many answers were over their budget (0 by construction).
# Environment: LODOPT (default build/cli/lodopt), LODOPT_OUT (default out/versus_engine_rules),
# LODOPT_SCENES (default "harbor forest city"; a glTF path works too), LODOPT_ARGS (extra options).
set -euo pipefail
cd "$(dirname "$0")/.."
fractions=${1:-0.4}
size=${2:-512x512}
lodopt=${LODOPT:-build/cli/lodopt}
out=${LODOPT_OUT:-out/versus_engine_rules}
rules="screensize distance pixelerror unreal-auto"
mkdir -p "$out"

echo "scene,view,fraction,budget_ms,answer,fitness,predicted_ms,butteraugli"
for scene in ${LODOPT_SCENES:-harbor forest city}; do
  tag=$(basename "$scene" | sed 's/\.[a-z]*$//')
  views=$("$lodopt" scene info "$scene" --json | python3 -c "import json,sys; print(' '.join(v['name'] for v in json.load(sys.stdin)['views']))")
  for view in $views; do
    dir="$out/$tag-$view"
    # The cheapest combination's prediction is in the budget error; the finest's in an unlimited run.
    low=$( ("$lodopt" optimize --scene "$scene" --view "$view" --size "$size" --budget-ms 1e-9 --algo screensize \
            --no-judge --out "$dir/probe" --quiet 2>&1 || true) | sed -n 's/.*which is predicted at \([0-9.e+-]*\) ms.*/\1/p')
    [ -n "$low" ] || { echo "versus_engine_rules: no minimum for $scene/$view" >&2; exit 1; }
    "$lodopt" optimize --scene "$scene" --view "$view" --size "$size" --budget-ms 1e9 --algo screensize \
      --no-judge --out "$dir/finest" --quiet >/dev/null
    high=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['predicted_ms'])" "$dir/finest/result.json")
    for fraction in $fractions; do
      budget=$(python3 -c "print($low + $fraction * ($high - $low))")
      for answer in default $rules; do
        algo=()
        [ "$answer" = default ] || algo=(--algo "$answer")
        # shellcheck disable=SC2086
        "$lodopt" optimize --scene "$scene" --view "$view" --size "$size" --budget-ms "$budget" "${algo[@]}" \
          --out "$dir/$fraction/$answer" --quiet ${LODOPT_ARGS:-} >/dev/null
        python3 - "$tag" "$view" "$fraction" "$budget" "$answer" "$dir/$fraction/$answer/result.json" <<'PY'
import json, sys
scene, view, fraction, budget, answer, path = sys.argv[1:]
r = json.load(open(path))
print(f"{scene},{view},{fraction},{float(budget):.4f},{answer},{r['fitness']:.5f},{r['predicted_ms']:.4f},"
      f"{r['judge']['butteraugli']:.4f}")
PY
      done
    done
  done
done | tee "$out/rows.csv"

python3 - "$out/rows.csv" <<'PY'
import collections, random, statistics, sys
rows = [line.strip().split(",") for line in open(sys.argv[1]) if line.strip() and not line.startswith("scene,")]
cases = collections.defaultdict(dict)
for scene, view, fraction, budget, answer, fitness, ms, judge in rows:
    cases[(scene, view, fraction)][answer] = (float(fitness), float(judge), float(ms) <= float(budget) * (1 + 1e-9))
by_scene = collections.defaultdict(list)
over_budget = 0
for (scene, view, fraction), answers in cases.items():
    over_budget += sum(1 for fitness, judge, within in answers.values() if not within)
    best_rule = min(judge for name, (fitness, judge, within) in answers.items() if name != "default")
    by_scene[scene].append(best_rule - answers["default"][1])
by_scene["all"] = [m for scene in list(by_scene) for m in by_scene[scene]]


def interval(margins, draws=2000):
    """95 % bootstrap interval of the mean (seeded: the same figures every run)."""
    generator = random.Random(1)
    means = sorted(statistics.fmean(generator.choices(margins, k=len(margins))) for _ in range(draws))
    return means[int(0.025 * draws)], means[int(0.975 * draws) - 1]


# A tie: the judge distances differ by at most 0.1 % of the default's.
print("scene,cases,default_at_least_as_good,wins,ties,losses,mean_judge_margin,margin_95_low,margin_95_high")
for scene, margins in by_scene.items():
    ties = sum(1 for m in margins if abs(m) <= 1e-3 * 1.0)
    wins = sum(1 for m in margins if m > 1e-3)
    losses = sum(1 for m in margins if m < -1e-3)
    low, high = interval(margins)
    print(f"{scene},{len(margins)},{wins + ties},{wins},{ties},{losses},{statistics.fmean(margins):+.4f},"
          f"{low:+.4f},{high:+.4f}")
print(f"answers over their budget: {over_budget}")
PY
