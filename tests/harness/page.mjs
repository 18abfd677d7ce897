// The three.js reference renderer, run by headless Chromium on page.html (render_threejs.mjs
// serves both on 127.0.0.1). It fetches /jobs, renders each one and posts the result to
// /result/<index>, then posts /done. three.js is set up to match lodopt's PBR rig
// (docs/renderer.md, docs/harness.md "The rig"), not the other way round.
import * as THREE from 'three';
import { makeCamera, makeLoader, post } from './page_common.mjs';

// The key light travels along this world direction; it sits at -kKeyDirection.
const kKeyDirection = new THREE.Vector3(-0.4, -1.0, -0.3).normalize();
const kKeyIlluminance = 2.5;
// The sky: background bytes (158, 194, 230), never tone mapped.
const kSky = new THREE.Color().setRGB(158 / 255, 194 / 255, 230 / 255, THREE.SRGBColorSpace);

const log = (message) => post('/log', { message: String(message) });
window.addEventListener('error', (event) => log(`page error: ${event.message}`));
window.addEventListener('unhandledrejection', (event) => log(`unhandled rejection: ${event.reason}`));

function makeRenderer() {
    const canvas = document.createElement('canvas');
    const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true, alpha: false });
    renderer.setPixelRatio(1);
    renderer.outputColorSpace = THREE.SRGBColorSpace;
    renderer.toneMapping = THREE.NeutralToneMapping;
    renderer.toneMappingExposure = 1;
    renderer.shadowMap.enabled = false;
    renderer.setClearColor(kSky, 1);
    return renderer;
}

// Key light (directional, white, illuminance 2.5) and ambient (hemisphere, sky 1, ground 0.3,
// linear), which is all the light there is: no environment map, no shadows, no fog.
function addRig(scene, { key = true, hemisphere = true } = {}) {
    if (key) {
        const light = new THREE.DirectionalLight(0xffffff, kKeyIlluminance);
        light.position.copy(kKeyDirection).multiplyScalar(-1);  // three lights along position - target
        light.target.position.set(0, 0, 0);
        scene.add(light, light.target);
    }
    if (hemisphere) {
        const light = new THREE.HemisphereLight();
        light.color.setRGB(1, 1, 1, THREE.LinearSRGBColorSpace);
        light.groundColor.setRGB(0.3, 0.3, 0.3, THREE.LinearSRGBColorSpace);
        light.intensity = 1;
        light.position.set(0, 1, 0);  // up = +Y
        scene.add(light);
    }
    scene.background = kSky;
}

function dispose(root) {
    root.traverse((object) => {
        if (object.geometry) object.geometry.dispose();
        const materials = Array.isArray(object.material) ? object.material : object.material ? [object.material] : [];
        for (const material of materials) {
            for (const value of Object.values(material)) if (value && value.isTexture) value.dispose();
            material.dispose();
        }
    });
}

// A white Lambertian-looking surface (base color 1, metallic 0, roughness `roughness`) facing
// the key light, seen from the light's side (view = light = normal direction): the linear
// radiance three.js computes before tone mapping, read from a float render target, for the key
// light alone, the hemisphere alone and both; then the sRGB bytes it writes with both.
function probeLighting(renderer, roughness) {
    const normal = kKeyDirection.clone().multiplyScalar(-1);
    const plane = new THREE.Mesh(new THREE.PlaneGeometry(10, 10),
        new THREE.MeshStandardMaterial({ color: 0xffffff, roughness, metalness: 0 }));
    plane.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), normal);
    const camera = new THREE.PerspectiveCamera(10, 1, 0.1, 100);
    camera.position.copy(normal).multiplyScalar(5);
    camera.up.set(0, 0, 1);
    camera.lookAt(0, 0, 0);
    const target = new THREE.WebGLRenderTarget(8, 8, { type: THREE.FloatType });
    const result = { roughness, normal: normal.toArray() };
    for (const [name, lights] of [['key', { key: true, hemisphere: false }],
                                  ['hemisphere', { key: false, hemisphere: true }],
                                  ['both', { key: true, hemisphere: true }]]) {
        const scene = new THREE.Scene();
        addRig(scene, lights);
        scene.add(plane);
        renderer.setRenderTarget(target);
        renderer.render(scene, camera);
        const pixel = new Float32Array(4);
        renderer.readRenderTargetPixels(target, 4, 4, 1, 1, pixel);
        result[`linear_${name}`] = Array.from(pixel.slice(0, 3));
        scene.remove(plane);
    }
    const scene = new THREE.Scene();
    addRig(scene);
    scene.add(plane);
    renderer.setRenderTarget(null);
    renderer.setSize(8, 8, false);
    renderer.render(scene, camera);
    const gl = renderer.getContext();
    const bytes = new Uint8Array(4);
    gl.readPixels(4, 4, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
    result.srgb_bytes_both = Array.from(bytes.slice(0, 3));
    target.dispose();
    dispose(plane);
    return result;
}

async function main() {
    const jobs = await (await fetch('/jobs')).json();
    const renderer = makeRenderer();
    const loader = makeLoader(renderer);
    let loaded = null;  // { url, gltf }: consecutive views of one model load it once
    for (let index = 0; index < jobs.length; ++index) {
        const job = jobs[index];
        const start = performance.now();
        try {
            if (job.kind === 'probe') {
                const probes = [1.0, 0.5].map((roughness) => probeLighting(renderer, roughness));
                await post(`/result/${index}`, { probes, ms: performance.now() - start });
                continue;
            }
            if (!loaded || loaded.url !== job.url) {
                if (loaded) dispose(loaded.gltf.scene);
                loaded = null;
                loaded = { url: job.url, gltf: await loader.loadAsync(job.url) };
            }
            const loadMs = performance.now() - start;
            const scene = new THREE.Scene();
            addRig(scene);
            const model = loaded.gltf.scene;
            model.traverse((object) => { object.frustumCulled = false; });  // lodopt culls nothing
            scene.add(model);
            renderer.setRenderTarget(null);
            renderer.setSize(job.width, job.height, false);
            const camera = makeCamera(job.view, job.width / job.height);
            renderer.render(scene, camera);
            const png = renderer.domElement.toDataURL('image/png');
            scene.remove(model);
            await post(`/result/${index}`, { png, ms: performance.now() - start, load_ms: loadMs });
        } catch (error) {
            await post(`/result/${index}`, { error: String(error && error.stack ? error.stack : error) });
        }
    }
    if (loaded) dispose(loaded.gltf.scene);
    await post('/done', {});
}

main().catch((error) => post('/done', { error: String(error && error.stack ? error.stack : error) }));
