#include "visibility.hpp"

#include <algorithm>

namespace lodopt::evaluation::detail {

VisibilityBounds::VisibilityBounds(const ViewSetup& setup)
    : mBounds(std::size_t(setup.width()) * std::size_t(setup.height())) {
    const int width = setup.width(), height = setup.height();
    std::vector<float> farthest;  // per pixel of the object's levels' union rectangle
    std::vector<int> covering;    // how many of its levels cover the pixel
    for (std::size_t o = 0; o < setup.objects().size(); ++o) {
        const ObjectSetup& object = setup.objects()[o];
        std::vector<int> levels = object.optionLevels;
        if (object.skip != SkipReason::None || levels.empty()) levels = {object.fixedLevel};
        renderer::PixelRect unionRect{width, height, 0, 0};
        for (int level : levels) {
            const renderer::PixelRect& r = setup.layer(int(o), level).rect;
            if (r.empty()) continue;
            unionRect = {std::min(unionRect.x0, r.x0), std::min(unionRect.y0, r.y0), std::max(unionRect.x1, r.x1),
                         std::max(unionRect.y1, r.y1)};
        }
        unionRect = {std::max(unionRect.x0, 0), std::max(unionRect.y0, 0), std::min(unionRect.x1, width),
                     std::min(unionRect.y1, height)};
        if (unionRect.empty()) continue;
        const int unionWidth = unionRect.width();
        farthest.assign(std::size_t(unionWidth) * unionRect.height(), 0.0f);
        covering.assign(farthest.size(), 0);
        for (int level : levels) {
            const renderer::Layer& layer = setup.layer(int(o), level);
            const renderer::PixelRect& r = layer.rect;
            for (int y = std::max(r.y0, unionRect.y0); y < std::min(r.y1, unionRect.y1); ++y) {
                const float* depth = layer.occluderDepth().data() + std::size_t(y - r.y0) * r.width();
                const std::size_t row = std::size_t(y - unionRect.y0) * unionWidth;
                for (int x = std::max(r.x0, unionRect.x0); x < std::min(r.x1, unionRect.x1); ++x) {
                    const float d = depth[x - r.x0];
                    if (!(d < 1.0f)) continue;
                    const std::size_t at = row + std::size_t(x - unionRect.x0);
                    ++covering[at];
                    farthest[at] = std::max(farthest[at], d);
                }
            }
        }
        // Only where every level covers the pixel is the object sure to be there.
        for (int y = unionRect.y0; y < unionRect.y1; ++y) {
            for (int x = unionRect.x0; x < unionRect.x1; ++x) {
                const std::size_t at = std::size_t(y - unionRect.y0) * unionWidth + std::size_t(x - unionRect.x0);
                if (covering[at] == int(levels.size())) mBounds.offer(std::size_t(y) * width + x, farthest[at], int(o));
            }
        }
    }
}

}  // namespace lodopt::evaluation::detail
