#!/usr/bin/env python3
"""Replays the measured-time feedback (DONG15 eq. 9) of recorded `lodopt schedule --render` runs
with other gains: how well each gain would have predicted the frames, and what share of the
binding frames would have been measured in the budget's band.
    scripts/feedback_replay.py [--betas 0.1,0.3,0.5,0.7,0.9] [--json] RUN_DIR [RUN_DIR ...]
RUN_DIR: a schedule's --out folder (frames.csv, summary.json).

Per frame, the model's own prediction before feedback is predicted_ms / the scale the frame was
decided with (the previous row's feedback_scale; 1 for the first), so measured / that prediction
is what any gain sees. Each gain's scale is replayed with the library's bounds (relative error
clamped to ±1, scale kept in [1/4, 4]). A frame counts in the band when
predicted_ms / budget x measured / (replayed prediction) is within ±10%: the replay keeps each
frame's decision and its place under the budget, and the binding frames (budget reachable,
all-finest predicted over it) as recorded. Decisions made with another scale would differ; the
replay ranks gains, a rendered run measures one. At the gain the run used, the replay gives the
run's own `goal_1.within_10_percent`: the check that the reconstruction is right."""
import csv
import json
import os
import sys

MAX_RELATIVE_ERROR = 1.0  # timemodel::FeedbackParameters
MAX_DRIFT = 4.0


def load(run_dir):
    with open(os.path.join(run_dir, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(run_dir, "frames.csv")) as f:
        rows = list(csv.DictReader(f))
    if not rows or not summary.get("measured_ms"):
        sys.stderr.write(f"{run_dir}: not a rendered schedule (no measured frames)\n")
        sys.exit(2)
    budget = float(summary["budget_ms"])
    frames, scale_before = [], 1.0
    for row in rows:
        predicted, measured = float(row["predicted_ms"]), float(row["measured_ms"])
        frames.append({
            "model_ms": predicted / scale_before,
            "place": predicted / budget,
            "measured_ms": measured,
            "binding": row["budget_reachable"] == "1" and float(row["finest_predicted_ms"]) > budget,
        })
        scale_before = float(row["feedback_scale"])
    return summary, frames


def lag1_autocorrelation(values):
    mean = sum(values) / len(values)
    var = sum((v - mean) ** 2 for v in values)
    return sum((a - mean) * (b - mean) for a, b in zip(values, values[1:])) / var if var > 0 else None


def replay(frames, beta):
    scale, errors, in_band, binding = 1.0, [], 0, 0
    for frame in frames:
        ratio = frame["measured_ms"] / (frame["model_ms"] * scale)  # measured / this gain's prediction
        errors.append(abs(ratio - 1.0))
        if frame["binding"]:
            binding += 1
            in_band += abs(frame["place"] * ratio - 1.0) <= 0.1  # measured / budget, had the decision sat here
        relative = max(-MAX_RELATIVE_ERROR, min(MAX_RELATIVE_ERROR, ratio - 1.0))
        scale = max(1.0 / MAX_DRIFT, min(MAX_DRIFT, scale * (1.0 + beta * relative)))
    return {"beta": beta, "mean_error": sum(errors) / len(errors),
            "binding_frames": binding, "within_10_percent": in_band / binding if binding else None}


def main(argv):
    betas, as_json, dirs = [0.1, 0.3, 0.5, 0.7, 0.9], False, []
    args = iter(argv)
    for a in args:
        if a == "--betas":
            betas = [float(v) for v in next(args).split(",")]
        elif a == "--json":
            as_json = True
        else:
            dirs.append(a)
    if not dirs or not all(0.0 < b < 1.0 for b in betas):
        sys.stderr.write(__doc__ + "\n")
        sys.exit(2)
    results = []
    for run_dir in dirs:
        summary, frames = load(run_dir)
        results.append({"run": run_dir, "scene": summary.get("scene"), "budget_ms": summary["budget_ms"],
                        "recorded_beta": summary.get("feedback_beta"),
                        "recorded_within_10_percent": summary["goal_1"]["within_10_percent"],
                        # Near 1: the model's miss wanders slowly (the machine's speed), and the
                        # last frames predict the next; near 0: it is noise a gain can only chase.
                        "ratio_lag1_autocorrelation": lag1_autocorrelation([f["measured_ms"] / f["model_ms"] for f in frames]),
                        "replays": [replay(frames, b) for b in betas]})
    if as_json:
        print(json.dumps(results, indent=2))
        return
    print("| run | scene, budget | binding | lag-1 | recorded (β) | " + " | ".join(f"β {b:g}" for b in betas) + " |")
    print("|---|---|---|---|---|" + "---|" * len(betas))
    pct = lambda v: "n/a" if v is None else f"{100 * v:.1f}%"
    for r in results:
        cells = [f"{pct(x['within_10_percent'])} ({100 * x['mean_error']:.1f}%)" for x in r["replays"]]
        beta = "?" if r["recorded_beta"] is None else f"{r['recorded_beta']:g}"
        lag1 = r["ratio_lag1_autocorrelation"]
        print(f"| {r['run']} | {r['scene']}, {r['budget_ms']:g} ms | {r['replays'][0]['binding_frames']} | "
              f"{'n/a' if lag1 is None else f'{lag1:.2f}'} | "
              f"{pct(r['recorded_within_10_percent'])} ({beta}) | " + " | ".join(cells) + " |")
    print("\nlag-1: autocorrelation of measured / the model's prediction before feedback, frame to frame;"
          "\ncells: binding frames within ±10% of the budget (mean |measured / predicted - 1| over all frames)")


if __name__ == "__main__":
    main(sys.argv[1:])
