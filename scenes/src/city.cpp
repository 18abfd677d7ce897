// The built-in city: about 1,250 buildings with three LODs each (city_building.hpp) on a
// 12 x 12 grid of blocks, with a ground object, street-level and aerial viewpoints and a
// fly-through path (the urban scenes of CITY17 and HYBRID14, scaled to a software renderer).
//
// Layout, deterministic from the seed:
//  - streets: 13 per axis, 14 m wide, the middle one of each axis a 26 m avenue; blocks are
//    64 m (x) by 44 m (z) with a 3 m sidewalk; the city spans about 962 m x 722 m;
//  - ground: asphalt under the grid, block plinths with curbs (paving, or lawn for parks),
//    avenue centre lines, and open land out to 2 km; a second level without curbs and lines;
//  - parks: 4-6 blocks away from the avenues are lawns without buildings;
//  - lots: each block has two rows of 4-5 lots (so >= 8 buildings a block and >= 1,104 in
//    all); a building fills its lot's frontage less a gap and 11-17 m of its depth;
//  - heights: storeys ~ 2 + 28 exp(-(r / 0.3)^2) with r the distance from the centre over
//    450 m, times a random 0.6-1.4, and a few towers; low buildings (<= 5 storeys) get gable
//    or hip roofs 60% of the time, the rest flat roofs with parapets;
//  - palettes: six wall tints; each tint has its own wall (plaster and windows), facade and small
//    facade materials (the textures are shared).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>

#include "city_building.hpp"
#include "procedural.hpp"
#include "procedural_textures.hpp"
#include "scenes/builtin.hpp"

namespace lodopt::scenes {

namespace {

using city::BuildingSpec;
using city::RoofShape;
using procedural::Rng;

constexpr int kBlocks = 12;                // per axis
constexpr float kStreetWidth = 14.0f;      // metres
constexpr float kAvenueWidth = 26.0f;      // metres, the middle street of each axis
constexpr int kAvenueIndex = kBlocks / 2;  // street index of the avenue
constexpr float kBlockX = 64.0f, kBlockZ = 44.0f;
constexpr float kSidewalk = 3.0f;
constexpr float kCurbHeight = 0.15f;
constexpr float kLandExtent = 2000.0f;  // half size of the ground plane, metres
constexpr int kFlyFrames = 900;         // 30 s at 30 fps
constexpr float kFlyFramesPerSecond = 30.0f;

enum Stream : std::uint64_t { kParkStream = 1, kBlockStreamBase = 1000 };

constexpr std::array<glm::vec3, 6> kTints = {{{0.95f, 0.89f, 0.76f},
                                              {0.78f, 0.50f, 0.40f},
                                              {0.76f, 0.77f, 0.79f},
                                              {0.97f, 0.97f, 0.95f},
                                              {0.90f, 0.75f, 0.52f},
                                              {0.64f, 0.72f, 0.82f}}};

// Street centre lines and block extents along one axis.
struct Grid {
    std::array<float, kBlocks + 1> streetCenter;
    std::array<float, kBlocks> blockMin, blockMax;
    float extent = 0.0f;  // half the total size
};

Grid makeGrid(float blockSize) {
    Grid grid;
    float total = 0.0f;
    for (int s = 0; s <= kBlocks; ++s) total += s == kAvenueIndex ? kAvenueWidth : kStreetWidth;
    total += float(kBlocks) * blockSize;
    grid.extent = 0.5f * total;
    float x = -grid.extent;
    for (int s = 0; s <= kBlocks; ++s) {
        float width = s == kAvenueIndex ? kAvenueWidth : kStreetWidth;
        grid.streetCenter[std::size_t(s)] = x + 0.5f * width;
        x += width;
        if (s < kBlocks) {
            grid.blockMin[std::size_t(s)] = x;
            x += blockSize;
            grid.blockMax[std::size_t(s)] = x;
        }
    }
    return grid;
}

struct CityMaterials {
    std::array<city::BuildingMaterials, 2 * kTints.size()> building;  // [tint * 2 + pitched]
    int asphalt = -1, paving = -1, grass = -1, marking = -1;
    int asphaltSmall = -1, pavingSmall = -1, grassSmall = -1;
};

CityMaterials addCityMaterials(Scene& scene, std::uint32_t seed) {
    auto addTexture = [&](Texture texture) { return procedural::addTexture(scene, std::move(texture)); };
    auto addMaterial = [&](std::string name, glm::vec3 color, int texture) {
        return procedural::addDiffuseMaterial(scene, std::move(name), color, texture);
    };
    const int wall = addTexture(procedural::makePlasterAndWindowTexture("plaster_window_bay", 64, seed));
    const int facade = addTexture(procedural::makeFacadeTexture("facade_bay", 64, seed + 2u));
    const int facadeSmall = addTexture(procedural::makeFacadeTexture("facade_bay_small", 16, seed + 2u));
    const int gravel = addTexture(procedural::makeGravelTexture("roof_gravel", 64, seed + 3u));
    const int tiles = addTexture(procedural::makeRoofTileTexture("roof_tiles", 64, seed + 4u));
    CityMaterials m;
    const int roofFlat = addMaterial("roof_gravel", glm::vec3(1.0f), gravel);
    const int roofTiles = addMaterial("roof_tiles", glm::vec3(1.0f), tiles);
    for (std::size_t t = 0; t < kTints.size(); ++t) {
        // Appending (not operator+) avoids GCC 12's false -Wrestrict on string concatenation.
        auto named = [t](const char* base) {
            std::string name(base);
            name.append("_").append(std::to_string(t));
            return name;
        };
        city::BuildingMaterials b;
        b.wall = addMaterial(named("wall"), kTints[t], wall);
        b.facade = addMaterial(named("facade"), kTints[t], facade);
        b.facadeSmall = addMaterial(named("facade_small"), kTints[t], facadeSmall);
        b.roof = roofFlat;
        m.building[2 * t] = b;
        b.roof = roofTiles;
        m.building[2 * t + 1] = b;
    }
    m.asphalt =
        addMaterial("asphalt", glm::vec3(1.0f), addTexture(procedural::makeAsphaltTexture("asphalt", 128, seed + 5u)));
    m.paving =
        addMaterial("paving", glm::vec3(1.0f), addTexture(procedural::makePavingTexture("paving", 64, seed + 6u)));
    m.grass = addMaterial("lawn", glm::vec3(1.0f), addTexture(procedural::makeGrassTexture("lawn", 64, seed + 7u)));
    m.marking = addMaterial("road_marking", glm::vec3(0.92f, 0.92f, 0.88f), -1);
    m.asphaltSmall = addMaterial("asphalt_small", glm::vec3(1.0f),
                                 addTexture(procedural::makeAsphaltTexture("asphalt_small", 32, seed + 5u)));
    m.pavingSmall = addMaterial("paving_small", glm::vec3(1.0f),
                                addTexture(procedural::makePavingTexture("paving_small", 16, seed + 6u)));
    m.grassSmall = addMaterial("lawn_small", glm::vec3(1.0f),
                               addTexture(procedural::makeGrassTexture("lawn_small", 16, seed + 7u)));
    return m;
}

void flatRect(Mesh& mesh, glm::vec2 lo, glm::vec2 hi, float y, float uvMetres) {
    auto at = [y](float x, float z) { return glm::vec3(x, y, z); };
    auto uv = [uvMetres](float x, float z) { return glm::vec2(x, z) / uvMetres; };
    procedural::appendQuad(mesh, at(lo.x, hi.y), at(hi.x, hi.y), at(hi.x, lo.y), at(lo.x, lo.y), uv(lo.x, hi.y),
                           uv(hi.x, hi.y), uv(hi.x, lo.y), uv(lo.x, lo.y));
}

// Curb faces of a block plinth (the top is drawn by flatRect).
void curbs(Mesh& mesh, glm::vec2 lo, glm::vec2 hi) {
    const glm::vec2 c[4] = {{lo.x, hi.y}, {hi.x, hi.y}, {hi.x, lo.y}, {lo.x, lo.y}};
    for (int i = 0; i < 4; ++i) {
        glm::vec2 p = c[i], q = c[(i + 1) % 4];
        float length = glm::length(q - p) / 4.0f;
        procedural::appendQuad(mesh, {p.x, 0.0f, p.y}, {q.x, 0.0f, q.y}, {q.x, kCurbHeight, q.y},
                               {p.x, kCurbHeight, p.y}, {0, 0}, {length, 0}, {length, 0.05f}, {0, 0.05f});
    }
}

Object makeGroundObject(const Grid& gx, const Grid& gz, const std::vector<bool>& park, const CityMaterials& m) {
    Mesh asphalt, paving, lawn, marking, asphaltSmall, pavingSmall, lawnSmall;
    asphalt.material = m.asphalt;
    paving.material = m.paving;
    lawn.material = m.grass;
    marking.material = m.marking;
    asphaltSmall.material = m.asphaltSmall;
    pavingSmall.material = m.pavingSmall;
    lawnSmall.material = m.grassSmall;
    const glm::vec2 lo(-gx.extent - 40.0f, -gz.extent - 40.0f), hi(gx.extent + 40.0f, gz.extent + 40.0f);
    flatRect(asphalt, lo, hi, 0.0f, 12.0f);
    flatRect(asphaltSmall, lo, hi, 0.0f, 12.0f);
    // Open land around the city out to kLandExtent, so distant views have a horizon: four
    // lawn strips framing the asphalt (no overlap, so nothing is coplanar).
    const glm::vec2 far(kLandExtent);
    const std::array<std::array<glm::vec2, 2>, 4> strips = {{{glm::vec2(-far.x, hi.y), glm::vec2(far.x, far.y)},
                                                             {glm::vec2(-far.x, -far.y), glm::vec2(far.x, lo.y)},
                                                             {glm::vec2(-far.x, lo.y), glm::vec2(lo.x, hi.y)},
                                                             {glm::vec2(hi.x, lo.y), glm::vec2(far.x, hi.y)}}};
    for (const auto& strip : strips) {
        flatRect(lawn, strip[0], strip[1], 0.0f, 8.0f);
        flatRect(lawnSmall, strip[0], strip[1], 0.0f, 8.0f);
    }
    for (int i = 0; i < kBlocks; ++i) {
        for (int j = 0; j < kBlocks; ++j) {
            glm::vec2 a(gx.blockMin[std::size_t(i)], gz.blockMin[std::size_t(j)]);
            glm::vec2 b(gx.blockMax[std::size_t(i)], gz.blockMax[std::size_t(j)]);
            bool isPark = park[std::size_t(i * kBlocks + j)];
            flatRect(isPark ? lawn : paving, a, b, kCurbHeight, isPark ? 8.0f : 4.0f);
            flatRect(isPark ? lawnSmall : pavingSmall, a, b, kCurbHeight, isPark ? 8.0f : 4.0f);
            curbs(paving, a, b);
        }
    }
    // Dashed centre lines along both avenues, 3 m dashes every 9 m, 0.2 m wide.
    const float y = 0.03f;
    for (float x = -gx.extent; x + 3.0f < gx.extent; x += 9.0f) {
        float z = gz.streetCenter[kAvenueIndex];
        flatRect(marking, {x, z - 0.1f}, {x + 3.0f, z + 0.1f}, y, 1.0f);
    }
    for (float z = -gz.extent; z + 3.0f < gz.extent; z += 9.0f) {
        float x = gx.streetCenter[kAvenueIndex];
        flatRect(marking, {x - 0.1f, z}, {x + 0.1f, z + 3.0f}, y, 1.0f);
    }
    Object ground;
    ground.name = "ground";
    Level fine, coarse;
    for (Mesh* mesh : {&asphalt, &paving, &lawn, &marking}) {
        if (!mesh->indices.empty()) fine.meshes.push_back(std::move(*mesh));
    }
    for (Mesh* mesh : {&asphaltSmall, &pavingSmall, &lawnSmall}) {
        if (!mesh->indices.empty()) coarse.meshes.push_back(std::move(*mesh));
    }
    ground.levels.push_back(std::move(fine));
    ground.levels.push_back(std::move(coarse));
    return ground;
}

// Parks: 4-6 blocks not touching an avenue.
std::vector<bool> choosePark(std::uint32_t seed) {
    Rng rng(seed, kParkStream);
    std::vector<bool> park(std::size_t(kBlocks * kBlocks), false);
    const int count = rng.uniformInt(4, 6);
    for (int placed = 0, attempt = 0; placed < count && attempt < 1000; ++attempt) {
        int i = rng.uniformInt(0, kBlocks - 1), j = rng.uniformInt(0, kBlocks - 1);
        bool nearAvenue = i == kAvenueIndex - 1 || i == kAvenueIndex || j == kAvenueIndex - 1 || j == kAvenueIndex;
        if (nearAvenue || park[std::size_t(i * kBlocks + j)]) continue;
        park[std::size_t(i * kBlocks + j)] = true;
        ++placed;
    }
    return park;
}

struct Placed {
    BuildingSpec spec;
    glm::vec2 center;
    int tint = 0;
};

// The buildings of one block: two rows of lots along x, fronting the streets at -z and +z.
void fillBlock(glm::vec2 lo, glm::vec2 hi, Rng& rng, std::vector<Placed>& out) {
    const glm::vec2 inner0 = lo + glm::vec2(kSidewalk), inner1 = hi - glm::vec2(kSidewalk);
    const float rowDepth = 0.5f * (inner1.y - inner0.y);
    for (int row = 0; row < 2; ++row) {
        const int lots = rng.uniformInt(4, 5);
        std::array<float, 5> weight{};
        float sum = 0.0f;
        for (int k = 0; k < lots; ++k) sum += (weight[std::size_t(k)] = rng.uniform(0.6f, 1.4f));
        float x = inner0.x;
        for (int k = 0; k < lots; ++k) {
            float frontage = (inner1.x - inner0.x) * weight[std::size_t(k)] / sum;
            Placed p;
            BuildingSpec& s = p.spec;
            s.width = std::max(4.0f, frontage - rng.uniform(0.4f, 1.5f));
            s.depth = std::min(rowDepth - 0.5f, rng.uniform(11.0f, 17.0f));
            // Front face on the street: row 0 fronts -z, row 1 fronts +z.
            float z = row == 0 ? inner0.y + 0.5f * s.depth : inner1.y - 0.5f * s.depth;
            p.center = {x + 0.5f * frontage, z};
            x += frontage;
            float r = glm::length(p.center) / 450.0f;
            float storeys = (2.0f + 28.0f * std::exp(-(r / 0.3f) * (r / 0.3f))) * rng.uniform(0.6f, 1.4f);
            if (rng.chance(0.12f * std::exp(-(r / 0.45f) * (r / 0.45f)))) storeys *= 2.0f;  // a tower
            s.floors = std::clamp(int(std::lround(storeys)), 2, 45);
            s.floorHeight = rng.uniform(3.0f, 3.6f);
            s.groundFloorHeight = s.floorHeight + rng.uniform(0.6f, 1.4f);
            s.bayWidth = rng.uniform(2.4f, 3.4f);
            bool pitched = s.floors <= 5 && rng.chance(0.6f);
            s.roof = pitched ? (rng.chance(0.6f) ? RoofShape::Gable : RoofShape::Hip) : RoofShape::Flat;
            s.roofRise = pitched ? 0.5f * std::min(s.width, s.depth) * rng.uniform(0.5f, 0.9f) : 0.0f;
            s.plantRoom = {rng.uniform(-0.25f, 0.25f) * s.width, rng.uniform(-0.2f, 0.2f) * s.depth};
            s.chimney = {rng.uniform(-0.3f, 0.3f) * s.width, rng.uniform(-0.3f, 0.3f) * s.depth};
            // Towers in cool tints, low houses in warm ones.
            p.tint = s.floors > 12 ? (rng.chance(0.5f) ? 2 : (rng.chance(0.5f) ? 5 : 3)) : rng.uniformInt(0, 5);
            out.push_back(p);
        }
    }
}

Camera makeCamera(const std::string& name, glm::vec3 position, glm::vec3 target, float fov, float nearPlane) {
    Camera camera;
    camera.name = name;
    camera.position = position;
    camera.target = target;
    camera.fovYDegrees = fov;
    camera.nearPlane = nearPlane;
    camera.farPlane = 3000.0f;
    return camera;
}

}  // namespace

Scene makeCityScene(std::uint32_t seed) {
    Scene scene;
    scene.name = "city";
    const Grid gx = makeGrid(kBlockX), gz = makeGrid(kBlockZ);
    const CityMaterials materials = addCityMaterials(scene, seed);
    const std::vector<bool> park = choosePark(seed);
    scene.objects.push_back(makeGroundObject(gx, gz, park, materials));

    std::vector<Placed> buildings;
    for (int i = 0; i < kBlocks; ++i) {
        for (int j = 0; j < kBlocks; ++j) {
            if (park[std::size_t(i * kBlocks + j)]) continue;
            Rng rng(seed, kBlockStreamBase + std::uint64_t(i * kBlocks + j));
            fillBlock({gx.blockMin[std::size_t(i)], gz.blockMin[std::size_t(j)]},
                      {gx.blockMax[std::size_t(i)], gz.blockMax[std::size_t(j)]}, rng, buildings);
        }
    }
    scene.objects.reserve(buildings.size() + 1);
    for (std::size_t b = 0; b < buildings.size(); ++b) {
        const Placed& p = buildings[b];
        Object object;
        char name[32];
        std::snprintf(name, sizeof(name), "building_%04zu", b);
        object.name = name;
        object.transform = glm::translate(glm::mat4(1.0f), glm::vec3(p.center.x, 0.0f, p.center.y));
        const auto& m = materials.building[std::size_t(2 * p.tint + (p.spec.roof == RoofShape::Flat ? 0 : 1))];
        object.levels = city::buildBuildingLevels(p.spec, m);
        scene.objects.push_back(std::move(object));
    }

    // Viewpoints: down a side street at eye height, along the avenue from a first floor, an
    // oblique aerial view and the skyline from outside the city.
    const float avenueZ = gz.streetCenter[kAvenueIndex], avenueX = gx.streetCenter[kAvenueIndex];
    const float sideStreetZ = gz.streetCenter[kAvenueIndex - 2];
    scene.views.push_back(makeCamera("street", {-300.0f, 1.7f, sideStreetZ}, {0.0f, 12.0f, sideStreetZ}, 60.0f, 0.3f));
    scene.views.push_back(
        makeCamera("avenue", {-gx.extent + 40.0f, 12.0f, avenueZ}, {100.0f, 30.0f, avenueZ}, 55.0f, 0.5f));
    scene.views.push_back(makeCamera("aerial", {260.0f, 380.0f, 320.0f}, {0.0f, 0.0f, 0.0f}, 45.0f, 1.0f));
    scene.views.push_back(makeCamera("skyline", {60.0f, 25.0f, -gz.extent - 320.0f}, {0.0f, 40.0f, 0.0f}, 40.0f, 1.0f));

    // Fly-through: descend from the west onto the avenue, fly its length at about 30 m
    // between the towers, climb away to the north over the east side and circle west along
    // the north edge, looking at the centre from the end of the avenue on.
    const std::vector<glm::vec3> controls = {{-gx.extent - 160.0f, 140.0f, avenueZ - 180.0f},
                                             {-gx.extent - 30.0f, 60.0f, avenueZ - 20.0f},
                                             {-gx.extent + 60.0f, 32.0f, avenueZ},
                                             {-150.0f, 30.0f, avenueZ},
                                             {avenueX + 150.0f, 32.0f, avenueZ},
                                             {320.0f, 60.0f, avenueZ + 60.0f},
                                             {380.0f, 150.0f, 260.0f},
                                             {250.0f, 230.0f, gz.extent + 150.0f},
                                             {-50.0f, 280.0f, gz.extent + 230.0f},
                                             {-450.0f, 300.0f, gz.extent + 120.0f}};
    std::vector<glm::vec3> eyes = procedural::sampleSplineEvenly(controls, kFlyFrames);
    Camera lens = makeCamera("", {}, {}, 55.0f, 0.5f);
    CameraPath path = procedural::makeLookAheadPath("flythrough", kFlyFramesPerSecond, eyes, 30, 6.0f, lens);
    // Looking ahead suits the avenue, but climbing out of it the camera would see sky: the
    // view never points above a downward slope that steepens with height (0.05 at 30 m, 0.25
    // at 130 m), and from the avenue's east end the camera turns (over 3 s) to look at the
    // centre. The turn is under 180 degrees, so the blended direction never vanishes.
    std::size_t turn = 0;
    for (std::size_t i = 0; i < eyes.size(); ++i) {
        if (glm::length(eyes[i] - controls[5]) < glm::length(eyes[turn] - controls[5])) turn = i;
    }
    const glm::vec3 downtown(0.0f, 30.0f, 0.0f);
    for (std::size_t i = 0; i < path.frames.size(); ++i) {
        Camera& frame = path.frames[i];
        glm::vec3 direction = glm::normalize(frame.target - frame.position);
        if (i >= turn) {
            float w = std::min(float(i - turn) / (3.0f * kFlyFramesPerSecond), 1.0f);
            w = w * w * (3.0f - 2.0f * w);
            direction = glm::normalize(glm::mix(direction, glm::normalize(downtown - frame.position), w));
        }
        float maxSlope = -0.05f - 0.002f * std::max(frame.position.y - 30.0f, 0.0f);
        glm::vec2 level(direction.x, direction.z);
        if (direction.y / std::max(glm::length(level), 1e-3f) > maxSlope) {
            direction = glm::normalize(glm::vec3(level.x, maxSlope * glm::length(level), level.y));
        }
        frame.target = frame.position + 100.0f * direction;
    }
    scene.paths.push_back(std::move(path));

    updateStatistics(scene);
    validateScene(scene);
    return scene;
}

}  // namespace lodopt::scenes
