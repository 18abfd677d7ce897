// Helpers of the fast path's exactness tests: random walks of level changes, a from-scratch
// composite to score them against, and a bit-for-bit comparison of scores.
#pragma once

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "evaluation/evaluation.hpp"

namespace lodopt::test_walks {

inline metrics::ImageView viewOf(const renderer::Frame& frame) {
    return metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4);
}

// The combination's image composited from scratch, independent of any evaluator state.
inline renderer::Frame freshComposite(const evaluation::ViewSetup& setup, const optimizer::Combination& combination) {
    const scenes::Combination levels = setup.toScene(combination);
    std::vector<const renderer::Layer*> layers;
    for (std::size_t o = 0; o < levels.size(); ++o) layers.push_back(&setup.layer(int(o), levels[o]));
    renderer::Frame frame;
    renderer::composite(layers, setup.width(), setup.height(), setup.clearColor(), frame);
    return frame;
}

inline void expectSameScore(const optimizer::Score& a, const optimizer::Score& b, const std::string& what) {
    EXPECT_EQ(a.fitness, b.fitness) << what;
    ASSERT_EQ(a.componentCount, b.componentCount) << what;
    for (int c = 0; c < a.componentCount; ++c) EXPECT_EQ(a.components[c], b.components[c]) << what << " component " << c;
}

// A random walk: each step sets 1–3 random variables to random options (sometimes their
// current one, so some steps change nothing). Every few steps a large jump changes half.
inline std::vector<optimizer::Combination> randomWalk(const std::vector<int>& counts, int steps, unsigned seed) {
    std::mt19937 random(seed);
    std::vector<optimizer::Combination> walk;
    optimizer::Combination current(counts.size(), 0);
    for (int k = 0; k < steps; ++k) {
        const int changes = k % 25 == 24 ? int(counts.size()) / 2 : 1 + int(random() % 3);
        for (int c = 0; c < changes; ++c) {
            const std::size_t v = random() % counts.size();
            current[v] = int(random() % counts[v]);
        }
        walk.push_back(current);
    }
    return walk;
}

}  // namespace lodopt::test_walks
