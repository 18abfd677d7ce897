// Procedural buildings with three discrete levels of detail for the built-in city scene
// (the three-level building LODs of CITY17 and HYBRID14: detailed model → block → box).
//
//   level 0: modelled facade. Each storey is a flush spandrel (plaster) below a ribbon of
//            windows recessed kWindowRecess into the facade, with sill and head reveals;
//            the window bay repeats once per bay. A flat roof gets a cornice, a parapet, a
//            gravel slab and a rooftop plant room; a gable or hip roof gets eaves, gable
//            walls and a chimney. Two draw calls: walls with windows (one texture holding
//            plaster and the window bay), roof.
//   level 1: block with roof. Four walls painted with a facade texture (one window per
//            bay and storey, aligned with level 0's bays), and the roof simplified (gable
//            and hip keep their planes, flat keeps the slab and the plant room). Two draw
//            calls: facade, roof.
//   level 2: box. Four walls and a top (no bottom) with a 16x16 facade texture; the top
//            samples the texture's wall colour. One draw call.
// Object space: footprint centred on the origin, x in [-width/2, width/2], z in
// [-depth/2, depth/2], ground at y = 0.
#pragma once

#include <vector>

#include "procedural.hpp"
#include "scenes/scene.hpp"

namespace lodopt::scenes::city {

enum class RoofShape { Flat, Gable, Hip };

inline constexpr float kWindowRecess = 0.3f;  // metres
inline constexpr int kBuildingLevels = 3;

struct BuildingSpec {
    float width = 12.0f;             // x extent, metres, >= 4
    float depth = 12.0f;             // z extent, metres, >= 4
    int floors = 3;                  // >= 1
    float floorHeight = 3.2f;        // metres, upper storeys
    float groundFloorHeight = 4.2f;  // metres
    RoofShape roof = RoofShape::Flat;
    float roofRise = 0.0f;      // ridge above the eaves, metres (gable and hip)
    float bayWidth = 2.8f;      // target window bay width, metres
    glm::vec2 plantRoom{0.0f};  // rooftop plant room offset from the roof centre (flat roofs)
    glm::vec2 chimney{0.0f};    // chimney offset (pitched roofs)
};

// Height of the walls (top of the last storey), metres.
float wallHeight(const BuildingSpec& spec);

// Materials a building's levels draw with (indices into Scene::materials).
struct BuildingMaterials {
    int wall = -1;         // level 0 walls, windows, reveals, cornice, parapet (plaster + window bay)
    int roof = -1;         // levels 0-1 roof surfaces (gravel or tiles)
    int facade = -1;       // level 1 walls (facade bay texture)
    int facadeSmall = -1;  // level 2 (16x16 facade bay texture)
};

// Meshes the kBuildingLevels levels of a building (statistics are not filled in).
std::vector<Level> buildBuildingLevels(const BuildingSpec& spec, const BuildingMaterials& materials);

}  // namespace lodopt::scenes::city
