#!/usr/bin/env python3
"""The table of scripts/peers.sh: per view, every algorithm's median gap to the best known
fitness at each evaluation budget, how many runs came within 1e-3 of it at the largest budget
(with their median evaluations to get there) and the median wall time at that budget.

usage: scripts/peers_table.py OUT   (OUT: the folders <scene>-<view>-<start>: -seeded for
gapso as optimize runs it, any other label for benches from a random start)

The best known fitness of a view is the larger of its two benches' (the exhaustive optimum on
the harbor); gaps and evaluations to within 1e-3 are recomputed against it from each run's
improvement curve in bench.json ("runs").
"""
import json
import statistics
import sys
from pathlib import Path


NEAR = 1e-3  # evaluation::kNearBestKnown


def load(folder):
    document = json.loads((folder / "bench.json").read_text())
    return document, document["runs"]


def evaluations_to_near(run, best):
    for evaluations, fitness in run["improvements"]:
        if fitness >= best - NEAR:
            return evaluations
    return None


def main(out):
    views = {}
    for folder in sorted(Path(out).iterdir()):
        if not (folder / "bench.json").exists():
            continue
        key, start = folder.name.rsplit("-", 1)
        views.setdefault(key, {})[start] = load(folder)
    for key, benches in views.items():
        best = max(document["best_known"]["fitness"] for document, _ in benches.values())
        source = next(iter(benches.values()))[0]["best_known"]["source"]
        first = next(iter(benches.values()))[0]
        budgets = first["evaluation_budgets"]
        top = budgets[-1]
        print(f"\n{first['scene']} / {first['view']}: {first['searched_objects']} searched objects, budget "
              f"{first['budget_ms']:.3f} ms, best known {best:.6f} ({source})")
        header = ["algorithm"] + [f"gap @{b}" for b in budgets] + [f"within 1e-3 @{top}", f"wall s @{top}"]
        print("| " + " | ".join(header) + " |")
        print("|" + "---|" * len(header))
        # Random-start runs first (a view's may be split over several folders), seeded last.
        groups = [("random", [run for label, (_, runs) in benches.items() if label != "seeded" for run in runs])]
        if "seeded" in benches:
            groups.append(("seeded", benches["seeded"][1]))
        for start, runs in groups:
            own = sorted(set(run["algorithm"] for run in runs))
            names = [n for n in ("gapso", "mckp") if n in own] + [n for n in own if n not in ("gapso", "mckp")]
            for name in names:
                label = name + (" (seeded, optimize's default)" if start == "seeded" else "")
                cells = [label]
                for budget in budgets:
                    gaps = [best - r["fitness"] for r in runs if r["algorithm"] == name and r["evaluation_budget"] == budget]
                    cells.append(f"{statistics.median(gaps):.2e}" if gaps else "-")
                last = [r for r in runs if r["algorithm"] == name and r["evaluation_budget"] == top]
                reached = [e for e in (evaluations_to_near(r, best) for r in last) if e is not None]
                near = f"{len(reached)}/{len(last)}"
                if reached:
                    near += f", median {statistics.median(reached):.0f} evals"
                cells.append(near)
                cells.append(f"{statistics.median(r['wall_seconds'] for r in last):.3f}")
                print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
