// Float64 references of the three metrics at their default parameters, written from the
// definitions in docs/metrics.md with OpenCV primitives and nothing shared with the metrics'
// own kernels. What "the float64 reference" means wherever the metrics are checked or
// benchmarked: tests/metrics/reference_values_test.cpp pins them to scikit-image and the
// script's values, `lodopt bench` and bench/metrics_bench report the metrics' deviation from
// them. Slow (allocates every image): never in a search.
//
// Defaults they implement: gray Y = 0.30 R + 0.59 G + 0.11 B (GAPSO15 §2; a 1-channel image is
// its own gray, alpha is ignored); SSIM (Wang et al. 2004) with an 11×11 Gaussian window of
// σ 1.5, population moments, C1 = (0.01·255)², C2 = (0.03·255)², the mean over valid windows;
// boundary entropy: Shannon entropy of the 256-bin histogram of the Sobel gradient magnitude
// over interior pixels, bins over [0, 255·√20]; information entropy: Shannon entropy of the
// 256-bin histogram of the gray level rounded half up (exactly: (30 R + 59 G + 11 B + 50) / 100
// in integers).
#pragma once

#include "metrics/metrics.hpp"

namespace lodopt::metrics::reference {

// `candidate` and `reference` of one size, at least 11×11, 1, 3 or 4 channels.
double ssim(const ImageView& candidate, const ImageView& reference);
// At least 3×3.
double boundaryEntropy(const ImageView& image);
double informationEntropy(const ImageView& image);
// GAPSO15's fused fitness with equal weights: (clamp(SSIM, 0, 1) + the two entropy
// fidelities 1 − |e − e_ref| / max(|e_ref|, 1e-6), clamped to [0, 1]) / 3.
double fitness(const ImageView& candidate, const ImageView& reference);

// Limits OpenCV to one thread for every later call, so that timing a reference compares like
// with like against the metrics (single-threaded). Process-wide.
void useOneThread();

}  // namespace lodopt::metrics::reference
