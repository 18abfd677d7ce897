// The THREE.LOD side of lod_threejs.mjs, run by headless Chromium on page.html?page=lod_page.mjs.
// Jobs (from /jobs): first {kind: 'load', url, coverage, fov_y_degrees}: the model loaded by
// GLTFLoader with MSFTLodPlugin (msft_lod_plugin.mjs), its result every LOD's userData.msftLod;
// then one {kind: 'camera', view} per camera: lod.update(camera) on every LOD (hysteresis 0, the
// distances set for the camera's field of view), its result lod.getCurrentLevel() per LOD in the
// load result's order. Each result goes to /result/<index>, then /done. Nothing is drawn: THREE.LOD
// picks its level from the camera's distance alone.
import { Vector3 } from 'three';
import { makeCamera, makeLoader, post } from './page_common.mjs';
import { MSFTLodPlugin, setLodFieldOfView } from './msft_lod_plugin.mjs';

const log = (message) => post('/log', { message: String(message) });
window.addEventListener('error', (event) => log(`page error: ${event.message}`));
window.addEventListener('unhandledrejection', (event) => log(`unhandled rejection: ${event.reason}`));

async function main() {
    const jobs = await (await fetch('/jobs')).json();
    let lods = null;
    for (let index = 0; index < jobs.length; ++index) {
        const job = jobs[index];
        const start = performance.now();
        try {
            if (job.kind === 'load') {
                const loader = makeLoader();
                let plugin = null;
                loader.register((parser) => (plugin = new MSFTLodPlugin(parser, { fovYDegrees: job.fov_y_degrees, coverage: job.coverage })));
                const gltf = await loader.loadAsync(job.url);
                const json = gltf.parser.json;
                lods = plugin.lods;
                for (const lod of lods) lod.updateMatrixWorld(true);
                await post(`/result/${index}`, {
                    // Where THREE.LOD measures from: its world position.
                    lods: lods.map((lod) => ({ ...lod.userData.msftLod, position: lod.getWorldPosition(new Vector3()).toArray() })),
                    convention_mark: (json.asset && json.asset.extras && json.asset.extras.lodopt_screencoverage) || null,
                    ms: performance.now() - start,
                });
                continue;
            }
            if (!lods) throw new Error('no model loaded');
            const camera = makeCamera({ up: [0, 1, 0], near: 0.1, far: 1e6, ...job.view }, job.view.aspect || 1);
            const levels = lods.map((lod) => {
                setLodFieldOfView(lod, camera.fov);
                lod.update(camera);
                return lod.getCurrentLevel();
            });
            await post(`/result/${index}`, { levels, ms: performance.now() - start });
        } catch (error) {
            await post(`/result/${index}`, { error: String(error && error.stack ? error.stack : error) });
        }
    }
    await post('/done', {});
}

main().catch((error) => post('/done', { error: String(error && error.stack ? error.stack : error) }));
