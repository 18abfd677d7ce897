// The independent judge: Butteraugli (Alakuijala, Obryk, Szabadka et al., Google; the libjxl
// implementation, Debian's libjxl 0.7 C API `jxl/butteraugli.h`), a model of human vision that
// scores how visibly a candidate image differs from a reference.
//
// lodopt's search optimizes the fused fitness (metrics.hpp); a score the search optimizes is no
// evidence of its own quality, so every answer lodopt keeps is also scored by this judge, which
// no search ever reads (docs/metrics.md "The judge"). Butteraugli converts both images from
// sRGB to linear light, to its opsin (cone) space, and compares them band by band with masking;
// the result is a per-pixel distance map. Distances are in "just noticeable differences": about
// 1.0 is the largest difference a viewer does not notice under the stated viewing conditions;
// 0 for identical images; larger is worse. The map is pooled by a p-norm (the 3-norm, as
// `butteraugli_main --pnorm 3` prints, weighs the whole image; the maximum weighs the single
// worst place).
//
// Viewing conditions are parameters: the display's intensity target (nits) and how many display
// pixels one image pixel stands for (a 512-pixel render shown as a 1024-pixel window is scale 2;
// butteraugli's contrast sensitivity is tuned to a viewing distance in display pixels).
#pragma once

#include <vector>

#include "metrics/metrics.hpp"

namespace lodopt::metrics {

struct JudgeParameters {
    // > 0, nits: the display's white. 80 is libjxl's and butteraugli_main's default (an sRGB
    // office display).
    double intensityTargetNits = 80.0;
    // > 0: how much more a lost high-frequency detail counts than an added one (butteraugli's
    // hf_asymmetry). 0.8 is what butteraugli_main uses, so the figures equal that tool's.
    double hfAsymmetry = 0.8;
    // >= 1: the p of the p-norm pooling the distance map. 3, butteraugli_main's --pnorm 3.
    double pnorm = 3.0;
    // 1..16: display pixels per image pixel on each axis; the image is enlarged by pixel
    // replication before judging. 1: one image pixel is one display pixel. An image with a side
    // under 8 pixels is enlarged at least until that side reaches 8 (butteraugli gives 0 below).
    int displayScale = 1;
    // Keep the distance map in JudgeResult::distanceMap (image pixels, rows top to bottom).
    bool keepDistanceMap = false;
};

// Throws MetricError naming the first field out of its stated range.
void validateJudgeParameters(const JudgeParameters& parameters);

struct JudgeResult {
    double distance = 0;     // the p-norm of the distance map, >= 0, 0 for identical images
    double maxDistance = 0;  // the largest value of the map, >= distance
    // With keepDistanceMap: width * height values (display pixels averaged back to image
    // pixels when displayScale > 1), else empty.
    std::vector<float> distanceMap;
    int width = 0;
    int height = 0;
};

// Butteraugli distance of `candidate` from `reference`: same width, height and channel count
// (1 gray, 3 RGB, 4 RGBA; alpha is ignored: renders are opaque), 8-bit sRGB-encoded as stored.
// Throws MetricError for images or parameters it cannot use (naming both sizes or the field),
// std::runtime_error when libjxl fails.
JudgeResult judge(const ImageView& candidate, const ImageView& reference, const JudgeParameters& parameters = {});

}  // namespace lodopt::metrics
