// Timing one context's frames (renderer.hpp FrameTimes, FrameClock): the GL_TIME_ELAPSED query,
// which clock is the frame's time, the one-time warm-up and the timed draws. Private to the
// renderer; the context must be current for every call (the Renderer activates it first).
#pragma once

#include <functional>
#include <string>

#include "gl_common.hpp"
#include "renderer/renderer.hpp"

namespace lodopt::renderer {

class FrameTimer {
public:
    // Creates the query where the driver's timer has counter bits and resolves `requested` for the
    // renderer named `glRenderer`; throws RenderError for FrameClock::GpuTimer without a timer.
    FrameTimer(FrameClock requested, const std::string& glRenderer);
    // Deletes the query (context current).
    void release();

    FrameClock clock() const { return mClock; }
    bool hasQuery() const { return mQuery != 0; }

    // The first call of a context's timing: `drawAndReadBack` once, then `draw` (draw + glFinish)
    // until at least kWarmUpDraws and kWarmUpSeconds have passed. On llvmpipe a context's draws are
    // slower until its first read-back (about twice: harbor 256x192, 11-17 ms before, 6 ms after,
    // AMD EPYC), and its first dozen draws after that alternate between two speeds; a command
    // that times one frame right after start (render --time) would time that instead of what a
    // running application sees (docs/renderer.md "Timing"). Later calls do nothing.
    void warmUpOnce(const std::function<void()>& drawAndReadBack, const std::function<void()>& draw);

    // `warmup` untimed calls of `draw`, then `repeats` timed ones (each followed by glFinish).
    FrameTimes time(const std::function<void()>& draw, int repeats, int warmup);

private:
    static constexpr int kWarmUpDraws = 12;
    static constexpr double kWarmUpSeconds = 0.25;
    GLuint mQuery = 0;  // GL_TIME_ELAPSED; 0 when the driver's timer has no counter bits
    FrameClock mClock = FrameClock::Wall;
    bool mWarmedUp = false;
};

}  // namespace lodopt::renderer
