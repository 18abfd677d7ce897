// What the harness's browser pages share (page.mjs renders, lod_page.mjs runs THREE.LOD): the
// POST back to the loopback server, lodopt's camera as a three.js camera, and the GLTFLoader
// with the decoders served from node_modules (nothing is fetched from anywhere else).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { DRACOLoader } from 'three/addons/loaders/DRACOLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';

export async function post(path, body) {
    await fetch(path, { method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body) });
}

// lodopt's camera (scenes::viewMatrix, projectionMatrix): glm::lookAt and glm::perspective,
// including its replacement of an up vector parallel to the view direction.
export function makeCamera(view, aspect) {
    const camera = new THREE.PerspectiveCamera(view.fov_y_degrees, aspect, view.near, view.far);
    const position = new THREE.Vector3().fromArray(view.position);
    const target = new THREE.Vector3().fromArray(view.target);
    const forward = target.clone().sub(position);
    let up = new THREE.Vector3().fromArray(view.up);
    if (new THREE.Vector3().crossVectors(forward, up).length() < 1e-6 * forward.length()) {
        up = Math.abs(forward.y) > Math.abs(forward.z) ? new THREE.Vector3(0, 0, 1) : new THREE.Vector3(0, 1, 0);
    }
    camera.position.copy(position);
    camera.up.copy(up);
    camera.lookAt(target);
    camera.updateProjectionMatrix();
    camera.updateMatrixWorld(true);
    return camera;
}

// GLTFLoader with MeshoptDecoder and DRACOLoader (three's wasm decoder, served locally).
export function makeLoader() {
    const draco = new DRACOLoader();
    draco.setDecoderPath('/three/examples/jsm/libs/draco/');
    draco.setDecoderConfig({ type: 'wasm' });
    const loader = new GLTFLoader();
    loader.setDRACOLoader(draco);
    loader.setMeshoptDecoder(MeshoptDecoder);
    return loader;
}
