// Procedural RGBA8 textures of the forest and city scenes, all tileable (uv wraps at 1) and
// deterministic from `seed`. Colours are display RGB in [0, 1]; every texture is opaque (the
// renderer has no alpha test). Sizes: `width`, `height` > 0 texels; coarser levels use
// smaller sizes of the same texture so texture bytes shrink with the level.
#pragma once

#include <cstdint>
#include <string>

#include "scenes/scene.hpp"

namespace lodopt::scenes::procedural {

// Bark along a cylinder: u around, v along the branch. `style`: 0 furrowed (oak), 1 plated
// (pine), 2 white with dark lenticel dashes (birch).
Texture makeBarkTexture(std::string name, int width, int height, glm::vec3 color, int style, std::uint32_t seed);
// A leaf-cluster card: the diamond's midrib runs along u = 0.5 from v = 0 (base) to v = 1.
Texture makeLeafTexture(std::string name, int size, glm::vec3 color, std::uint32_t seed);
// Clumpy foliage for crown hulls and billboards.
Texture makeFoliageTexture(std::string name, int size, glm::vec3 color, std::uint32_t seed);
// Grass with bare patches; `size` texels cover one uv repeat.
Texture makeGrassTexture(std::string name, int size, std::uint32_t seed);

// Level 0 of a building in one texture (size x 2 size): plaster in v in [0, 0.5) (light
// grey noise, tinted by the material, tiling along u) and one window bay of a recessed
// ribbon in [0.5, 1): a glass pane (sill at v = 0.5, head at v = 1) in a frame with a pier
// on each side, tiling along u once per bay.
Texture makePlasterAndWindowTexture(std::string name, int size, std::uint32_t seed);
// One facade bay (one window in its share of wall, one floor high): what level 1 and 2 of a
// building paint instead of modelling. Texel (0.02, 0.02) is wall: coarse roofs sample it.
Texture makeFacadeTexture(std::string name, int size, std::uint32_t seed);
// Flat roof gravel, and clay tiles (courses along v) for pitched roofs.
Texture makeGravelTexture(std::string name, int size, std::uint32_t seed);
Texture makeRoofTileTexture(std::string name, int size, std::uint32_t seed);
// Street surfaces.
Texture makeAsphaltTexture(std::string name, int size, std::uint32_t seed);
Texture makePavingTexture(std::string name, int size, std::uint32_t seed);

}  // namespace lodopt::scenes::procedural
