// Procedural geometry for the built-in scenes: boxes, cylinders, cones, ellipsoids, height
// grids and quads, appended into one Mesh under a current transform.
//
// Every add* call emits its own vertices (no welding across primitives), with normals:
// flat for boxes and quads, smooth for curved surfaces. `segments` is the number of sides
// around an axis, `rings` the number of bands from pole to pole; both are clamped to >= 3
// (>= 2 rings). UVs are always generated (planar or cylindrical) so any material may carry a
// texture.
#pragma once

#include <functional>

#include "scenes/scene.hpp"

namespace lodopt::scenes {

class MeshBuilder {
public:
    explicit MeshBuilder(int material = -1) { mMesh.material = material; }

    // Transform applied to everything added afterwards (object space of the result).
    void setTransform(const glm::mat4& transform);
    const glm::mat4& transform() const { return mTransform; }

    void addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c);
    // Quad a-b-c-d counter-clockwise seen from the front; UVs (0,0) (1,0) (1,1) (0,1).
    void addQuad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d);
    // Axis-aligned box around `center` (before the transform).
    void addBox(glm::vec3 center, glm::vec3 halfExtents);
    // Frustum of a cone along +Y from `base`; radiusTop 0 gives a cone. Capped at both ends
    // when `capped`.
    void addCylinder(glm::vec3 base, float height, float radiusBottom, float radiusTop, int segments,
                     bool capped = true);
    void addEllipsoid(glm::vec3 center, glm::vec3 radii, int segments, int rings);
    // A grid in the XZ plane centred on `center`, size x size, cellsX x cellsZ cells, with
    // y = center.y + height(x, z) (world units before the transform).
    void addHeightGrid(glm::vec3 center, glm::vec2 size, int cellsX, int cellsZ,
                       const std::function<float(float, float)>& height);
    // A quad through `a`→`b` along its bottom edge, `height` tall along `up`, with both faces
    // (leaf cards and billboards are seen from both sides).
    void addDoubleSidedCard(glm::vec3 a, glm::vec3 b, glm::vec3 up, float height);

    bool empty() const { return mMesh.indices.empty(); }
    std::size_t triangleCount() const { return mMesh.indices.size() / 3; }
    // Returns the mesh and leaves the builder empty (same material).
    Mesh finish();

private:
    std::uint32_t addVertex(glm::vec3 position, glm::vec3 normal, glm::vec2 uv);

    Mesh mMesh;
    glm::mat4 mTransform{1.0f};
    glm::mat3 mNormalMatrix{1.0f};
};

}  // namespace lodopt::scenes
