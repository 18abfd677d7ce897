#!/usr/bin/env node
// Renders glTF/GLB files with three.js in headless Chromium, set up as lodopt's PBR rig
// (docs/harness.md). A loopback HTTP server (127.0.0.1, a free port) serves page.html, three.js
// from node_modules and the models' folders, hands the page the list of jobs and receives one
// PNG per job by POST; one Chromium process renders a whole batch. Nothing is fetched from
// anywhere else. The server and Chromium's launch are runPageInChromium, which lod_threejs.mjs
// runs with its own page module (lod_page.mjs).
//
//   node render_threejs.mjs --model F.gltf --position X,Y,Z --target X,Y,Z [--up 0,1,0]
//        [--fov 45] [--near 0.1] [--far 1000] [--size 256x256] --out image.png
//   node render_threejs.mjs --model F.gltf --view V --lodopt build/cli/lodopt ...   (camera V of
//        `lodopt scene info F --json`)
//   node render_threejs.mjs --jobs jobs.json   ([{model, view: {position, target, up,
//        fov_y_degrees, near, far}, width, height, out}, ...])
//   node render_threejs.mjs --probe            (three.js's lighting of a white surface, JSON)
// Options: --chromium PATH (else $LODOPT_CHROMIUM, else chromium in PATH), --job-timeout S
// (60: seconds without progress, the first job includes Chromium's start), --json.
// Exit: 0 every job rendered, 1 a job or Chromium failed, 2 bad usage.
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const kHarnessDir = path.dirname(fileURLToPath(import.meta.url));
const kThreeDir = path.join(kHarnessDir, 'node_modules', 'three');
const kContentTypes = {
    '.html': 'text/html', '.mjs': 'text/javascript', '.js': 'text/javascript', '.wasm': 'application/wasm',
    '.json': 'application/json', '.gltf': 'model/gltf+json', '.glb': 'model/gltf-binary', '.png': 'image/png',
    '.jpg': 'image/jpeg', '.jpeg': 'image/jpeg', '.webp': 'image/webp', '.ktx2': 'image/ktx2',
};

// The Chromium to run: `explicit`, else $LODOPT_CHROMIUM, else the first of the usual names in PATH.
export function findChromium(explicit) {
    const candidates = explicit ? [explicit]
        : process.env.LODOPT_CHROMIUM ? [process.env.LODOPT_CHROMIUM]
        : ['chromium', 'chromium-browser', 'google-chrome'];
    for (const candidate of candidates) {
        if (candidate.includes('/')) { if (fs.existsSync(candidate)) return candidate; continue; }
        for (const dir of (process.env.PATH || '').split(':')) {
            const full = path.join(dir, candidate);
            if (dir && fs.existsSync(full)) return full;
        }
    }
    return null;
}

// Writes `bytes` to `file` through a temporary name and a rename.
export function writeFileAtomically(file, bytes) {
    const temporary = `${file}.tmp${process.pid}`;
    fs.writeFileSync(temporary, bytes);
    fs.renameSync(temporary, file);
}

// Serves `root`-relative `relative` (already URL-decoded) when it stays inside `root`.
function serveFile(response, root, relative) {
    const full = path.resolve(root, relative);
    if (full !== root && !full.startsWith(root + path.sep)) return notFound(response);
    fs.readFile(full, (error, bytes) => {
        if (error) return notFound(response);
        response.writeHead(200, { 'Content-Type': kContentTypes[path.extname(full).toLowerCase()] || 'application/octet-stream',
                                  'Cache-Control': 'no-store' });
        response.end(bytes);
    });
}
function notFound(response) { response.writeHead(404); response.end(); }

function readBody(request) {
    return new Promise((resolve, reject) => {
        const chunks = [];
        request.on('data', (chunk) => chunks.push(chunk));
        request.on('end', () => resolve(Buffer.concat(chunks).toString('utf8')));
        request.on('error', reject);
    });
}

// The browser modules page.html may load (served as /harness/<name>): page.mjs renders,
// lod_page.mjs runs THREE.LOD (lod_threejs.mjs); the others are modules they import.
const kPageModules = new Set(['page.mjs', 'page_common.mjs', 'lod_page.mjs', 'msft_lod_plugin.mjs']);

// The URL under which runPageInChromium serves `file`: its folder is added to `modelDirs` (served
// as /model/<index>/...) when it is not there yet.
export function modelUrl(modelDirs, file) {
    const model = path.resolve(file);
    const dir = path.dirname(model);
    let id = modelDirs.indexOf(dir);
    if (id < 0) id = modelDirs.push(dir) - 1;
    return `/model/${id}/${encodeURIComponent(path.basename(model))}`;
}

// Runs the browser module `page` (one of kPageModules) in one headless Chromium on a loopback
// server that serves page.html, three.js from node_modules and the folders in `modelDirs`, and
// hands the page `jobs` at /jobs. Each POST /result/<index> calls `onResult(index, body)`; the
// page ends with POST /done. `jobTimeoutSeconds`: the longest wait for the next result before
// Chromium is killed. Resolves to {failure (null when the page finished), received (results)};
// rejects when Chromium or three.js cannot be found.
export async function runPageInChromium({ page = 'page.mjs', jobs, modelDirs = [], onResult, chromium, jobTimeoutSeconds = 60,
                                          log = () => {} }) {
    const executable = findChromium(chromium);
    if (!executable) throw new Error('Chromium not found: install Debian\'s chromium (scripts/quickstart.sh does) or set LODOPT_CHROMIUM');
    if (!fs.existsSync(path.join(kThreeDir, 'build', 'three.module.js'))) {
        throw new Error(`three.js not found in ${kThreeDir}: run npm ci --prefix tests/harness (scripts/quickstart.sh does)`);
    }
    if (!kPageModules.has(page)) throw new Error(`unknown page module ${page}`);
    let received = 0;
    let finish;
    const finished = new Promise((resolve) => { finish = resolve; });

    const server = http.createServer(async (request, response) => {
        try {
            const url = new URL(request.url, 'http://127.0.0.1');
            const parts = url.pathname.split('/').slice(1).map(decodeURIComponent);
            if (request.method === 'GET') {
                if (url.pathname === '/') return serveFile(response, kHarnessDir, 'page.html');
                if (url.pathname === '/jobs') { response.writeHead(200, { 'Content-Type': 'application/json' }); return response.end(JSON.stringify(jobs)); }
                if (parts[0] === 'harness' && parts.length === 2 && kPageModules.has(parts[1])) return serveFile(response, kHarnessDir, parts[1]);
                if (parts[0] === 'three') return serveFile(response, kThreeDir, parts.slice(1).join('/'));
                if (parts[0] === 'model' && modelDirs[Number(parts[1])] !== undefined) {
                    return serveFile(response, modelDirs[Number(parts[1])], parts.slice(2).join('/'));
                }
                if (url.pathname === '/favicon.ico') return notFound(response);
                log(`unexpected request ${url.pathname}`);
                return notFound(response);
            }
            const body = JSON.parse((await readBody(request)) || '{}');
            response.writeHead(204);
            response.end();
            if (parts[0] === 'log') return log(`page: ${body.message}`);
            if (parts[0] === 'done') return finish(body.error ? `page failed: ${body.error}` : null);
            if (parts[0] === 'result') {
                const index = Number(parts[1]);
                if (!(index >= 0 && index < jobs.length)) return;
                ++received;
                watchdog.refresh();
                onResult(index, body);
            }
        } catch (error) {
            log(`server: ${error.stack || error}`);
            if (!response.headersSent) { response.writeHead(500); response.end(); }
        }
    });
    await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
    const port = server.address().port;
    const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'lodopt-chromium-'));
    const pageQuery = page === 'page.mjs' ? '' : `?page=${encodeURIComponent(page)}`;
    const browser = spawn(executable, [
        '--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
        `--user-data-dir=${profile}`, '--no-first-run', '--no-default-browser-check', '--disable-extensions',
        '--disable-background-networking', '--disable-component-update', '--disable-sync', '--mute-audio',
        '--disable-background-timer-throttling', '--disable-renderer-backgrounding',
        `http://127.0.0.1:${port}/${pageQuery}`,
    ], { stdio: ['ignore', 'ignore', 'pipe'], detached: true });
    let browserErrors = '';
    browser.stderr.on('data', (chunk) => { browserErrors = (browserErrors + chunk).slice(-4000); });
    browser.on('exit', (code, signal) => finish(`Chromium exited (${signal || code}) after ${received} of ${jobs.length} results`));
    browser.on('error', (error) => finish(`Chromium did not start: ${error.message}`));
    const watchdog = setTimeout(() => finish(`no result from Chromium for ${jobTimeoutSeconds} s after ${received} of ${jobs.length}`),
        jobTimeoutSeconds * 1000);

    const failure = await finished;
    clearTimeout(watchdog);
    browser.removeAllListeners('exit');
    if (browser.exitCode === null && browser.signalCode === null) {
        try { process.kill(-browser.pid, 'SIGKILL'); } catch { /* already gone */ }
        // The 5 s fallback is cleared on exit: a pending timer would keep node alive 5 s longer.
        await new Promise((resolve) => {
            const fallback = setTimeout(resolve, 5000);
            browser.once('exit', () => { clearTimeout(fallback); resolve(); });
        });
    }
    server.closeAllConnections();
    server.close();
    fs.rmSync(profile, { recursive: true, force: true });
    if (failure) {
        log(failure);
        if (received < jobs.length) log(`Chromium's last messages:\n${browserErrors}`);
    }
    return { failure, received };
}

// Renders `jobs` in one Chromium; resolves to one result per job: {ok, out?, ms?, error?} (and
// {probes} for a probe job). Jobs: {model, view, width, height, out} or {kind: 'probe'}.
// `jobTimeoutSeconds`: the longest wait for the next result before Chromium is killed and the
// jobs left fail. Never rejects for a job's failure; rejects when Chromium cannot be found.
export async function renderWithThreeJs(jobs, { chromium, jobTimeoutSeconds = 60, log = () => {} } = {}) {
    const modelDirs = [];  // served as /model/<index>/...
    const pageJobs = jobs.map((job) => {
        if (job.kind === 'probe') return job;
        return { url: modelUrl(modelDirs, job.model), view: job.view, width: job.width, height: job.height };
    });
    const results = jobs.map(() => ({ ok: false, error: 'not rendered' }));
    const onResult = (index, body) => {
        const job = jobs[index];
        if (body.error) results[index] = { ok: false, error: body.error };
        else if (job.kind === 'probe') results[index] = { ok: true, probes: body.probes, ms: body.ms };
        else {
            const png = Buffer.from(body.png.replace(/^data:image\/png;base64,/, ''), 'base64');
            writeFileAtomically(job.out, png);
            results[index] = { ok: true, out: job.out, ms: body.ms, load_ms: body.load_ms };
        }
    };
    const { failure } = await runPageInChromium({ page: 'page.mjs', jobs: pageJobs, modelDirs, onResult, chromium, jobTimeoutSeconds, log });
    if (failure) {
        for (const result of results) if (!result.ok && result.error === 'not rendered') result.error = failure;
    }
    return results;
}

// The views of `model` as `lodopt scene info --json` prints them.
export function lodoptViews(lodopt, model) {
    const run = spawnSync(lodopt, ['scene', 'info', model, '--json'], { encoding: 'utf8', maxBuffer: 1 << 28 });
    if (run.status !== 0) throw new Error(`lodopt scene info ${model}: exit ${run.status}: ${(run.stderr || '').trim()}`);
    return JSON.parse(run.stdout).views;
}

function parseVector(text, name) {
    const values = String(text).split(',').map(Number);
    if (values.length !== 3 || values.some((v) => !Number.isFinite(v))) throw new UsageError(`${name}: expected X,Y,Z`);
    return values;
}
export function parseSize(text) {
    const match = /^(\d+)x(\d+)$/.exec(String(text));
    if (!match || Number(match[1]) < 1 || Number(match[2]) < 1) throw new UsageError(`--size: expected WIDTHxHEIGHT, got '${text}'`);
    return [Number(match[1]), Number(match[2])];
}
export class UsageError extends Error {}

// --name value pairs (names in `names`) and bare --flags (names in `flags`).
export function parseArguments(argv, names, flags = []) {
    const options = {};
    for (let i = 0; i < argv.length; ++i) {
        const word = argv[i];
        if (!word.startsWith('--')) throw new UsageError(`unexpected argument '${word}'`);
        const name = word.slice(2);
        if (!names.includes(name) && !flags.includes(name)) throw new UsageError(`unknown option ${word}`);
        if (flags.includes(name)) options[name] = true;
        else if (i + 1 < argv.length) options[name] = argv[++i];
        else throw new UsageError(`${word} needs a value`);
    }
    return options;
}

async function main() {
    const options = parseArguments(process.argv.slice(2), ['model', 'position', 'target', 'up', 'fov', 'near', 'far', 'size', 'out',
        'view', 'lodopt', 'jobs', 'chromium', 'job-timeout'], ['probe', 'json']);
    const log = (message) => process.stderr.write(`render_threejs: ${message}\n`);
    let jobs;
    if (options.probe) jobs = [{ kind: 'probe' }];
    else if (options.jobs) jobs = JSON.parse(fs.readFileSync(options.jobs, 'utf8'));
    else {
        if (!options.model || !options.out) throw new UsageError('give --model and --out, or --jobs FILE, or --probe');
        const [width, height] = parseSize(options.size || '256x256');
        let view;
        if (options.view !== undefined) {
            if (!options.lodopt) throw new UsageError('--view needs --lodopt (the camera comes from lodopt scene info)');
            const views = lodoptViews(options.lodopt, options.model);
            view = /^\d+$/.test(options.view) ? views[Number(options.view)] : views.find((v) => v.name === options.view);
            if (!view) throw new UsageError(`--view ${options.view}: ${options.model} has views ${views.map((v) => v.name).join(', ')}`);
        } else {
            if (!options.position || !options.target) throw new UsageError('give --position and --target, or --view with --lodopt');
            view = {
                position: parseVector(options.position, '--position'), target: parseVector(options.target, '--target'),
                up: parseVector(options.up || '0,1,0', '--up'), fov_y_degrees: Number(options.fov || 45),
                near: Number(options.near || 0.1), far: Number(options.far || 1000),
            };
        }
        jobs = [{ model: options.model, view, width, height, out: options.out }];
    }
    const results = await renderWithThreeJs(jobs, { chromium: options.chromium, jobTimeoutSeconds: Number(options['job-timeout'] || 60), log });
    if (options.json || options.probe) process.stdout.write(JSON.stringify(results.length === 1 ? results[0] : results, null, 2) + '\n');
    for (const [index, result] of results.entries()) if (!result.ok) log(`job ${index} (${jobs[index].model || 'probe'}): ${result.error}`);
    return results.every((result) => result.ok) ? 0 : 1;
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
    // exitCode, not exit(): a large JSON written to a pipe must drain before node ends.
    main().then((code) => { process.exitCode = code; }, (error) => {
        process.stderr.write(`render_threejs: ${error instanceof UsageError ? '' : 'error: '}${error.message}\n`);
        process.exitCode = error instanceof UsageError ? 2 : 1;
    });
}
