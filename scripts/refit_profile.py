#!/usr/bin/env python3
"""Refit a device profile's linear model on feature subsets, offline.

Usage: scripts/refit_profile.py [--statistic STATISTIC] PROFILE.json [PROFILE.json ...]

Reads the samples a `lodopt calibrate` profile stores (features, times by the statistic named:
median (the default: what every profile predicts), least-median, least or cpu; a profile written
before the median was the predicted quantity names them wall-median, wall-min-median, wall-min;
held-out flags, viewpoints) and, for the default feature set and each variant with one feature left
out, fits the `linear` model the way timemodel does (non-negative least squares on relative
residuals, intercept included) and prints the held-out mean / p90 of |t_act - t_est| / t_act,
and the same for leave-one-viewpoint-out cross-validation over the fitted viewpoints. An
analysis aid (docs/timemodel.md): needs python3-numpy (Debian), not part of the build.
"""
import json
import sys

import numpy as np

DEFAULT = ['vertices', 'triangles', 'texture_bytes', 'draw_calls', 'pixels', 'drawn_objects',
           'visible_triangles', 'raster_pixels', 'edge_pixels', 'shaded_pixels', 'textured_pixels',
           'shaded_edge_pixels', 'partial_blocks', 'shaded_partial_blocks']


def nnls(a, b, sweeps=3000):
    """Projected coordinate descent; the problems here have ~11 columns."""
    x = np.zeros(a.shape[1])
    ata, atb = a.T @ a, a.T @ b
    for _ in range(sweeps):
        before = x.copy()
        for j in range(len(x)):
            if ata[j, j] > 0:
                x[j] = max(0.0, (atb[j] - ata[j] @ x + ata[j, j] * x[j]) / ata[j, j])
        if np.abs(x - before).max() < 1e-12:
            break
    return x


def predict(design, times, train):
    a = design[train] / times[train, None]
    scale = np.abs(a).max(0)
    scale[scale == 0] = 1
    return design @ (nnls(a / scale, np.ones(train.sum())) / scale)


def evaluate(profile, columns):
    names = profile['feature_names']
    samples = profile['samples']
    x = np.array([s['features'] for s in samples])
    t = np.array([s[CLOCK_FIELD] if CLOCK_FIELD in s else s[OLDER_NAMES[CLOCK_FIELD]] for s in samples])
    held = np.array([s['held_out'] for s in samples])
    view = np.array([s['viewpoint'] for s in samples])
    columns = [c for c in columns if c in names]  # profiles older than a feature lack it
    design = np.column_stack([np.ones(len(t))] + [x[:, names.index(c)] for c in columns])
    error = np.abs(predict(design, t, ~held) - t) / t
    cv = []
    for v in sorted(set(view[~held])):
        p = predict(design, t, (~held) & (view != v))
        cv.extend(np.abs(p[view == v] - t[view == v]) / t[view == v])
    cv = np.array(cv)
    return error[held].mean(), np.percentile(error[held], 90), cv.mean(), np.percentile(cv, 90)


CLOCK_FIELD = 'median_ms'
OLDER_NAMES = {'median_ms': 'wall_median_ms', 'least_median_ms': 'wall_min_median_ms', 'least_ms': 'wall_min_ms'}


def main():
    global CLOCK_FIELD
    paths = sys.argv[1:]
    if len(paths) >= 2 and paths[0] == '--statistic':
        CLOCK_FIELD = paths[1].replace('-', '_') + '_ms'
        paths = paths[2:]
    if not paths:
        sys.exit(__doc__)
    for path in paths:
        profile = json.load(open(path))
        present = [c for c in DEFAULT if c in profile['feature_names']]
        variants = [('default', present)] + [('without ' + c, [d for d in present if d != c]) for c in present]
        print(path)
        for label, columns in variants:
            m, p90, cvm, cvp90 = evaluate(profile, columns)
            print(f'  {label:28s} held-out {m * 100:5.1f}% / {p90 * 100:5.1f}%   '
                  f'leave-one-viewpoint-out {cvm * 100:5.1f}% / {cvp90 * 100:5.1f}%')


if __name__ == '__main__':
    main()
