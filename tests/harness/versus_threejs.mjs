#!/usr/bin/env node
// lodopt against three.js on real glTF files (docs/harness.md): for every model and every view
// `lodopt scene info` gives it, renders lodopt (`lodopt render --scene F --view V`, every object
// at level 0) and three.js (render_threejs.mjs, same camera and size), scores the pair with
// `lodopt metrics LODOPT.png THREE.png --json` (SSIM on gray, three.js as the reference) and
// writes OUT/versus.csv, OUT/versus.md, OUT/versus.json and, per view, the two images and an
// absolute difference image (×4) under OUT/images/.
//
//   node versus_threejs.mjs --data ../shared/data --lodopt build/cli/lodopt [--out DIR]
//        [--shading pbr|lambert|default] [--size 256x256] [--only NAME,NAME] [--json]
// --data: the models are every .gltf/.glb under DATA/gltf/{models,msft_lod,render-tests}
// (--dir DIR instead: every .gltf/.glb under DIR, e.g. packed copies from validate_corpus.mjs);
// --only keeps those whose path (relative to DATA/gltf, or DIR) contains one of the names.
// --shading: passed to `lodopt render --shading` (default pbr); `default` passes nothing (the
// renderer's own shading, for a lodopt without the option). --out: out/versus_threejs.
// Exit: 0 every pair rendered and scored (a model lodopt refuses for a required extension is
// listed as skipped), 1 a render or score failed, 2 bad usage.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { decodePng, encodePng } from './png.mjs';
import { parseArguments, parseSize, renderWithThreeJs, UsageError, writeFileAtomically } from './render_threejs.mjs';
import { findModels } from './validate_corpus.mjs';

function run(executable, args) {
    const start = process.hrtime.bigint();
    const result = spawnSync(executable, args, { encoding: 'utf8', maxBuffer: 1 << 28, env: { ...process.env, CI: '1' } });
    const ms = Number(process.hrtime.bigint() - start) / 1e6;
    const message = (result.stderr || '').trim().split('\n').slice(-3).join(' | ');
    return { status: result.status, stdout: result.stdout, message, ms };
}

const kSky = [158, 194, 230];

// Mean absolute difference over R, G and B in bytes, the difference image (×4, clamped), the
// share of pixels that are not sky in either image (coverage) and the share that is sky in
// exactly one of them (silhouette: where geometry or camera disagree, whatever the shading).
function difference(fileA, fileB) {
    const a = decodePng(fs.readFileSync(fileA));
    const b = decodePng(fs.readFileSync(fileB));
    if (a.width !== b.width || a.height !== b.height) throw new Error(`sizes differ: ${a.width}x${a.height} and ${b.width}x${b.height}`);
    const diff = new Uint8Array(a.rgb.length);
    let sum = 0;
    for (let i = 0; i < a.rgb.length; ++i) {
        const d = Math.abs(a.rgb[i] - b.rgb[i]);
        sum += d;
        diff[i] = Math.min(255, d * 4);
    }
    const isSky = (rgb, p) => rgb[p * 3] === kSky[0] && rgb[p * 3 + 1] === kSky[1] && rgb[p * 3 + 2] === kSky[2];
    let covered = 0, silhouette = 0;
    const pixels = a.width * a.height;
    for (let p = 0; p < pixels; ++p) {
        const skyA = isSky(a.rgb, p), skyB = isSky(b.rgb, p);
        covered += !skyA || !skyB;
        silhouette += skyA !== skyB;
    }
    return { meanAbsDiff: sum / a.rgb.length, coverage: covered / pixels, silhouette: silhouette / pixels, png: encodePng(a.width, a.height, diff) };
}

// Runs the comparison; resolves to {rows, assets, mean_ssim}. Each row: asset, view, view_name,
// status ('ok' or what failed), ssim, mean_abs_diff, lodopt_ms, three_ms, images.
export async function versus({ data, dir, lodopt, out, shading = 'pbr', size = '256x256', only = [], log = () => {} }) {
    const [width, height] = parseSize(size);
    const gltfDir = dir || path.join(data, 'gltf');
    const models = (dir ? findModels(dir) : ['models', 'msft_lod', 'render-tests'].flatMap((sub) => findModels(path.join(gltfDir, sub))))
        .filter((file) => only.length === 0 || only.some((name) => path.relative(gltfDir, file).includes(name)));
    const imagesDir = path.join(out, 'images');
    fs.mkdirSync(imagesDir, { recursive: true });
    const rows = [];
    const jobs = [];
    for (const model of models) {
        const asset = path.relative(gltfDir, model);
        const stem = asset.replace(/\.(gltf|glb)$/i, '').replace(/[^A-Za-z0-9_.-]+/g, '_');
        const info = run(lodopt, ['scene', 'info', model, '--json']);
        if (info.status !== 0) {
            // A file lodopt refuses for a required extension it cannot decode has nothing to compare.
            const refused = info.status === 2 && /extensionsRequired: (\S+) is not supported/.exec(info.message);
            rows.push({ asset, view: '', view_name: '', status: refused ? `skipped: lodopt refuses ${refused[1]}` : `lodopt scene info exit ${info.status}: ${info.message}` });
            continue;
        }
        const views = JSON.parse(info.stdout).views;
        for (const [index, view] of views.entries()) {
            const images = {
                lodopt: path.join(imagesDir, `${stem}__v${index}_lodopt.png`),
                three: path.join(imagesDir, `${stem}__v${index}_three.png`),
                diff: path.join(imagesDir, `${stem}__v${index}_diff.png`),
            };
            const row = { asset, view: index, view_name: view.name, status: 'ok', images };
            rows.push(row);
            const shadingArgs = shading === 'default' ? [] : ['--shading', shading];
            const render = run(lodopt, ['render', '--scene', model, '--view', String(index), '--size', size, '--out', images.lodopt, ...shadingArgs]);
            row.lodopt_ms = render.ms;
            if (render.status !== 0) row.status = `lodopt render exit ${render.status}: ${render.message}`;
            jobs.push({ model, view, width, height, out: images.three, row });
        }
    }
    log(`${models.length} models, ${jobs.length} views: rendering three.js`);
    const results = await renderWithThreeJs(jobs, { log, jobTimeoutSeconds: 120 });
    for (const [index, result] of results.entries()) {
        const { row } = jobs[index];
        row.three_ms = result.ms;
        if (!result.ok) { row.status = row.status === 'ok' ? `three.js: ${result.error.split('\n')[0]}` : row.status; continue; }
        if (row.status !== 'ok') continue;
        const metrics = run(lodopt, ['metrics', row.images.lodopt, row.images.three, '--json']);
        if (metrics.status !== 0) { row.status = `lodopt metrics exit ${metrics.status}: ${metrics.message}`; continue; }
        row.ssim = JSON.parse(metrics.stdout).ssim.candidate;
        const diff = difference(row.images.lodopt, row.images.three);
        row.mean_abs_diff = diff.meanAbsDiff;
        row.coverage = diff.coverage;
        row.silhouette_diff = diff.silhouette;
        writeFileAtomically(row.images.diff, diff.png);
    }
    // Means leave out views where both images are all sky (a flat model seen edge-on): they
    // score 1 whatever the shading.
    const assets = {};
    for (const row of rows) {
        if (row.ssim === undefined || row.coverage === 0) continue;
        (assets[row.asset] ||= []).push(row.ssim);
    }
    const assetMeans = Object.fromEntries(Object.entries(assets).map(([asset, values]) => [asset, values.reduce((s, v) => s + v, 0) / values.length]));
    const scored = rows.filter((row) => row.ssim !== undefined && row.coverage > 0);
    const meanSsim = scored.length ? scored.reduce((s, row) => s + row.ssim, 0) / scored.length : null;
    return { shading, size, rows, asset_mean_ssim: assetMeans, mean_ssim: meanSsim };
}

function writeTables(result, out) {
    const fixed = (value, digits) => (Number.isFinite(value) ? Number(value).toFixed(digits) : '');
    const csv = ['asset,view,view_name,ssim,mean_abs_diff,coverage,silhouette_diff,lodopt_ms,three_ms,status'];
    const md = [`lodopt (--shading ${result.shading}) against three.js at ${result.size}: SSIM on gray, three.js as the reference; mean |diff| over RGB bytes; coverage: pixels not sky in either image; silhouette: pixels sky in exactly one (geometry or camera disagree); times are each renderer's wall time for the view (lodopt: the whole process; three.js: in the page, loading included for a model's first view).`, '',
        '| asset | view | SSIM | mean abs diff | coverage % | silhouette % | lodopt ms | three.js ms | status |', '|---|---|---|---|---|---|---|---|---|'];
    for (const row of result.rows) {
        csv.push([row.asset, row.view, row.view_name, fixed(row.ssim, 4), fixed(row.mean_abs_diff, 2), fixed(row.coverage, 4), fixed(row.silhouette_diff, 4),
            fixed(row.lodopt_ms, 0), fixed(row.three_ms, 0),
            row.status].map((v) => `"${String(v).replace(/"/g, '""')}"`).join(','));
        md.push(`| ${row.asset} | ${row.view === '' ? '' : `${row.view} ${row.view_name}`} | ${fixed(row.ssim, 4)} | ${fixed(row.mean_abs_diff, 2)} | ${fixed(row.coverage * 100, 1)} | ${fixed(row.silhouette_diff * 100, 2)} | ${fixed(row.lodopt_ms, 0)} | ${fixed(row.three_ms, 0)} | ${row.status.replace(/\|/g, '\\|')} |`);
    }
    md.push('', '| asset | mean SSIM over its views (all-sky views left out) |', '|---|---|');
    for (const [asset, mean] of Object.entries(result.asset_mean_ssim)) md.push(`| ${asset} | ${mean.toFixed(4)} |`);
    md.push(`| **all views** | **${fixed(result.mean_ssim, 4)}** |`);
    writeFileAtomically(path.join(out, 'versus.csv'), csv.join('\n') + '\n');
    writeFileAtomically(path.join(out, 'versus.md'), md.join('\n') + '\n');
    writeFileAtomically(path.join(out, 'versus.json'), JSON.stringify(result, null, 1) + '\n');
    return md.join('\n');
}

async function main() {
    const options = parseArguments(process.argv.slice(2), ['data', 'dir', 'lodopt', 'out', 'shading', 'size', 'only'], ['json']);
    if (!(options.data || options.dir) || !options.lodopt) throw new UsageError('give --data DIR (../shared/data) or --dir DIR, and --lodopt EXE');
    const out = path.resolve(options.out || 'out/versus_threejs');
    const log = (message) => process.stderr.write(`versus_threejs: ${message}\n`);
    const result = await versus({
        data: options.data && path.resolve(options.data), dir: options.dir && path.resolve(options.dir), lodopt: path.resolve(options.lodopt), out, shading: options.shading || 'pbr',
        size: options.size || '256x256', only: options.only ? options.only.split(',') : [], log,
    });
    const table = writeTables(result, out);
    process.stdout.write(options.json ? JSON.stringify(result, null, 1) + '\n' : `${table}\n`);
    return result.rows.every((row) => row.status === 'ok' || row.status.startsWith('skipped:')) ? 0 : 1;
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
    // exitCode, not exit(): a large JSON written to a pipe must drain before node ends.
    main().then((code) => { process.exitCode = code; }, (error) => {
        process.stderr.write(`versus_threejs: ${error instanceof UsageError ? error.message : `error: ${error.stack || error.message}`}\n`);
        process.exitCode = error instanceof UsageError ? 2 : 1;
    });
}
