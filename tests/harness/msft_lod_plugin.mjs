// A GLTFLoader plugin for the MSFT_lod node extension (three.js has none): every node with
// MSFT_lod becomes a THREE.LOD whose levels are the node itself (level 0) and the nodes its
// `ids` name (levels 1, 2, ...), switched by distance as THREE.LOD does, with the distances
// converted from the node's extras.MSFT_screencoverage. Written for the harness
// (lod_threejs.mjs, docs/harness.md "THREE.LOD from MSFT_lod"); it knows nothing of lodopt
// beyond the file.
//
//   loader.register((parser) => new MSFTLodPlugin(parser, { fovYDegrees: 60 }));
//
// Conventions (MSFT_screencoverage = [c_0, ..., c_(L-1)], level k drawn while the object's size
// on screen is at least c_k, the last value 0):
//  - What a value measures: asset.extras.lodopt_screencoverage says it. "unity_relative_height"
//    (what lodopt thresholds writes; UnityGLTF's reading): the level-0 world bounds' largest box
//    extent e over the view height at the camera's distance d, e / (2 d tan(fovY/2)). Without the
//    mark (or with an unknown one), a screen size as lodopt reads unmarked files: the bounds'
//    sphere diameter 2r over the view height, 2r / (2 d tan(fovY/2)). `options.coverage`
//    ('unity_relative_height' or 'screen_size') overrides the mark.
//  - Bounds as lodopt computes them (scenes::worldBounds of level 0): the box of every vertex of
//    the level-0 node's meshes in the node's own space (descendants' vertices carried into it;
//    descendants with their own MSFT_lod left out), its 8 corners through the node's world
//    matrix, boxed again; r is half that box's diagonal, e its largest side, its centre c.
//  - Distances: level k+1 from d_(k+1) = e / (2 c_k tan(fovY/2)) (relative heights) or
//    r / (c_k tan(fovY/2)) (screen sizes) on; a value <= 0 before the last level makes the
//    coarser levels unreachable (distance Infinity). A node without MSFT_screencoverage (or
//    with fewer values than levels - 1) gets the screen sizes 1, 1/2, 1/4, ... (lodopt's
//    thresholds for an object no view fitted) and lod.userData.msftLod.coverageSource
//    'default'.
//  - Placement: the THREE.LOD takes the level-0 node's place in its parent, positioned at c
//    (THREE.LOD measures from its own position), each level node keeps its world placement
//    (its translation moved by -c in the parent's space); level nodes are placed like the
//    level-0 node under its parent, as the extension says.
//  - Field of view: distances hold for one vertical field of view, options.fovYDegrees (45 by
//    default); setLodFieldOfView(lod, fov) recomputes them for a camera with another one (a
//    screen-size rule does not depend on the lens, a distance does).
// Each LOD has lod.userData.msftLod = {node, name, levels, coverage, convention, coverageSource,
// center, extent, radius, fovYDegrees, distances, placementError (the largest relative
// difference between a level's world matrix under the LOD and the file's)}; plugin.lods lists
// them in node order.
import * as THREE from 'three';

export const kUnityRelativeHeight = 'unity_relative_height';
export const kScreenSize = 'screen_size';

// Level k+1's switch distance for each value c_k, k = 0 .. levels - 2 (see above).
export function lodDistances(info, fovYDegrees) {
    const tanHalf = Math.tan(THREE.MathUtils.degToRad(fovYDegrees) / 2);
    const distances = [0];
    for (let k = 0; k + 1 < info.levels; ++k) {
        const c = info.coverage[k];
        const size = info.convention === kUnityRelativeHeight ? info.extent : 2 * info.radius;
        distances.push(c > 0 ? size / (2 * c * tanHalf) : Infinity);
    }
    return distances;
}

// Sets the distances of an LOD made by the plugin for a camera of vertical field of view `fov`.
export function setLodFieldOfView(lod, fovYDegrees) {
    const info = lod.userData.msftLod;
    if (info.fovYDegrees === fovYDegrees) return;
    info.fovYDegrees = fovYDegrees;
    info.distances = lodDistances(info, fovYDegrees);
    // addLevel keeps the levels sorted by distance; the distances never decrease with k for
    // non-increasing coverage, so level k stays levels[k] (equal distances keep their order).
    for (let k = 0; k < lod.levels.length; ++k) lod.levels[k].distance = info.distances[k];
    lod.levels.sort((a, b) => a.distance - b.distance);
}

// The box of every vertex under `node` in `node`'s space, leaving out subtrees for which
// `skip(object)` is true (below `node`).
function localVertexBox(node, skip) {
    const box = new THREE.Box3();
    const vertex = new THREE.Vector3();
    const visit = (object, toNode) => {
        const position = object.geometry && object.geometry.attributes && object.geometry.attributes.position;
        if (position) {
            if (toNode.equals(new THREE.Matrix4())) {
                object.geometry.computeBoundingBox();
                box.union(object.geometry.boundingBox);
            } else {
                for (let i = 0; i < position.count; ++i) box.expandByPoint(vertex.fromBufferAttribute(position, i).applyMatrix4(toNode));
            }
        }
        for (const child of object.children) {
            if (skip(child)) continue;
            visit(child, toNode.clone().multiply(child.matrix));
        }
    };
    node.traverse((object) => object.updateMatrix());
    visit(node, new THREE.Matrix4());
    return box;
}

export class MSFTLodPlugin {
    constructor(parser, options = {}) {
        this.name = 'MSFT_lod';
        this.parser = parser;
        this.options = { fovYDegrees: 45, coverage: undefined, ...options };
        this.lods = [];
    }

    // The convention of MSFT_screencoverage in this file (see the header).
    convention() {
        if (this.options.coverage) return this.options.coverage;
        const extras = this.parser.json.asset && this.parser.json.asset.extras;
        return extras && extras.lodopt_screencoverage === kUnityRelativeHeight ? kUnityRelativeHeight : kScreenSize;
    }

    async afterRoot(result) {
        const parser = this.parser;
        const nodeDefs = parser.json.nodes || [];
        const nodeIndex = (object) => {
            const association = parser.associations.get(object);
            return association && association.nodes !== undefined ? association.nodes : undefined;
        };
        const hasLod = (object) => {
            const index = nodeIndex(object);
            return index !== undefined && Boolean(nodeDefs[index].extensions && nodeDefs[index].extensions.MSFT_lod);
        };
        // Level-0 objects first (the scene graph changes below), in node order.
        const found = [];
        for (const scene of result.scenes) scene.traverse((object) => { if (hasLod(object)) found.push(object); });
        found.sort((a, b) => nodeIndex(a) - nodeIndex(b));
        const convention = this.convention();
        const placements = [];
        for (const node of found) {
            const index = nodeIndex(node);
            const nodeDef = nodeDefs[index];
            const ids = Array.isArray(nodeDef.extensions.MSFT_lod.ids) ? nodeDef.extensions.MSFT_lod.ids : [];
            const levelNodes = [node];
            for (const id of ids) levelNodes.push(await parser.getDependency('node', id));
            const parent = node.parent;
            parent.updateWorldMatrix(true, false);
            node.updateMatrixWorld(true);
            const world = localVertexBox(node, (object) => object !== node && hasLod(object)).applyMatrix4(node.matrixWorld);
            const center = world.getCenter(new THREE.Vector3());
            const size = world.getSize(new THREE.Vector3());
            const extent = Math.max(size.x, size.y, size.z);
            const radius = size.length() / 2;
            const values = nodeDef.extras && Array.isArray(nodeDef.extras.MSFT_screencoverage) ? nodeDef.extras.MSFT_screencoverage : null;
            const levels = levelNodes.length;
            const usable = values && values.length >= levels - 1 && values.slice(0, levels - 1).every((v) => Number.isFinite(v));
            const info = {
                node: index, name: nodeDef.name === undefined ? null : nodeDef.name, levels,
                coverage: usable ? values.slice(0, levels).map(Number) : Array.from({ length: levels }, (_, k) => (k + 1 < levels ? 2 ** -k : 0)),
                convention: usable ? convention : kScreenSize,
                coverageSource: usable ? 'file' : 'default',
                center: center.toArray(), extent, radius, fovYDegrees: this.options.fovYDegrees,
            };
            info.distances = lodDistances(info, info.fovYDegrees);

            // Each level's world matrix as the file places it (level nodes like level 0 under its parent).
            const placed = levelNodes.map((level) => {
                level.updateMatrix();
                return parent.matrixWorld.clone().multiply(level.matrix);
            });
            placements.push({ info, levelNodes, placed });

            const lod = new THREE.LOD();
            lod.name = node.name;
            lod.userData.msftLod = info;
            const centerInParent = parent.worldToLocal(center.clone());
            lod.position.copy(centerInParent);
            parent.add(lod);
            parent.remove(node);
            for (let k = 0; k < levels; ++k) {
                const level = levelNodes[k];
                if (level.parent) level.parent.remove(level);
                level.position.sub(centerInParent);  // T(-c) M: same world placement under the LOD
                lod.addLevel(level, info.distances[k], 0);
            }
            // Keep the associations for the level-0 node and the LOD (for users of parser.associations).
            parser.associations.set(lod, { nodes: index });
            this.lods.push(lod);
        }
        for (const scene of result.scenes) scene.updateMatrixWorld(true);
        // Self-check: under its LOD every level keeps the world placement the file gives it
        // (largest difference of a matrix element, relative to the matrix's largest).
        for (const { info, levelNodes, placed } of placements) {
            info.placementError = 0;
            levelNodes.forEach((level, k) => {
                const a = level.matrixWorld.elements, b = placed[k].elements;
                const scale = Math.max(1, ...b.map(Math.abs));
                for (let i = 0; i < 16; ++i) info.placementError = Math.max(info.placementError, Math.abs(a[i] - b[i]) / scale);
            });
        }
        result.userData.msftLods = this.lods;
    }
}
