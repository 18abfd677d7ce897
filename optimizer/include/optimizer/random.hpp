// Deterministic random numbers for the algorithms.
//
// std::mt19937_64's output sequence is fixed by the standard, but the std distributions are
// not (libstdc++ and libc++ give different numbers for the same engine), so the distributions
// here are built from the raw 64-bit output: a result depends on the seed alone, on any
// platform. Each algorithm owns one Random seeded from its parameters; there is no global RNG.
#pragma once

#include <cassert>
#include <cstdint>
#include <random>

namespace lodopt::optimizer {

class Random {
public:
    explicit Random(std::uint64_t seed) : mEngine(seed) {}

    std::uint64_t next() { return mEngine(); }

    // Uniform in [0, 1): the top 53 bits scaled by 2^-53.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

    // Uniform in [low, high).
    double uniform(double low, double high) { return low + (high - low) * uniform(); }

    // Uniform integer in [0, n), n >= 1, by rejection (no modulo bias).
    std::uint64_t below(std::uint64_t n) {
        assert(n >= 1);
        const std::uint64_t limit = -n % n;  // 2^64 mod n: values below it are rejected
        for (;;) {
            const std::uint64_t value = next();
            if (value >= limit) return value % n;
        }
    }

    int belowInt(int n) { return static_cast<int>(below(static_cast<std::uint64_t>(n))); }

    // True with probability p (p <= 0: never, p >= 1: always).
    bool chance(double p) { return uniform() < p; }

private:
    std::mt19937_64 mEngine;
};

}  // namespace lodopt::optimizer
