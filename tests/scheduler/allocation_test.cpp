// A warmed-up decision allocates nothing (scheduler.hpp's promise for Bounds features): every
// operator new of this test program is counted.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "fixtures.hpp"
#include "scheduler/scheduler.hpp"

namespace {
std::atomic<long> gAllocations{0};
}

void* operator new(std::size_t size) {
    ++gAllocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}

namespace lodopt::scheduler {
namespace {

TEST(Allocation, WarmDecisionsDoNotAllocate) {
    const scenes::Scene scene = testing::makeGridScene(6, 6, 5.0f);
    const SceneIndex index(scene, 96, 96, FeatureMode::Bounds);
    for (Organisation organisation : {Organisation::Flat, Organisation::Tiles}) {
        SchedulerParameters p;
        p.organisation = organisation;
        p.budgetMs = 4.0;
        FrameScheduler scheduler(index, testing::triangleModel(0.5, 1e-3), p);
        std::vector<scenes::Camera> path;
        for (int f = 0; f < 20; ++f) {
            path.push_back(testing::lookAt({-15.0f + 1.5f * float(f), 8, 22}, {0, 0, 0}));
        }
        for (const scenes::Camera& camera : path) scheduler.decide(camera, 0.0);  // warm up
        scheduler.reset();
        const long before = gAllocations.load();
        double sum = 0.0;
        for (std::size_t f = 0; f < path.size(); ++f) {
            const FrameDecision& d = scheduler.decide(path[f], f / 30.0);
            scheduler.reportMeasuredMs(d.predictedMs * 1.1);
            sum += d.predictedMs;
        }
        EXPECT_EQ(gAllocations.load() - before, 0) << toString(organisation);
        EXPECT_GT(sum, 0.0);
    }
}

}  // namespace
}  // namespace lodopt::scheduler
