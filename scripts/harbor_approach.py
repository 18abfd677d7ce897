#!/usr/bin/env python3
"""The harbor's approach path for the scheduler's goal scripts: 300 frames (10 s at 30 fps), a
spiral from 250 m out and 45 m up to 35 m and 9 m around the ship, looking at (0, 4, 0).
    scripts/harbor_approach.py OUT.json"""
import json
import math
import sys

frames = []
for f in range(300):
    t = f / 299
    r, h, a = 250 - 215 * t, 45 - 36 * t, math.radians(135 + 270 * t)
    frames.append({"position": [r * math.cos(a), h, r * math.sin(a)], "target": [0, 4, 0], "near": 0.5, "far": 1500})
with open(sys.argv[1], "w") as out:
    json.dump({"name": "approach", "frames_per_second": 30, "frames": frames}, out)
