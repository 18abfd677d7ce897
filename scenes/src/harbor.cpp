// The built-in `harbor` scene, modelled on the test scene of Che & Kang 2015 (GAPSO15 §4):
// a sea with 6 levels, a ship with 5 and an aircraft with 5. Triangle counts follow the
// paper's order of magnitude (ship ≈ 6.5k → 3k, aircraft ≈ 1.2k → 0.4k); coarse levels drop
// the parts that make a silhouette recognisable (masts, railings, propellers, wave crests,
// the wake), so the metrics have something to see.
#include <cmath>
#include <cstdint>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/builtin.hpp"
#include "scenes/mesh_builder.hpp"

#include "procedural.hpp"

namespace lodopt::scenes {
namespace {

int addMaterial(Scene& scene, const char* name, glm::vec3 color, int texture = -1) {
    return procedural::addDiffuseMaterial(scene, name, color, texture);
}

// Hull plating: anti-fouling red below the waterline, a white boot stripe, dark topsides
// with a row of portholes. v = 0 at the keel, 1 at the deck edge.
int addHullTexture(Scene& scene, int size) {
    Texture texture;
    texture.name = "hull_" + std::to_string(size);
    texture.width = texture.height = size;
    texture.rgba.resize(std::size_t(size) * size * 4);
    for (int y = 0; y < size; ++y) {
        // glTF convention: v = 0 is the first row, so row 0 is the keel.
        float v = (float(y) + 0.5f) / float(size);
        for (int x = 0; x < size; ++x) {
            float u = (float(x) + 0.5f) / float(size);
            glm::vec3 c = v < 0.45f ? glm::vec3(0.55f, 0.12f, 0.10f)
                          : v < 0.52f ? glm::vec3(0.92f, 0.92f, 0.90f)
                                      : glm::vec3(0.10f, 0.12f, 0.16f);
            // Portholes: a row of light dots, only resolvable on the larger textures.
            float pu = std::fmod(u * 24.0f, 1.0f) - 0.5f, pv = (v - 0.75f) * 24.0f;
            if (pu * pu + pv * pv < 0.06f) c = glm::vec3(0.85f, 0.85f, 0.75f);
            std::uint8_t* p = &texture.rgba[(std::size_t(y) * size + x) * 4];
            p[0] = std::uint8_t(c.r * 255.0f + 0.5f);
            p[1] = std::uint8_t(c.g * 255.0f + 0.5f);
            p[2] = std::uint8_t(c.b * 255.0f + 0.5f);
            p[3] = 255;
        }
    }
    return procedural::addTexture(scene, std::move(texture));
}

// A hull lofted along +X: `sections` cross-sections of `profilePoints` points each on a
// half-ellipse, tapering to a bow at +X and a transom at -X, closed by a flat deck.
Mesh makeHull(float length, float beam, float depth, int sections, int profilePoints, int material) {
    Mesh mesh;
    mesh.material = material;
    auto halfWidth = [&](float t) {  // t = 0 stern .. 1 bow
        float stern = 0.82f + 0.18f * std::sqrt(glm::clamp(t / 0.25f, 0.0f, 1.0f));
        float bow = t > 0.65f ? std::pow(std::max(1.0f - (t - 0.65f) / 0.35f, 0.0f), 0.75f) : 1.0f;
        return 0.5f * beam * stern * std::max(bow, 0.02f);
    };
    auto keelDepth = [&](float t) { return depth * (t > 0.85f ? 1.0f - 0.6f * (t - 0.85f) / 0.15f : 1.0f); };
    const float deckY = 0.35f * depth;  // freeboard above the waterline (y = 0)
    for (int s = 0; s <= sections; ++s) {
        float t = float(s) / float(sections);
        float x = -0.5f * length + t * length;
        float sheer = 0.4f * depth * t * t;  // deck rises toward the bow
        for (int p = 0; p <= profilePoints; ++p) {
            float a = glm::pi<float>() * float(p) / float(profilePoints);  // port deck → keel → starboard deck
            float z = halfWidth(t) * std::cos(a);
            float y = deckY + sheer - (keelDepth(t) + deckY + sheer) * std::pow(std::max(std::sin(a), 0.0f), 0.6f);
            mesh.positions.emplace_back(x, y, z);
            mesh.uvs.emplace_back(t, (y + depth) / (deckY + sheer + depth));
        }
    }
    const std::uint32_t stride = static_cast<std::uint32_t>(profilePoints + 1);
    for (int s = 0; s < sections; ++s) {
        for (int p = 0; p < profilePoints; ++p) {
            std::uint32_t a = s * stride + p, b = a + 1, c = a + stride, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    }
    // Deck: strips between the port and starboard deck edges of consecutive sections.
    for (int s = 0; s < sections; ++s) {
        std::uint32_t port0 = s * stride, star0 = port0 + profilePoints;
        std::uint32_t port1 = port0 + stride, star1 = star0 + stride;
        mesh.indices.insert(mesh.indices.end(), {port0, star0, port1, star0, star1, port1});
    }
    // Transom: a fan over the stern section.
    for (int p = 1; p < profilePoints; ++p) {
        mesh.indices.insert(mesh.indices.end(), {0u, std::uint32_t(p + 1), std::uint32_t(p)});
    }
    computeNormals(mesh);
    return mesh;
}

struct ShipDetail {
    int hullSections, hullProfile;
    int railingPosts;  // per side; 0 = no railing
    int curvedSegments;
    bool masts, radar, lifeboats, cranes;
    int containerRows;
    int hullTexture;
};

Level makeShipLevel(Scene& scene, const ShipDetail& detail, int whiteMaterial, int deckMaterial,
                    int funnelMaterial, int darkMaterial) {
    const float length = 60.0f, beam = 10.0f, depth = 4.0f;
    Level level;
    int hullMaterial = addMaterial(scene, "ship_hull", glm::vec3(1.0f), detail.hullTexture);
    level.meshes.push_back(makeHull(length, beam, depth, detail.hullSections, detail.hullProfile, hullMaterial));

    const float deckY = 0.35f * depth;
    MeshBuilder white(whiteMaterial), deck(deckMaterial), funnel(funnelMaterial), dark(darkMaterial);
    // Superstructure aft of midships: three stacked decks, the bridge on top.
    white.addBox({-14.0f, deckY + 1.5f, 0.0f}, {6.0f, 1.5f, 4.0f});
    white.addBox({-13.0f, deckY + 4.2f, 0.0f}, {4.5f, 1.2f, 3.6f});
    white.addBox({-12.0f, deckY + 6.4f, 0.0f}, {3.0f, 1.0f, 4.6f});  // bridge wings overhang
    funnel.addCylinder({-18.0f, deckY + 3.0f, 0.0f}, 6.0f, 1.3f, 1.1f, detail.curvedSegments);
    dark.addCylinder({-18.0f, deckY + 9.0f, 0.0f}, 0.8f, 1.12f, 1.1f, detail.curvedSegments);
    if (detail.masts) {
        white.addCylinder({-12.0f, deckY + 7.4f, 0.0f}, 7.0f, 0.18f, 0.1f, detail.curvedSegments / 2);
        white.addBox({-12.0f, deckY + 12.0f, 0.0f}, {0.08f, 0.08f, 2.0f});  // yard arm
        white.addCylinder({18.0f, deckY, 0.0f}, 10.0f, 0.25f, 0.12f, detail.curvedSegments / 2);
        white.addBox({18.0f, deckY + 8.0f, 0.0f}, {0.1f, 0.1f, 2.5f});
    }
    if (detail.radar) {
        dark.addBox({-12.0f, deckY + 8.6f, 0.0f}, {0.15f, 0.15f, 1.4f});
        dark.addCylinder({-10.5f, deckY + 7.4f, 2.0f}, 0.8f, 0.5f, 0.5f, detail.curvedSegments / 2);
        dark.addEllipsoid({-10.5f, deckY + 8.5f, 2.0f}, {0.5f, 0.5f, 0.5f}, detail.curvedSegments / 2,
                          detail.curvedSegments / 4);
    }
    if (detail.lifeboats) {
        for (int side = -1; side <= 1; side += 2) {
            for (int k = 0; k < 2; ++k) {
                glm::vec3 center(-16.5f + 5.0f * k, deckY + 3.6f, side * 4.8f);
                funnel.addEllipsoid(center, {1.8f, 0.45f, 0.6f}, detail.curvedSegments, detail.curvedSegments / 2);
            }
        }
    }
    // Deck cargo: rows of containers forward of the superstructure.
    for (int row = 0; row < detail.containerRows; ++row) {
        for (int col = -1; col <= 1; ++col) {
            glm::vec3 center(-4.0f + 4.5f * row, deckY + 1.2f, 2.6f * col);
            deck.addBox(center, {2.0f, 1.2f, 1.2f});
            if (detail.containerRows > 3) deck.addBox(center + glm::vec3(0.0f, 2.4f, 0.0f), {2.0f, 1.2f, 1.2f});
        }
    }
    if (detail.cranes) {
        for (int k = 0; k < 2; ++k) {
            float x = -2.0f + 11.0f * k;
            dark.addCylinder({x, deckY, 4.2f}, 7.0f, 0.35f, 0.3f, detail.curvedSegments / 2);
            MeshBuilder boom(darkMaterial);
            boom.setTransform(glm::rotate(glm::translate(glm::mat4(1.0f), {x, deckY + 6.5f, 4.2f}),
                                          glm::radians(-35.0f), {0.0f, 0.0f, 1.0f}));
            boom.addBox({3.5f, 0.0f, 0.0f}, {3.5f, 0.15f, 0.15f});
            level.meshes.push_back(boom.finish());
        }
    }
    if (detail.railingPosts > 0) {
        for (int side = -1; side <= 1; side += 2) {
            for (int k = 0; k < detail.railingPosts; ++k) {
                float x = -27.0f + 40.0f * float(k) / float(detail.railingPosts - 1);
                white.addBox({x, deckY + 0.55f, side * 4.75f}, {0.04f, 0.55f, 0.04f});
            }
            white.addBox({-7.0f, deckY + 1.1f, side * 4.75f}, {20.0f, 0.05f, 0.05f});
        }
    }
    for (MeshBuilder* builder : {&white, &deck, &funnel, &dark}) {
        if (!builder->empty()) level.meshes.push_back(builder->finish());
    }
    return level;
}

struct AircraftDetail {
    int fuselageSegments, fuselageRings;
    int engineSegments;
    bool propellers, canopy, antenna;
};

Level makeAircraftLevel(const AircraftDetail& detail, int bodyMaterial, int darkMaterial, int glassMaterial) {
    Level level;
    MeshBuilder body(bodyMaterial), dark(darkMaterial), glass(glassMaterial);
    // Fuselage along +X, 16 m; wings span 18 m (a twin-engine patrol aircraft).
    body.addEllipsoid({0.0f, 0.0f, 0.0f}, {8.0f, 1.1f, 1.1f}, detail.fuselageSegments, detail.fuselageRings);
    body.addBox({0.5f, 0.2f, 0.0f}, {1.4f, 0.12f, 9.0f});   // main wing
    body.addBox({-7.0f, 0.3f, 0.0f}, {0.8f, 0.08f, 3.2f});  // tailplane
    MeshBuilder fin(bodyMaterial);
    fin.setTransform(glm::rotate(glm::translate(glm::mat4(1.0f), {-6.8f, 1.6f, 0.0f}), glm::radians(-20.0f),
                                 {0.0f, 0.0f, 1.0f}));
    fin.addBox({0.0f, 0.0f, 0.0f}, {0.9f, 1.5f, 0.08f});
    level.meshes.push_back(fin.finish());
    for (int side = -1; side <= 1; side += 2) {
        MeshBuilder nacelle(bodyMaterial);
        nacelle.setTransform(glm::rotate(glm::translate(glm::mat4(1.0f), {2.2f, 0.0f, side * 3.5f}),
                                         glm::radians(90.0f), {0.0f, 0.0f, -1.0f}));
        nacelle.addCylinder({0.0f, 0.0f, 0.0f}, 3.2f, 0.45f, 0.35f, detail.engineSegments);
        level.meshes.push_back(nacelle.finish());
        if (detail.propellers) {
            for (int blade = 0; blade < 3; ++blade) {
                MeshBuilder prop(darkMaterial);
                prop.setTransform(glm::rotate(glm::translate(glm::mat4(1.0f), {2.3f, 0.0f, side * 3.5f}),
                                              glm::two_pi<float>() * float(blade) / 3.0f, {1.0f, 0.0f, 0.0f}));
                prop.addBox({0.0f, 0.8f, 0.0f}, {0.03f, 0.8f, 0.12f});
                level.meshes.push_back(prop.finish());
            }
        }
    }
    if (detail.canopy) {
        glass.addEllipsoid({5.2f, 0.75f, 0.0f}, {1.6f, 0.5f, 0.7f}, detail.fuselageSegments / 2,
                           detail.fuselageRings / 2);
    }
    if (detail.antenna) {
        dark.addCylinder({-1.0f, 1.0f, 0.0f}, 0.9f, 0.05f, 0.02f, 6, false);
        dark.addCylinder({-3.0f, -1.9f, 0.0f}, 0.9f, 0.02f, 0.05f, 6, false);
    }
    for (MeshBuilder* builder : {&body, &dark, &glass}) {
        if (!builder->empty()) level.meshes.push_back(builder->finish());
    }
    return level;
}

// Sea waves: a sum of directional sines; `wind` scales amplitude (the paper's wind 12/8/4).
float waveHeight(float x, float z, float wind) {
    float a = 0.012f * wind;
    return a * (std::sin(0.09f * x + 0.05f * z) + 0.6f * std::sin(0.17f * z - 0.11f * x + 1.3f) +
                0.35f * std::sin(0.31f * x + 0.27f * z + 2.1f));
}

struct SeaDetail {
    int cells;
    float wind;
    bool wake, spray;
};

Level makeSeaLevel(const SeaDetail& detail, int waterMaterial, int foamMaterial, glm::vec3 shipPosition) {
    Level level;
    MeshBuilder water(waterMaterial), foam(foamMaterial);
    const float size = 600.0f;
    water.addHeightGrid({0.0f, 0.0f, 0.0f}, {size, size}, detail.cells, detail.cells,
                        [&](float x, float z) { return waveHeight(x, z, detail.wind); });
    if (detail.wake) {
        // A V-shaped wake trailing astern (-X) of the ship, lying just above the waves.
        for (int side = -1; side <= 1; side += 2) {
            for (int k = 0; k < 24; ++k) {
                float x0 = shipPosition.x - 28.0f - 6.0f * k, x1 = x0 - 6.0f;
                float w0 = 1.5f + 0.35f * k, w1 = w0 + 0.35f;
                float y0 = waveHeight(x0, shipPosition.z, detail.wind) + 0.25f;
                float y1 = waveHeight(x1, shipPosition.z, detail.wind) + 0.25f;
                float z0 = shipPosition.z + side * (0.5f + 0.5f * k), z1 = z0 + side * 0.5f;
                glm::vec3 a(x0, y0, z0), b(x1, y1, z1), c(x1, y1, z1 + side * w1), d(x0, y0, z0 + side * w0);
                if (side > 0) foam.addQuad(a, d, c, b);
                else foam.addQuad(a, b, c, d);
            }
        }
        // The churned trail directly astern.
        for (int k = 0; k < 20; ++k) {
            float x0 = shipPosition.x - 28.0f - 5.0f * k, x1 = x0 - 5.0f;
            float w = 2.5f + 0.12f * k;
            float y0 = waveHeight(x0, shipPosition.z, detail.wind) + 0.3f;
            float y1 = waveHeight(x1, shipPosition.z, detail.wind) + 0.3f;
            foam.addQuad({x0, y0, shipPosition.z - w}, {x0, y0, shipPosition.z + w}, {x1, y1, shipPosition.z + w},
                         {x1, y1, shipPosition.z - w});
        }
    }
    if (detail.spray) {
        // Bow spray: small cards around the stem.
        std::uint32_t state = 12345u;
        auto next = [&state] {
            state = state * 1664525u + 1013904223u;
            return float(state >> 8) / float(1u << 24);
        };
        for (int k = 0; k < 60; ++k) {
            float x = shipPosition.x + 25.0f + 6.0f * next();
            float z = shipPosition.z + (next() - 0.5f) * 14.0f;
            float y = 0.3f + 2.0f * next();
            float s = 0.3f + 0.5f * next();
            foam.addDoubleSidedCard({x - s, y, z}, {x + s, y, z + s * 0.3f}, {0.0f, 1.0f, 0.0f}, s);
        }
    }
    for (MeshBuilder* builder : {&water, &foam}) {
        if (!builder->empty()) level.meshes.push_back(builder->finish());
    }
    return level;
}

Camera makeCamera(const char* name, glm::vec3 position, glm::vec3 target, float fov = 45.0f) {
    Camera camera;
    camera.name = name;
    camera.position = position;
    camera.target = target;
    camera.fovYDegrees = fov;
    camera.nearPlane = 0.5f;
    camera.farPlane = 1500.0f;
    return camera;
}

}  // namespace

Scene makeHarborScene(std::uint32_t seed) {
    // The harbor is fixed; the seed only moves the aircraft along its track a little, so
    // that tests of seed handling see a difference.
    Scene scene;
    scene.name = "harbor";
    const int water = addMaterial(scene, "sea", {0.12f, 0.32f, 0.48f});
    const int foam = addMaterial(scene, "foam", {0.92f, 0.95f, 0.97f});
    const int white = addMaterial(scene, "ship_white", {0.90f, 0.90f, 0.87f});
    const int deck = addMaterial(scene, "containers", {0.70f, 0.38f, 0.18f});
    const int funnel = addMaterial(scene, "funnel", {0.85f, 0.45f, 0.10f});
    const int dark = addMaterial(scene, "dark_metal", {0.18f, 0.19f, 0.21f});
    const int body = addMaterial(scene, "aircraft_body", {0.72f, 0.74f, 0.78f});
    const int glass = addMaterial(scene, "canopy", {0.15f, 0.22f, 0.30f});

    const glm::vec3 shipPosition(0.0f, 0.0f, 0.0f);

    Object sea;
    sea.name = "sea";
    const SeaDetail seaLevels[] = {{110, 12.0f, true, true}, {80, 12.0f, true, false}, {56, 8.0f, true, false},
                                   {36, 8.0f, false, false}, {16, 4.0f, false, false}, {1, 0.0f, false, false}};
    for (const SeaDetail& detail : seaLevels) sea.levels.push_back(makeSeaLevel(detail, water, foam, shipPosition));

    Object ship;
    ship.name = "ship";
    ship.transform = glm::translate(glm::mat4(1.0f), shipPosition);
    const ShipDetail shipLevels[] = {
        {72, 28, 40, 24, true, true, true, true, 4, addHullTexture(scene, 256)},
        {64, 26, 24, 20, true, true, true, true, 4, addHullTexture(scene, 128)},
        {56, 24, 12, 16, true, false, true, true, 4, addHullTexture(scene, 64)},
        {44, 18, 0, 12, false, false, true, false, 3, addHullTexture(scene, 32)},
        {40, 16, 0, 10, false, false, false, false, 3, addHullTexture(scene, 16)},
    };
    for (const ShipDetail& detail : shipLevels) {
        ship.levels.push_back(makeShipLevel(scene, detail, white, deck, funnel, dark));
    }

    Object aircraft;
    aircraft.name = "aircraft";
    const float track = float(seed % 7u) * 0.5f;
    aircraft.transform = glm::rotate(glm::translate(glm::mat4(1.0f), {35.0f + track, 28.0f, -30.0f}),
                                     glm::radians(20.0f), {0.0f, 1.0f, 0.0f});
    aircraft.transform = glm::rotate(aircraft.transform, glm::radians(-12.0f), {1.0f, 0.0f, 0.0f});
    const AircraftDetail aircraftLevels[] = {{28, 18, 16, true, true, true},
                                             {22, 14, 12, true, true, false},
                                             {18, 12, 10, false, true, false},
                                             {14, 10, 8, false, false, false},
                                             {12, 8, 6, false, false, false}};
    for (const AircraftDetail& detail : aircraftLevels) {
        aircraft.levels.push_back(makeAircraftLevel(detail, body, dark, glass));
    }

    scene.objects = {std::move(sea), std::move(ship), std::move(aircraft)};
    scene.views = {
        makeCamera("overview", {-70.0f, 32.0f, 75.0f}, {5.0f, 6.0f, -5.0f}),
        makeCamera("ship_close", {-38.0f, 9.0f, 28.0f}, {-5.0f, 4.0f, 0.0f}),
        makeCamera("aircraft_chase", {10.0f, 34.0f, -8.0f}, {36.0f, 27.0f, -30.0f}),
        makeCamera("far", {-180.0f, 45.0f, 170.0f}, {10.0f, 8.0f, -10.0f}),
    };
    updateStatistics(scene);
    validateScene(scene);
    return scene;
}

}  // namespace lodopt::scenes
