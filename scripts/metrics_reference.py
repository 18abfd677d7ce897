#!/usr/bin/python3
"""Reference values for tests/metrics/reference_values_test.cpp, computed independently.

Run with Debian's Python (it has scikit-image): /usr/bin/python3 scripts/metrics_reference.py
It prints the values pinned in the test. SSIM comes from scikit-image's
structural_similarity (gaussian_weights=True, sigma, use_sample_covariance=False,
data_range=255); the information entropy from skimage.measure.shannon_entropy; the other
components from the definitions in docs/metrics.md written again with numpy/scipy.

  --float32-check  reproduces the measurement behind "float64, not float32" in docs/metrics.md.

The image generator below is mirrored exactly (integer arithmetic only) by
generateScene/generateNoise in tests/metrics/test_images.hpp.
"""
import math
import sys

import numpy as np
from scipy import ndimage
from skimage.measure import shannon_entropy
from skimage.metrics import structural_similarity

M = 0xFFFFFFFF
BACKGROUND = (158, 194, 230, 255)
GRAY_WEIGHTS = {"paper": ((30, 59, 11), 100), "bt601": ((299, 587, 114), 1000), "bt709": ((2126, 7152, 722), 10000)}


def hash32(x, y, c, seed):
    h = (x * 374761393 + y * 668265263 + c * 2246822519 + seed * 3266489917) & M
    h = ((h ^ (h >> 13)) * 1274126177) & M
    return h ^ (h >> 16)


def scene(width, height, channels, seed, shift):
    """Sky background, a shaded box and a disk, light noise on the objects."""
    img = np.zeros((height, width, channels), dtype=np.uint8)
    cx, cy = (13 * width) // 20, (9 * height) // 20
    radius = min(width, height) // 5 - (1 if shift else 0)
    for y in range(height):
        for x in range(width):
            color = list(BACKGROUND)
            covered = False
            if width // 5 + shift <= x < width // 2 + shift and height // 4 <= y < (3 * height) // 4:
                color = [(40 + 3 * x) % 200, (90 + 2 * y) % 150, 60, 255]
                covered = True
            if (x - cx) ** 2 + (y - cy) ** 2 <= radius * radius:
                color = [230 - 2 * (x - cx + radius), 120 + (y - cy), 30 + x % 17, 255]
                covered = True
            if covered:
                for c in range(3):
                    color[c] = min(255, max(0, color[c] + int(hash32(x, y, c, seed) % 7) - 3))
            if channels == 1:  # the paper's gray, rounded: the background becomes 187
                img[y, x, 0] = (30 * color[0] + 59 * color[1] + 11 * color[2] + 50) // 100
            else:
                img[y, x, :] = color[:channels]
    return img


def noise(width, height, channels, seed):
    img = np.zeros((height, width, channels), dtype=np.uint8)
    for y in range(height):
        for x in range(width):
            for c in range(channels):
                img[y, x, c] = hash32(x, y, c, seed) & 255
    return img


def scaled_gray(img, weights):
    (wr, wg, wb), scale = GRAY_WEIGHTS[weights]
    i = img.astype(np.int64)
    if img.shape[2] == 1:
        return i[:, :, 0] * scale, scale
    return wr * i[:, :, 0] + wg * i[:, :, 1] + wb * i[:, :, 2], scale


def ssim(cand, ref, weights="paper", sigma=1.5):
    x, s = scaled_gray(cand, weights)
    y, _ = scaled_gray(ref, weights)
    return structural_similarity(x / s, y / s, gaussian_weights=True, sigma=sigma,
                                 use_sample_covariance=False, data_range=255)


def entropy_of_counts(counts):
    counts = counts[counts > 0].astype(np.float64)
    p = counts / counts.sum()
    return float(-(p * np.log2(p)).sum())


def boundary_entropy(img, bins=256, weights="paper"):
    g, s = scaled_gray(img, weights)
    if g.shape[0] < 3 or g.shape[1] < 3:
        return 0.0
    kx = np.array([[-1, 0, 1], [-2, 0, 2], [-1, 0, 1]])
    gx = ndimage.correlate(g, kx)[1:-1, 1:-1]
    gy = ndimage.correlate(g, kx.T)[1:-1, 1:-1]
    magnitude = np.sqrt((gx * gx + gy * gy).astype(np.float64))
    scale = bins / (255.0 * math.sqrt(20.0) * s)
    index = np.minimum((magnitude * scale).astype(np.int64), bins - 1)
    return entropy_of_counts(np.bincount(index.ravel(), minlength=bins))


def information_entropy(img, weights="paper"):
    g, s = scaled_gray(img, weights)
    rounded = (g + s // 2) // s
    return float(shannon_entropy(rounded, base=2))


def boundary_entropy_paper(img, weights="paper"):
    g, s = scaled_gray(img, weights)
    a = (g[:-1, :-1] - g[1:, 1:]).astype(np.float64)
    b = (g[1:, :-1] - g[:-1, 1:]).astype(np.float64)
    m = np.sqrt(a * a + b * b) / s
    m = m[m > 0]
    return float(-(m * np.log2(m)).sum())


def information_entropy_paper(img, weights="paper"):
    g, _ = scaled_gray(img, weights)
    total = g.sum()
    if total == 0:
        return 0.0
    p = g[g > 0].astype(np.float64) / total
    return float(-(p * np.log2(p)).sum())


def precision_recall(cand, ref, tolerance=8):
    bg = np.array(BACKGROUND[:cand.shape[2]], dtype=np.int64)
    if cand.shape[2] == 1:
        (wr, wg, wb), s = GRAY_WEIGHTS["paper"]
        bg = np.array([(wr * BACKGROUND[0] + wg * BACKGROUND[1] + wb * BACKGROUND[2] + s // 2) // s])
    c = cand.astype(np.int64)
    r = ref.astype(np.int64)
    cov_c = (c != bg).any(axis=2)
    cov_r = (r != bg).any(axis=2)
    match = np.abs(c - r).max(axis=2) <= tolerance
    tp = cov_c & cov_r & match
    return int(tp.sum()), int((cov_c & ~tp).sum()), int((cov_r & ~tp).sum())


def float32_check():
    """Mean SSIM with float32 statistics versus float64, valid windows, separable Gaussian."""
    k = np.exp(-0.5 * (np.arange(-5, 6) / 1.5) ** 2)
    k /= k.sum()

    def filt(a, dt):
        kk = k.astype(dt)
        a = a.astype(dt)
        h = np.zeros((a.shape[0], a.shape[1] - 10), dt)
        for i in range(11):
            h += kk[i] * a[:, i:i + a.shape[1] - 10]
        v = np.zeros((a.shape[0] - 10, h.shape[1]), dt)
        for i in range(11):
            v += kk[i] * h[i:i + a.shape[0] - 10, :]
        return v

    def mean_ssim(x, y, dt):
        x, y = x.astype(dt), y.astype(dt)
        ux, uy, uxx, uyy, uxy = filt(x, dt), filt(y, dt), filt(x * x, dt), filt(y * y, dt), filt(x * y, dt)
        c1, c2 = dt(2.55 ** 2), dt(7.65 ** 2)
        s = ((2 * ux * uy + c1) * (2 * (uxy - ux * uy) + c2)) / ((ux * ux + uy * uy + c1) * (uxx - ux * ux + uyy - uy * uy + c2))
        return s.astype(np.float64).mean()

    rng = np.random.default_rng(1)
    yy, xx = np.mgrid[0:512, 0:512]
    smooth = (127 + 120 * np.sin(xx / 20.0) * np.cos(yy / 30.0)).round()
    bright = 250 + rng.integers(-2, 3, (512, 512)).astype(np.float64)
    cases = {
        "noise": (np.clip((n := rng.integers(0, 256, (512, 512)).astype(np.float64)) + rng.normal(0, 20, n.shape), 0, 255).round(), n),
        "smooth": (np.clip(smooth + rng.normal(0, 3, smooth.shape), 0, 255).round(), smooth),
        "bright flat, +-2 noise": (250 + rng.integers(-2, 3, (512, 512)).astype(np.float64), bright),
    }
    for name, (x, y) in cases.items():
        d = mean_ssim(x, y, np.float64)
        f = mean_ssim(x, y, np.float32)
        print(f"{name:>24}: float64 {d:.15f}  float32 - float64 = {f - d:+.3e}")


def main():
    if "--float32-check" in sys.argv:
        float32_check()
        return
    ref = scene(64, 48, 3, 1, 0)
    cand = scene(64, 48, 3, 2, 2)
    gray_ref = scene(50, 40, 1, 3, 0)
    gray_cand = scene(50, 40, 1, 4, 2)
    noise_ref = noise(40, 33, 3, 5)
    noise_cand = noise(40, 33, 3, 6)
    rgba_ref = scene(31, 27, 4, 7, 0)
    rgba_cand = scene(31, 27, 4, 8, 2)
    out = {
        "kSceneSsimPaper": ssim(cand, ref),
        "kSceneSsimBt601": ssim(cand, ref, "bt601"),
        "kSceneSsimBt709": ssim(cand, ref, "bt709"),
        "kSceneSsimSigma1": ssim(cand, ref, sigma=1.0),
        "kGraySsim": ssim(gray_cand, gray_ref),
        "kNoiseSsim": ssim(noise_cand, noise_ref),
        "kRgbaSsim": ssim(rgba_cand, rgba_ref),
        "kSceneBoundaryReference": boundary_entropy(ref),
        "kSceneBoundaryCandidate": boundary_entropy(cand),
        "kSceneBoundary64Bins": boundary_entropy(cand, bins=64),
        "kSceneBoundaryBt709": boundary_entropy(cand, weights="bt709"),
        "kNoiseBoundary": boundary_entropy(noise_ref),
        "kGrayBoundary": boundary_entropy(gray_ref),
        "kSceneInformationReference": information_entropy(ref),
        "kSceneInformationCandidate": information_entropy(cand),
        "kSceneInformationBt601": information_entropy(cand, "bt601"),
        "kNoiseInformation": information_entropy(noise_ref),
        "kGrayInformation": information_entropy(gray_ref),
        "kSceneBoundaryPaper": boundary_entropy_paper(ref),
        "kSceneInformationPaper": information_entropy_paper(ref),
    }
    for name, value in out.items():
        print(f"constexpr double {name} = {value!r};")
    for name, (c, r) in {"kScene": (cand, ref), "kGray": (gray_cand, gray_ref), "kRgba": (rgba_cand, rgba_ref)}.items():
        tp, fp, fn = precision_recall(c, r)
        print(f"// {name} TP/FP/FN")
        print(f"constexpr std::uint64_t {name}Counts[3] = {{{tp}, {fp}, {fn}}};")


if __name__ == "__main__":
    main()
