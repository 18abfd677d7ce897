#!/usr/bin/python3
"""How often image indexes rank answers as the judge (butteraugli) does.

  /usr/bin/python3 scripts/fusion_agreement.py DIR [DIR ...]

Each DIR holds optimize output folders DIR/CASE/FRACTION/ANSWER/ (result.json with its "judge",
optimized.png, reference.png), as scripts/versus_engine_rules.sh writes them. Answers of one CASE
(a scene's view) that hold the same combination count once. For every index below and every pair
of different answers of a case whose judge distances differ by more than 0.1 %, the pair agrees
when the index prefers the answer the judge finds closer to the reference. Prints, per index, the
share of agreeing pairs and on how many cases the index's best answer is the judge's best.
An analysis aid for docs/metrics.md "The judge" (docs/results.md §16), not part of the build;
needs Debian's python3-numpy, python3-scipy, python3-skimage and python3-pil.

Indexes (gray = 0.30 R + 0.59 G + 0.11 B, as lodopt's default):
  fused        lodopt's default fusion: mean of SSIM, global Sobel-histogram boundary-entropy
               fidelity and global gray-histogram information-entropy fidelity (docs/metrics.md)
  ssim         mean SSIM (11x11 Gaussian, sigma 1.5, valid windows)
  ssim_pP      SSIM pooled as 1 - (mean of (1 - SSIM)^P)^(1/P): the worst places weigh more
  fused_pP     the fusion with ssim_pP in place of the mean SSIM
  tileT        the entropy fidelities per TxT tile (16 bins), averaged, fused with the mean SSIM
  tileT_p3     the same fused with ssim_p3
  gmsd         minus the gradient-magnitude similarity deviation (Xue et al. 2014)
  psnr         minus the mean squared error of RGB
"""
import glob
import itertools
import json
import os
import sys

import numpy as np
from PIL import Image
from scipy import ndimage
from skimage.metrics import structural_similarity

SOBEL_RANGE = (0.0, 255.0 * np.sqrt(20.0))


def load(path):
    return np.asarray(Image.open(path).convert("RGB")).astype(np.float64)


def gray(image):
    return 0.30 * image[..., 0] + 0.59 * image[..., 1] + 0.11 * image[..., 2]


def ssim_map(a, b):
    _, full = structural_similarity(a, b, gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                                    data_range=255, full=True)
    return np.clip(full[5:-5, 5:-5], -1.0, 1.0)


def sobel(g):
    return np.hypot(ndimage.sobel(g, axis=1), ndimage.sobel(g, axis=0))[1:-1, 1:-1]


def entropy(values, bins, value_range):
    counts, _ = np.histogram(values, bins=bins, range=value_range)
    p = counts[counts > 0] / counts.sum()
    return float(-(p * np.log2(p)).sum())


def fidelity(candidate, reference):
    if reference < 1e-6 and candidate < 1e-6:
        return 1.0
    return max(0.0, 1.0 - abs(candidate - reference) / max(reference, 1e-6))


def tiled_fidelity(reference, candidate, tile, value_range):
    height, width = reference.shape
    values = [fidelity(entropy(candidate[y:y + tile, x:x + tile], 16, value_range),
                       entropy(reference[y:y + tile, x:x + tile], 16, value_range))
              for y in range(0, height - tile + 1, tile) for x in range(0, width - tile + 1, tile)]
    return float(np.mean(values))


def indexes(reference, candidate):
    gr, gc = gray(reference), gray(candidate)
    dissimilarity = 1.0 - ssim_map(gr, gc)
    sr, sc = sobel(gr), sobel(gc)
    boundary = fidelity(entropy(sc, 256, SOBEL_RANGE), entropy(sr, 256, SOBEL_RANGE))
    information = fidelity(entropy(gc, 256, (0, 256)), entropy(gr, 256, (0, 256)))
    out = {"ssim": 1.0 - dissimilarity.mean()}
    out["fused"] = (out["ssim"] + boundary + information) / 3
    for p in (2, 3, 4, 6):
        pooled = 1.0 - np.mean(dissimilarity ** p) ** (1.0 / p)
        out[f"ssim_p{p}"] = pooled
        out[f"fused_p{p}"] = (pooled + boundary + information) / 3
    for tile in (16, 32):
        entropies = tiled_fidelity(sr, sc, tile, SOBEL_RANGE) + tiled_fidelity(gr, gc, tile, (0, 256))
        out[f"tile{tile}"] = (out["ssim"] + entropies) / 3
        out[f"tile{tile}_p3"] = (out["ssim_p3"] + entropies) / 3
    c = 0.0026 * 255 * 255
    out["gmsd"] = -float(((2 * sr * sc + c) / (sr * sr + sc * sc + c)).std())
    out["psnr"] = -float(np.mean((reference - candidate) ** 2))
    return out


def main(folders):
    cases = {}
    for folder in folders:
        for path in glob.glob(os.path.join(folder, "*", "*", "*", "result.json")):
            result = json.load(open(path))
            if not result.get("judge"):
                continue
            answer = os.path.dirname(path)
            case = os.path.relpath(os.path.dirname(os.path.dirname(answer)), folder)
            cases.setdefault(case, {})[tuple(result["combination"])] = (result["judge"]["butteraugli"], answer)
    agreeing, pairs, best = {}, 0, {}
    for case, answers in sorted(cases.items()):
        reference = load(os.path.join(next(iter(answers.values()))[1], "reference.png"))
        scored = [(judge, indexes(reference, load(os.path.join(folder, "optimized.png"))))
                  for judge, folder in answers.values()]
        for (ja, ia), (jb, ib) in itertools.combinations(scored, 2):
            if abs(ja - jb) <= 1e-3 * max(ja, jb):
                continue
            pairs += 1
            for name in ia:
                agreeing[name] = agreeing.get(name, 0) + int(ia[name] != ib[name] and (ia[name] > ib[name]) == (ja < jb))
        judge_best = min(judge for judge, _ in scored)
        for name in scored[0][1]:
            pick = max(scored, key=lambda item: item[1][name])[0]
            best[name] = best.get(name, 0) + int(pick <= judge_best * 1.0001)
    print(f"{len(cases)} cases, {pairs} pairs of answers the judge tells apart")
    print("index,agreeing_pairs,share,best_is_judges_best")
    for name in sorted(agreeing, key=lambda n: -agreeing[n]):
        print(f"{name},{agreeing[name]},{agreeing[name] / max(pairs, 1):.3f},{best[name]}/{len(cases)}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
