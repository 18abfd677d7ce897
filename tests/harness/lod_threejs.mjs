#!/usr/bin/env node
// "A real consumer agrees": loads a glTF/GLB with MSFT_lod (lodopt thresholds' <scene>.lod.glb)
// with three.js's GLTFLoader and the harness's MSFT_lod plugin (msft_lod_plugin.mjs: one
// THREE.LOD per MSFT_lod node, distances from extras.MSFT_screencoverage) in headless Chromium,
// and for each camera records the level THREE.LOD picks for every LOD (lod.update(camera),
// hysteresis 0, lod.getCurrentLevel()). Also runs the Khronos glTF-Validator on the file.
// Served and launched as render_threejs.mjs does (runPageInChromium); docs/harness.md.
//
//   node lod_threejs.mjs --model M.lod.glb --cameras CAMS.json --out LEVELS.json
//        [--coverage auto|unity_relative_height|screen_size] [--fov DEG] [--chromium PATH]
//        [--job-timeout S] [--json]
// CAMS.json: [{position: [x, y, z], target: [x, y, z], up?, fov_y_degrees, near?, far?, aspect?},
// ...] or {cameras: [...]}. --coverage: how to read MSFT_screencoverage (auto: as
// asset.extras.lodopt_screencoverage says, screen sizes without it). --fov: the field of view
// the LODs are built for (default the first camera's; a camera with another one gets its
// distances recomputed, see msft_lod_plugin.mjs).
// LEVELS.json: {format: "lodopt-lod-threejs", model, three, coverage_mark, validator: {errors,
// warnings, infos, hints, codes: {CODE: count}}, lods: [{node, name, levels, coverage, convention,
// coverage_source, center (of the level-0 world bounds), position (the LOD's, world), extent,
// radius, distances (for --fov), placement_error (levels' world matrices under the LOD against the
// file's, relative)}, ...], cameras: [{view,
// levels: [level of lods[i], ...]}, ...], seconds: {validator, chromium}}.
// Exit: 0 the file loaded and every camera ran (whatever the validator says: its counts are in
// the output), 1 Chromium, the page or a camera failed, 2 bad usage.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { modelUrl, parseArguments, runPageInChromium, UsageError, writeFileAtomically } from './render_threejs.mjs';
import { loadValidator, validatorReport } from './validate_corpus.mjs';

const kHarnessDir = path.dirname(fileURLToPath(import.meta.url));
const kConventions = ['auto', 'unity_relative_height', 'screen_size'];

// The validator's counts for `file`, and how often each code occurs.
export async function validatorCounts(file) {
    const report = await validatorReport(loadValidator(), file);
    const codes = {};
    for (const message of report.issues.messages) codes[message.code] = (codes[message.code] || 0) + 1;
    return {
        errors: report.issues.numErrors, warnings: report.issues.numWarnings, infos: report.issues.numInfos,
        hints: report.issues.numHints, codes,
    };
}

// Loads `model` in Chromium with the MSFT_lod plugin and runs every camera; resolves to
// {lods, cameras: [{levels}], coverage_mark} or rejects naming what failed.
export async function lodLevelsWithThreeJs(model, cameras, { coverage = 'auto', fovYDegrees, chromium, jobTimeoutSeconds = 120,
                                                              log = () => {} } = {}) {
    const modelDirs = [];
    const fov = fovYDegrees !== undefined ? fovYDegrees : cameras.length ? cameras[0].fov_y_degrees : 45;
    const jobs = [{ kind: 'load', url: modelUrl(modelDirs, model), coverage: coverage === 'auto' ? undefined : coverage, fov_y_degrees: fov },
        ...cameras.map((view) => ({ kind: 'camera', view }))];
    const results = new Array(jobs.length).fill(null);
    const { failure } = await runPageInChromium({ page: 'lod_page.mjs', jobs, modelDirs, chromium, jobTimeoutSeconds, log,
        onResult: (index, body) => { results[index] = body; } });
    if (failure) throw new Error(failure);
    const errors = results.map((result, index) => (result === null ? `job ${index}: no result` : result.error ? `job ${index}: ${result.error}` : null))
        .filter(Boolean);
    if (errors.length) throw new Error(errors.slice(0, 5).join('\n'));
    return {
        coverage_mark: results[0].convention_mark,
        load_ms: results[0].ms,
        lods: results[0].lods.map((info) => ({
            node: info.node, name: info.name, levels: info.levels, coverage: info.coverage, convention: info.convention,
            coverage_source: info.coverageSource, center: info.center, position: info.position, extent: info.extent, radius: info.radius,
            fov_y_degrees: fov, distances: info.distances.map((d) => (Number.isFinite(d) ? d : null)), placement_error: info.placementError,
        })),
        cameras: results.slice(1).map((result, index) => ({ view: index, levels: result.levels })),
    };
}

function readCameras(file) {
    const document = JSON.parse(fs.readFileSync(file, 'utf8'));
    const cameras = Array.isArray(document) ? document : document.cameras;
    if (!Array.isArray(cameras)) throw new UsageError(`--cameras ${file}: expected a list of cameras or {cameras: [...]}`);
    for (const [index, camera] of cameras.entries()) {
        const vector = (value) => Array.isArray(value) && value.length === 3 && value.every(Number.isFinite);
        if (!vector(camera.position) || !vector(camera.target)) throw new UsageError(`--cameras ${file}: camera ${index}: position and target must be [x, y, z]`);
        if (camera.fov_y_degrees === undefined) camera.fov_y_degrees = 45;
        if (!(camera.fov_y_degrees > 0 && camera.fov_y_degrees < 180)) throw new UsageError(`--cameras ${file}: camera ${index}: fov_y_degrees must be in (0, 180)`);
    }
    return cameras;
}

async function main() {
    const options = parseArguments(process.argv.slice(2), ['model', 'cameras', 'out', 'coverage', 'fov', 'chromium', 'job-timeout'], ['json']);
    if (!options.model || !options.cameras || !options.out) throw new UsageError('give --model FILE --cameras CAMS.json --out LEVELS.json');
    const coverage = options.coverage || 'auto';
    if (!kConventions.includes(coverage)) throw new UsageError(`--coverage: one of ${kConventions.join(', ')}`);
    if (!fs.existsSync(options.model)) throw new UsageError(`--model ${options.model}: no such file`);
    const cameras = readCameras(options.cameras);
    const fov = options.fov !== undefined ? Number(options.fov) : undefined;
    if (fov !== undefined && !(fov > 0 && fov < 180)) throw new UsageError('--fov: degrees in (0, 180)');
    const log = (message) => process.stderr.write(`lod_threejs: ${message}\n`);

    let start = process.hrtime.bigint();
    const validator = await validatorCounts(options.model);
    const validatorSeconds = Number(process.hrtime.bigint() - start) / 1e9;
    start = process.hrtime.bigint();
    const three = await lodLevelsWithThreeJs(options.model, cameras, { coverage, fovYDegrees: fov, chromium: options.chromium,
        jobTimeoutSeconds: Number(options['job-timeout'] || 120), log });
    const chromiumSeconds = Number(process.hrtime.bigint() - start) / 1e9;
    const threeVersion = JSON.parse(fs.readFileSync(path.join(kHarnessDir, 'node_modules', 'three', 'package.json'), 'utf8')).version;
    const result = {
        format: 'lodopt-lod-threejs', model: path.resolve(options.model), three: threeVersion, coverage, coverage_mark: three.coverage_mark,
        validator, lods: three.lods, cameras: three.cameras,
        seconds: { validator: validatorSeconds, chromium: chromiumSeconds, load_in_page: three.load_ms / 1000 },
    };
    fs.mkdirSync(path.dirname(path.resolve(options.out)), { recursive: true });
    writeFileAtomically(options.out, JSON.stringify(result));
    const summary = {
        out: options.out, lods: three.lods.length, cameras: three.cameras.length, validator,
        seconds: result.seconds,
    };
    if (options.json) process.stdout.write(JSON.stringify(summary, null, 1) + '\n');
    else {
        process.stdout.write(`${three.lods.length} LODs, ${three.cameras.length} cameras -> ${options.out}\n`);
        process.stdout.write(`validator: ${validator.errors} errors, ${validator.warnings} warnings, ${validator.infos} infos, ${validator.hints} hints` +
            `${Object.keys(validator.codes).length ? ` (${Object.entries(validator.codes).map(([c, n]) => `${c} x${n}`).join(', ')})` : ''}\n`);
    }
    return 0;
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
    // exitCode, not exit(): a large JSON written to a pipe must drain before node ends.
    main().then((code) => { process.exitCode = code; }, (error) => {
        process.stderr.write(`lod_threejs: ${error instanceof UsageError ? error.message : `error: ${error.stack || error.message}`}\n`);
        process.exitCode = error instanceof UsageError ? 2 : 1;
    });
}
