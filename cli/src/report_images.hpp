// Pictures of how a candidate rendering differs from the reference, for `lodopt report`.
//
// SSIM map: metrics::ssimMap (the same windows, weights and constants as the fitness) of the
// candidate against the reference, one value per valid 11x11 window, placed at its window's
// centre so the map lines up with the renders; the (window - 1) / 2 pixel border that no valid
// window is centred on is drawn mid-gray. Colours: magma from dark (the scale's low end) to
// pale yellow (SSIM 1). The low end adapts to the image: the lowest map value rounded down to
// a multiple of 0.05, never above 0.9 (so that near-identical images do not amplify noise into
// colour) and never below -1.
// Difference heat map: per pixel the largest |candidate - reference| over R, G and B
// (0..255), in inferno from black (equal) to pale yellow (the scale's high end: the largest
// difference in the image, at least 16 gray levels).
#pragma once

#include <string>

#include "metrics/judge.hpp"
#include "renderer/renderer.hpp"

namespace lodopt::cli {

// An 8-bit image file as RGBA (gray → R = G = B, alpha 255). Throws UsageError naming the
// file when it cannot be read.
renderer::Frame loadRgbaImage(const std::string& path);

struct DifferenceMaps {
    renderer::Frame ssimMap;     // the candidate's size, colour-coded (see the file comment)
    double meanSsim = 0.0;       // metrics::ssim of the pair
    double ssimLow = 0.0;        // SSIM at the dark end of the colour scale
    renderer::Frame difference;  // the candidate's size, colour-coded
    int differenceHigh = 0;      // difference (gray levels) at the bright end of the scale
    double changedShare = 0.0;   // share of pixels with any channel difference, [0, 1]
    int largestDifference = 0;   // 0..255
};
// `candidate` and `reference` must have the same size (else UsageError naming `what`).
DifferenceMaps differenceMaps(const renderer::Frame& candidate, const renderer::Frame& reference,
                              const std::string& what);

// The judge's distance map of `candidate` against `reference` (metrics::judge), colour-coded
// with inferno from 0 to `high` (the map's largest value rounded up, at least 1: about one
// just-noticeable difference). Same sizes as differenceMaps requires.
struct JudgeMap {
    renderer::Frame heat;
    double distance = 0.0;     // the p-norm
    double maxDistance = 0.0;  // the map's largest value
    double high = 1.0;         // distance at the bright end of the scale
};
JudgeMap judgeMap(const renderer::Frame& candidate, const renderer::Frame& reference,
                  const metrics::JudgeParameters& parameters, const std::string& what);

// The colour scales as CSS linear-gradient stops, for the page's legends.
std::string magmaCss();
std::string infernoCss();

}  // namespace lodopt::cli
