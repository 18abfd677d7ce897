// Procedural buildings and their three LODs; the levels are described in city_building.hpp.
#include "city_building.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace lodopt::scenes::city {

using procedural::appendQuad;
using procedural::appendTriangle;

float wallHeight(const BuildingSpec& spec) {
    return spec.groundFloorHeight + float(std::max(spec.floors, 1) - 1) * spec.floorHeight;
}

namespace {

constexpr float kWallUvMetres = 3.0f;  // one plaster repeat (along u) per 3 m
constexpr float kRoofUvMetres = 3.0f;
constexpr glm::vec2 kWallTexel{0.02f, 0.02f};  // a plain-wall texel of the facade textures
// Level 0's walls and windows share one texture, so one draw call (llvmpipe spends 10-20 us
// of CPU per draw, which over a thousand buildings adds up to tens of ms): plaster in
// v in [0, 0.5), the window bay in [0.5, 1). u repeats; each piece maps its height into its
// half, with a margin so that linear filtering does not bleed from the other half.
constexpr glm::vec2 kPlasterV{0.03f, 0.47f};
constexpr glm::vec2 kWindowV{0.53f, 0.97f};

// The footprint's sides as (from, to) corners in (x, z), ordered so that the outward normal
// is cross(to - from, +y): counter-clockwise seen from below, i.e. clockwise from above.
std::array<std::array<glm::vec2, 2>, 4> sidesOf(float hx, float hz) {
    const glm::vec2 c[4] = {{-hx, hz}, {hx, hz}, {hx, -hz}, {-hx, -hz}};
    return {{{c[0], c[1]}, {c[1], c[2]}, {c[2], c[3]}, {c[3], c[0]}}};
}

int baysAlong(float length, float bayWidth) {
    return std::max(1, int(std::lround(length / bayWidth)));
}

// Vertical walls around the rectangle (hx, hz) from y0 to y1. `uv(side, s, y)` gives the uv of
// the point at arc length s along the side (0 at `from`) and height y. Inward walls (a
// parapet's inner face) reverse the winding.
void ringWalls(Mesh& mesh, float hx, float hz, float y0, float y1, bool inward,
               const std::function<glm::vec2(int side, float s, float y)>& uv) {
    const auto sides = sidesOf(hx, hz);
    for (int i = 0; i < 4; ++i) {
        glm::vec2 p = sides[std::size_t(i)][0], q = sides[std::size_t(i)][1];
        float length = glm::length(q - p);
        glm::vec3 a(p.x, y0, p.y), b(q.x, y0, q.y), c(q.x, y1, q.y), d(p.x, y1, p.y);
        glm::vec2 ta = uv(i, 0.0f, y0), tb = uv(i, length, y0), tc = uv(i, length, y1), td = uv(i, 0.0f, y1);
        if (inward)
            appendQuad(mesh, b, a, d, c, tb, ta, td, tc);
        else
            appendQuad(mesh, a, b, c, d, ta, tb, tc, td);
    }
}

float plasterV(float y, float y0, float y1) {
    return glm::mix(kPlasterV.x, kPlasterV.y, std::clamp((y - y0) / std::max(y1 - y0, 1e-3f), 0.0f, 1.0f));
}

// Plaster on a wall piece from y0 to y1: u in metres / kWallUvMetres, v across the piece.
std::function<glm::vec2(int, float, float)> plasterUv(float y0, float y1) {
    return [y0, y1](int, float s, float y) { return glm::vec2(s / kWallUvMetres, plasterV(y, y0, y1)); };
}

// A horizontal plaster ring between the rectangles `outer` and `inner` (half extents) at
// height y, facing up or down.
void ringFlat(Mesh& mesh, glm::vec2 outer, glm::vec2 inner, float y, bool up) {
    const auto o = sidesOf(outer.x, outer.y), n = sidesOf(inner.x, inner.y);
    auto at = [y](glm::vec2 p) { return glm::vec3(p.x, y, p.y); };
    auto uv = [](glm::vec2 p, bool isOuter) {
        return glm::vec2((p.x + p.y) / kWallUvMetres, isOuter ? kPlasterV.x : kPlasterV.y);
    };
    for (std::size_t i = 0; i < 4; ++i) {
        glm::vec2 p = o[i][0], q = o[i][1], pi = n[i][0], qi = n[i][1];
        glm::vec2 tp = uv(p, true), tq = uv(q, true), tpi = uv(pi, false), tqi = uv(qi, false);
        if (up)
            appendQuad(mesh, at(p), at(q), at(qi), at(pi), tp, tq, tqi, tpi);
        else
            appendQuad(mesh, at(p), at(pi), at(qi), at(q), tp, tpi, tqi, tq);
    }
}

// The top of a plant room or chimney: plaster along u only.
glm::vec2 plasterTopUv(glm::vec2 q) {
    return {(q.x + q.y) / kWallUvMetres, 0.5f * (kPlasterV.x + kPlasterV.y)};
}

// A horizontal rectangle facing up, centred at `center` (x, z).
void topQuad(Mesh& mesh, glm::vec2 center, glm::vec2 half, float y, const std::function<glm::vec2(glm::vec2)>& uv) {
    glm::vec2 c[4] = {{center.x - half.x, center.y + half.y},
                      {center.x + half.x, center.y + half.y},
                      {center.x + half.x, center.y - half.y},
                      {center.x - half.x, center.y - half.y}};
    auto at = [y](glm::vec2 p) { return glm::vec3(p.x, y, p.y); };
    appendQuad(mesh, at(c[0]), at(c[1]), at(c[2]), at(c[3]), uv(c[0]), uv(c[1]), uv(c[2]), uv(c[3]));
}

// A box without a bottom (it stands on something): 5 faces, 20 vertices, 10 triangles.
void openBox(Mesh& mesh, glm::vec2 center, glm::vec2 half, float y0, float y1,
             const std::function<glm::vec2(int, float, float)>& wallUv,
             const std::function<glm::vec2(glm::vec2)>& topUv) {
    const std::size_t first = mesh.positions.size();
    ringWalls(mesh, half.x, half.y, y0, y1, false, wallUv);
    for (std::size_t v = first; v < mesh.positions.size(); ++v) {
        mesh.positions[v].x += center.x;
        mesh.positions[v].z += center.y;
    }
    topQuad(mesh, center, half, y1, topUv);
}

glm::vec2 plantRoomHalf(const BuildingSpec& spec) {
    return {std::min(2.0f, spec.width / 6.0f), std::min(1.5f, spec.depth / 6.0f)};
}

// Pitched roofs are built with the ridge along local x over half extents (a, b), a >= b,
// then turned a quarter about +y when the building is deeper than wide.
struct RoofFrame {
    bool turned = false;
    float a = 0.0f, b = 0.0f;
    glm::vec3 map(glm::vec3 p) const { return turned ? glm::vec3(p.z, p.y, -p.x) : p; }
};

RoofFrame roofFrame(const BuildingSpec& spec) {
    RoofFrame frame;
    frame.turned = spec.depth > spec.width;
    frame.a = 0.5f * std::max(spec.width, spec.depth);
    frame.b = 0.5f * std::min(spec.width, spec.depth);
    return frame;
}

// Gable or hip roof planes (roof material) and, for a gable, the two gable walls into
// `gableMesh` with `gableUv` (a constant uv paints them plain wall).
void pitchedRoof(const BuildingSpec& spec, Mesh& roofMesh, Mesh& gableMesh, bool constantGableUv) {
    const RoofFrame f = roofFrame(spec);
    const float h = wallHeight(spec), rise = spec.roofRise, o = 0.4f;
    const float eave = h - o * rise / f.b;  // the slope continued over the overhang
    const float top = h + rise;
    auto m = [&](float x, float y, float z) { return f.map({x, y, z}); };
    // Tiles: u along the ridge, v up the slope (courses parallel to the ridge).
    const float slope = std::sqrt((f.b + o) * (f.b + o) + (top - eave) * (top - eave)) / kRoofUvMetres;
    const float ua = (f.a + o) / kRoofUvMetres;
    if (spec.roof == RoofShape::Gable) {
        appendQuad(roofMesh, m(-f.a - o, eave, f.b + o), m(f.a + o, eave, f.b + o), m(f.a + o, top, 0),
                   m(-f.a - o, top, 0), {-ua, 0}, {ua, 0}, {ua, slope}, {-ua, slope});
        appendQuad(roofMesh, m(f.a + o, eave, -f.b - o), m(-f.a - o, eave, -f.b - o), m(-f.a - o, top, 0),
                   m(f.a + o, top, 0), {ua, 0}, {-ua, 0}, {-ua, slope}, {ua, slope});
        auto uv = [&](float s, float y) {
            return constantGableUv ? kWallTexel : glm::vec2(s / kWallUvMetres, plasterV(y, h, top));
        };
        appendTriangle(gableMesh, m(f.a, h, f.b), m(f.a, h, -f.b), m(f.a, top, 0), uv(0, h), uv(2 * f.b, h),
                       uv(f.b, top));
        appendTriangle(gableMesh, m(-f.a, h, -f.b), m(-f.a, h, f.b), m(-f.a, top, 0), uv(0, h), uv(2 * f.b, h),
                       uv(f.b, top));
        return;
    }
    // Hip: 45-degree hips, so the ridge is a - b long on each side of the centre.
    const float r = f.a - f.b;
    const glm::vec2 t0{0, 0}, t1{2 * ua, 0}, t2{ua + r / kRoofUvMetres, slope}, t3{ua - r / kRoofUvMetres, slope};
    if (r > 1e-3f) {
        appendQuad(roofMesh, m(-f.a - o, eave, f.b + o), m(f.a + o, eave, f.b + o), m(r, top, 0), m(-r, top, 0), t0, t1,
                   t2, t3);
        appendQuad(roofMesh, m(f.a + o, eave, -f.b - o), m(-f.a - o, eave, -f.b - o), m(-r, top, 0), m(r, top, 0), t0,
                   t1, t2, t3);
    } else {
        appendTriangle(roofMesh, m(-f.a - o, eave, f.b + o), m(f.a + o, eave, f.b + o), m(0, top, 0), t0, t1,
                       {ua, slope});
        appendTriangle(roofMesh, m(f.a + o, eave, -f.b - o), m(-f.a - o, eave, -f.b - o), m(0, top, 0), t0, t1,
                       {ua, slope});
    }
    const float ub = (f.b + o) / kRoofUvMetres;
    appendTriangle(roofMesh, m(f.a + o, eave, f.b + o), m(f.a + o, eave, -f.b - o), m(r, top, 0), {0, 0}, {2 * ub, 0},
                   {ub, slope});
    appendTriangle(roofMesh, m(-f.a - o, eave, -f.b - o), m(-f.a - o, eave, f.b + o), m(-r, top, 0), {0, 0},
                   {2 * ub, 0}, {ub, slope});
}

// Facade bays per side, from the outer footprint, so levels 0 and 1 put windows alike.
std::array<int, 4> baysPerSide(const BuildingSpec& spec) {
    int alongX = baysAlong(spec.width, spec.bayWidth), alongZ = baysAlong(spec.depth, spec.bayWidth);
    return {alongX, alongZ, alongX, alongZ};
}

Level detailedLevel(const BuildingSpec& spec, const BuildingMaterials& materials) {
    Mesh wall, roof;
    wall.material = materials.wall;
    roof.material = materials.roof;
    const float hx = 0.5f * spec.width, hz = 0.5f * spec.depth, r = kWindowRecess;
    const auto bays = baysPerSide(spec);
    float y0 = 0.0f;
    for (int floor = 0; floor < spec.floors; ++floor) {
        const float storey = floor == 0 ? spec.groundFloorHeight : spec.floorHeight;
        const float sill = y0 + (floor == 0 ? 0.6f : 0.9f), y1 = y0 + storey;
        ringWalls(wall, hx, hz, y0, sill, false, plasterUv(y0, sill));
        ringWalls(wall, hx - r, hz - r, sill, y1, false, [&](int side, float s, float y) {
            float length = side % 2 == 0 ? 2.0f * (hx - r) : 2.0f * (hz - r);
            return glm::vec2(float(bays[std::size_t(side)]) * s / length,
                             glm::mix(kWindowV.x, kWindowV.y, (y - sill) / (y1 - sill)));
        });
        ringFlat(wall, {hx, hz}, {hx - r, hz - r}, sill, true);  // sill reveal
        ringFlat(wall, {hx, hz}, {hx - r, hz - r}, y1, false);   // head reveal
        y0 = y1;
    }
    const float h = y0;
    if (spec.roof == RoofShape::Flat) {
        const float c = 0.35f, cornice = 0.45f, parapet = 0.9f, p = 0.25f, slab = h + 0.2f;
        const float top = h + cornice + parapet;
        ringFlat(wall, {hx + c, hz + c}, {hx, hz}, h, false);
        ringWalls(wall, hx + c, hz + c, h, h + cornice, false, plasterUv(h, h + cornice));
        ringFlat(wall, {hx + c, hz + c}, {hx, hz}, h + cornice, true);
        ringWalls(wall, hx, hz, h + cornice, top, false, plasterUv(h + cornice, top));
        ringFlat(wall, {hx, hz}, {hx - p, hz - p}, top, true);
        ringWalls(wall, hx - p, hz - p, slab, top, true, plasterUv(slab, top));
        topQuad(roof, {0, 0}, {hx - p, hz - p}, slab, [](glm::vec2 q) { return q / kRoofUvMetres; });
        openBox(wall, spec.plantRoom, plantRoomHalf(spec), slab, slab + 2.6f, plasterUv(slab, slab + 2.6f),
                plasterTopUv);
    } else {
        pitchedRoof(spec, roof, wall, false);
        const float chimneyTop = h + spec.roofRise + 1.0f;
        openBox(wall, spec.chimney, {0.35f, 0.35f}, h, chimneyTop, plasterUv(h, chimneyTop), plasterTopUv);
    }
    Level level;
    level.meshes.push_back(std::move(wall));
    level.meshes.push_back(std::move(roof));
    return level;
}

// Facade uv: u counts bays, v counts storeys (upper storeys land on whole numbers).
std::function<glm::vec2(int, float, float)> facadeUv(const BuildingSpec& spec) {
    const auto bays = baysPerSide(spec);
    return [spec, bays](int side, float s, float y) {
        float length = side % 2 == 0 ? spec.width : spec.depth;
        return glm::vec2(float(bays[std::size_t(side)]) * s / length,
                         (y - (spec.groundFloorHeight - spec.floorHeight)) / spec.floorHeight);
    };
}

Level blockLevel(const BuildingSpec& spec, const BuildingMaterials& materials) {
    Mesh facade, roof;
    facade.material = materials.facade;
    roof.material = materials.roof;
    const float hx = 0.5f * spec.width, hz = 0.5f * spec.depth, h = wallHeight(spec);
    ringWalls(facade, hx, hz, 0.0f, h, false, facadeUv(spec));
    auto plain = [](int, float, float) { return kWallTexel; };
    if (spec.roof == RoofShape::Flat) {
        topQuad(roof, {0, 0}, {hx, hz}, h, [](glm::vec2 q) { return q / kRoofUvMetres; });
        // The plant room keeps the block a step finer than the box, even on a small roof.
        openBox(facade, spec.plantRoom, plantRoomHalf(spec), h, h + 2.6f, plain, [](glm::vec2) { return kWallTexel; });
    } else {
        pitchedRoof(spec, roof, facade, true);
    }
    Level level;
    level.meshes.push_back(std::move(facade));
    level.meshes.push_back(std::move(roof));
    return level;
}

Level boxLevel(const BuildingSpec& spec, const BuildingMaterials& materials) {
    Mesh box;
    box.material = materials.facadeSmall;
    const float h = wallHeight(spec) + (spec.roof == RoofShape::Flat ? 0.0f : 0.4f * spec.roofRise);
    openBox(box, {0, 0}, {0.5f * spec.width, 0.5f * spec.depth}, 0.0f, h, facadeUv(spec),
            [](glm::vec2) { return kWallTexel; });
    Level level;
    level.meshes.push_back(std::move(box));
    return level;
}

}  // namespace

std::vector<Level> buildBuildingLevels(const BuildingSpec& spec, const BuildingMaterials& materials) {
    std::vector<Level> levels;
    levels.reserve(kBuildingLevels);
    levels.push_back(detailedLevel(spec, materials));
    levels.push_back(blockLevel(spec, materials));
    levels.push_back(boxLevel(spec, materials));
    return levels;
}

}  // namespace lodopt::scenes::city
