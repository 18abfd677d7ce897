#!/usr/bin/env python3
"""One row of scripts/timing_agreement.sh's table, from the files it wrote for one calibration:
    scripts/timing_agreement_row.py SCENE SEED CALIBRATION.json FRAMES.tsv PROBED.txt RENDER-1.txt [RENDER-2.txt ...]
FRAMES.tsv: view, levels, estimate per combination; PROBED.txt: `estimate --speed-probe` per
combination, made just before its first render ("-" or a missing file: not recorded); RENDER-k.txt:
pass k's `render --time` per combination. Errors are |estimate - render| / render, mean / p90."""
import json
import os
import statistics
import sys

scene, seed, calibration, rows, probed_path = sys.argv[1:6]
passes = [[float(v) for v in open(path)] for path in sys.argv[6:]]
c = json.load(open(calibration))
linear = next(m for m in c["models"] if m["name"] == "linear")
predicted = [float(line.split("\t")[2]) for line in open(rows)]


def q(values, f):
    values = sorted(values)
    x = f * (len(values) - 1)
    i = int(x)
    return values[i] if i + 1 >= len(values) else values[i] + (x - i) * (values[i + 1] - values[i])


def errors(estimates, measured):
    return [abs(p - m) / m for p, m in zip(estimates, measured)]


pct = lambda v: f"{100 * v:.1f}"
mp = lambda e: f"**{pct(sum(e) / len(e))} / {pct(q(e, 0.9))}**"
medians = [statistics.median(times) for times in zip(*passes)]
signed = [(p - m) / m for p, m in zip(predicted, medians)]
spread = [(max(t) - min(t)) / statistics.median(t) for t in zip(*passes)]
# One factor per calibration divided out: how well the model ranks the frames, whatever the
# machine's speed in the minutes of the renders against the minutes of the calibration.
offset = statistics.median(p / m for p, m in zip(predicted, medians))
without_offset = errors([p / offset for p in predicted], medians)
if os.path.exists(probed_path):
    probed = [float(v) for v in open(probed_path)]  # in the combinations' order, as pass 1
    ratios = [b / a for a, b in zip(predicted, probed)]  # the probes' now / then
    probe = f"{mp(errors(probed, passes[0]))} | {statistics.median(ratios):.2f} ({min(ratios):.2f}-{max(ratios):.2f})"
else:
    probe = "n/a | n/a"
h, r = linear["held_out_errors"], linear["rotated_held_out_errors"]
drift = c.get("pass_drift")
print(f"| {scene} | {seed} | {c['learned_from']} x {c['learned_scale']:.3f} | {pct(h['mean'])} / {pct(h['p90'])} | "
      f"{pct(r['mean'])} / {pct(r['p90'])} | {'n/a' if drift is None else pct(drift)} | "
      f"{mp(errors(predicted, passes[0]))} | {mp(errors(predicted, medians))} | {probe} | "
      f"{pct(sum(signed) / len(signed))} | {pct(statistics.median(spread))} | {mp(without_offset)} ({offset:.3f}) |")
