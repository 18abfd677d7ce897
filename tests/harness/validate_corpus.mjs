#!/usr/bin/env node
// "What the validator accepts, lodopt reads": runs the Khronos glTF-Validator over every
// .gltf/.glb under DATA/gltf and DATA/gltf-invalid (and, with --pack, over copies of the shared
// models packed by gltfpack and glTF-Transform), then `lodopt scene info FILE --json` over each.
// A file with 0 validator errors must load (exit 0) or be refused with exit 2 and a message
// naming exactly one required extension lodopt cannot decode; anything else is a violation.
//
//   node validate_corpus.mjs --data ../shared/data --lodopt build/cli/lodopt [--out DIR]
//        [--pack none|some|all] [--known FILE|none] [--concurrency N] [--json]
// --concurrency: lodopt processes at a time (2). --valid-only: run lodopt only on the files
// with 0 validator errors (what the property is about; the others' outcome is informational).
// --known: files (relative to DATA) that lodopt is known to refuse although the validator passes
// them, with the reason (default known_refusals.json beside this script): listed as
// 'failed (known)', not as violations.
// --pack: none (default); some: BoxTextured and babylon/cannon; all: every model under
// DATA/gltf/models, DATA/gltf/msft_lod and DATA/gltf/render-tests. Each is packed four ways:
// gltfpack (default), gltfpack -cc, gltf-transform draco, gltf-transform webp (into --out, a
// temporary folder when not given). Writes OUT/validate.json and OUT/validate.md when --out is
// given; prints the table (or the JSON with --json). A packer that fails on a source (gltfpack
// refuses kenney's cakeBirthday and tile, whose scene roots are also children) is listed in
// `problems`, not counted. Exit: 0 no violation, 1 a violation or a tool failed, 2 bad usage.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArguments, UsageError, writeFileAtomically } from './render_threejs.mjs';

const kHarnessDir = path.dirname(fileURLToPath(import.meta.url));
const kBin = path.join(kHarnessDir, 'node_modules', '.bin');

// Every .gltf/.glb under `dir`, sorted.
export function findModels(dir) {
    const found = [];
    const walk = (folder) => {
        for (const entry of fs.readdirSync(folder, { withFileTypes: true }).sort((a, b) => a.name.localeCompare(b.name))) {
            const full = path.join(folder, entry.name);
            if (entry.isDirectory()) walk(full);
            else if (/\.(gltf|glb)$/i.test(entry.name)) found.push(full);
        }
    };
    if (fs.existsSync(dir)) walk(dir);
    return found;
}

// The Khronos glTF-Validator (npm gltf-validator in node_modules).
export function loadValidator() {
    const require = createRequire(import.meta.url);
    return require(path.join(kHarnessDir, 'node_modules', 'gltf-validator'));
}

// The validator's whole report of `file` with its external resources read from beside it
// (report.issues: numErrors, numWarnings, numInfos, numHints, messages with code, severity 0-3
// for error, warning, info, hint, and pointer).
export async function validatorReport(validator, file) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    return validator.validateBytes(bytes, {
        uri: path.basename(file), maxIssues: 0, writeTimestamp: false,
        externalResourceFunction: (uri) => fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)))
            .then((data) => new Uint8Array(data)),
    });
}

// The validator's verdict on `file`: its error count, error codes and required extensions.
async function validate(validator, file) {
    const report = await validatorReport(validator, file);
    const errors = report.issues.messages.filter((m) => m.severity === 0).map((m) => m.code);
    return { errors: report.issues.numErrors, codes: [...new Set(errors)], required: report.info?.extensionsRequired || [] };
}

// What `lodopt scene info FILE --json` does with `file`: {outcome, exit, message, ms}.
// outcome: 'loads' (exit 0), 'refused: <extension>' (exit 2 naming exactly one required
// extension), 'failed' (anything else).
export async function lodoptOutcome(lodopt, file) {
    const start = process.hrtime.bigint();
    const run = await new Promise((resolve) => {
        const child = spawn(lodopt, ['scene', 'info', file, '--json'], { stdio: ['ignore', 'ignore', 'pipe'], env: { ...process.env, CI: '1' } });
        let stderr = '';
        child.stderr.on('data', (chunk) => { stderr = (stderr + chunk).slice(-8000); });
        child.on('exit', (status, signal) => resolve({ status, signal, stderr }));
        child.on('error', (error) => resolve({ status: null, signal: error.message, stderr: '' }));
    });
    const ms = Number(process.hrtime.bigint() - start) / 1e6;
    const message = run.stderr.trim().split('\n').filter((line) => line.includes('error')).join(' | ') || run.stderr.trim();
    if (run.status === 0) return { outcome: 'loads', exit: 0, message: '', ms };
    const named = [...run.stderr.matchAll(/extensionsRequired: (\S+) is not supported/g)].map((m) => m[1]);
    if (run.status === 2 && new Set(named).size === 1) return { outcome: `refused: ${named[0]}`, exit: 2, message, ms };
    return { outcome: 'failed', exit: run.status === null ? `signal ${run.signal}` : run.status, message, ms };
}

// Runs `task(item)` over `items`, `concurrency` at a time; resolves to the results in order.
async function mapConcurrently(items, concurrency, task) {
    const results = new Array(items.length);
    let next = 0;
    const worker = async () => { while (next < items.length) { const i = next++; results[i] = await task(items[i]); } };
    await Promise.all(Array.from({ length: Math.max(1, concurrency) }, worker));
    return results;
}

function runTool(command, args) {
    return new Promise((resolve) => {
        const child = spawn(command, args, { stdio: ['ignore', 'ignore', 'pipe'] });
        let errors = '';
        child.stderr.on('data', (chunk) => { errors = (errors + chunk).slice(-2000); });
        child.on('exit', (code) => resolve({ code, errors }));
        child.on('error', (error) => resolve({ code: -1, errors: error.message }));
    });
}

// extensionsRequired of a .gltf or .glb (empty when it cannot be read).
function requiredExtensions(file) {
    try {
        const bytes = fs.readFileSync(file);
        const json = bytes.toString('latin1', 0, 4) === 'glTF' ? bytes.toString('utf8', 20, 20 + bytes.readUInt32LE(12)) : bytes.toString('utf8');
        return JSON.parse(json).extensionsRequired || [];
    } catch { return []; }
}

// Packs `model` four ways into `dir`; resolves to the files made (a failed packer is reported).
// gltfpack cannot read Draco, so a Draco source is packed by glTF-Transform only.
async function pack(model, name, dir, problems) {
    const draco = requiredExtensions(model).includes('KHR_draco_mesh_compression');
    const ways = [
        ['gltfpack', `${name}.gltfpack.glb`, (out) => [path.join(kBin, 'gltfpack'), ['-i', model, '-o', out]]],
        ['gltfpack -cc', `${name}.gltfpack-cc.glb`, (out) => [path.join(kBin, 'gltfpack'), ['-i', model, '-o', out, '-cc']]],
        ['gltf-transform draco', `${name}.draco.glb`, (out) => [path.join(kBin, 'gltf-transform'), ['draco', model, out]]],
        ['gltf-transform webp', `${name}.webp.glb`, (out) => [path.join(kBin, 'gltf-transform'), ['webp', model, out]]],
    ];
    const made = [];
    for (const [way, file, command] of ways) {
        if (draco && way.startsWith('gltfpack')) continue;
        const out = path.join(dir, file);
        const [tool, args] = command(out);
        const run = await runTool(tool, args);
        if (run.code === 0 && fs.existsSync(out)) made.push({ file: out, packedBy: way, source: model });
        else problems.push(`${way} ${model}: exit ${run.code}: ${run.errors.trim().split('\n').slice(-2).join(' ')}`);
    }
    return made;
}

// Runs the whole check; resolves to {files: [...], summary, violations, problems}.
export async function checkCorpus({ data, lodopt, pack: packWhich = 'none', packDir, known = {}, concurrency = 2, validOnly = false }) {
    const validator = loadValidator();
    const inputs = [...findModels(path.join(data, 'gltf')), ...findModels(path.join(data, 'gltf-invalid'))]
        .map((file) => ({ file, packedBy: '', source: '' }));
    const problems = [];
    if (packWhich !== 'none') {
        const sources = packWhich === 'all'
            ? ['models', 'msft_lod', 'render-tests'].flatMap((dir) => findModels(path.join(data, 'gltf', dir)))
            : [path.join(data, 'gltf/render-tests/BoxTextured/glTF/BoxTextured.gltf'),
               path.join(data, 'gltf/models/babylon/cannon.glb')];
        const names = new Set();
        for (const source of sources) {
            let name = path.basename(source).replace(/\.(gltf|glb)$/i, '');
            if (path.basename(path.dirname(source)) === 'glTF-Binary') name += '-binary';
            while (names.has(name)) name += '_';
            names.add(name);
            inputs.push(...await pack(source, name, packDir, problems));
        }
    }
    const reports = [];
    for (const input of inputs) {
        try { reports.push(await validate(validator, input.file)); }
        catch (error) { reports.push({ errors: -1, codes: [`validator could not read the file: ${error}`], required: [] }); }
    }
    const notRun = { outcome: 'not run', exit: '', message: '', ms: 0 };
    const outcomes = await mapConcurrently(inputs.map((input, index) => [input, reports[index]]), concurrency,
        ([input, report]) => (validOnly && report.errors !== 0 ? notRun : lodoptOutcome(lodopt, input.file)));
    const files = [];
    for (const [index, input] of inputs.entries()) {
        const report = reports[index];
        const lodoptResult = { ...outcomes[index] };
        const valid = report.errors === 0;
        const name = path.relative(data, input.file).startsWith('..') ? input.file : path.relative(data, input.file);
        const isKnown = valid && lodoptResult.outcome === 'failed' && known[name] !== undefined;
        if (isKnown) lodoptResult.outcome = 'failed (known)';
        files.push({
            file: name,
            packed_by: input.packedBy, source: input.source ? path.relative(data, input.source) : '',
            validator_errors: report.errors, validator_codes: report.codes, extensions_required: report.required,
            lodopt: lodoptResult.outcome, lodopt_exit: lodoptResult.exit, lodopt_message: lodoptResult.message, lodopt_ms: lodoptResult.ms,
            violation: valid && lodoptResult.outcome === 'failed',
            known_reason: isKnown ? known[name] : undefined,
        });
    }
    const summary = {};
    for (const file of files) {
        const group = file.validator_errors === 0 ? 'valid' : 'invalid';
        const key = `${group}\t${file.packed_by ? 'packed' : 'shared'}\t${file.lodopt}`;
        summary[key] = (summary[key] || 0) + 1;
    }
    // A known file that now loads (or names its extension) can leave the list.
    const resolved = Object.keys(known).filter((name) => files.some((f) => f.file === name && !f.lodopt.startsWith('failed')));
    return { files, summary, violations: files.filter((f) => f.violation), problems, known_now_passing: resolved };
}

export function markdownTable(result) {
    const lines = ['| validator | files | lodopt scene info | count |', '|---|---|---|---|'];
    for (const key of Object.keys(result.summary).sort()) {
        const [group, origin, outcome] = key.split('\t');
        lines.push(`| ${group === 'valid' ? '0 errors' : '≥ 1 error'} | ${origin} | ${outcome} | ${result.summary[key]} |`);
    }
    return lines.join('\n');
}

async function main() {
    const options = parseArguments(process.argv.slice(2), ['data', 'lodopt', 'out', 'pack', 'known', 'concurrency'], ['json', 'valid-only']);
    if (!options.data || !options.lodopt) throw new UsageError('give --data DIR (../shared/data) and --lodopt EXE');
    if (!['none', 'some', 'all'].includes(options.pack || 'none')) throw new UsageError('--pack: none, some or all');
    if (options.out) fs.mkdirSync(options.out, { recursive: true });
    const packDir = options.pack && options.pack !== 'none'
        ? (options.out ? path.join(options.out, 'packed') : fs.mkdtempSync(path.join(os.tmpdir(), 'lodopt-packed-'))) : null;
    if (packDir) fs.mkdirSync(packDir, { recursive: true });
    const knownFile = options.known || path.join(kHarnessDir, 'known_refusals.json');
    const known = knownFile === 'none' ? {} : JSON.parse(fs.readFileSync(knownFile, 'utf8')).files;
    const result = await checkCorpus({ data: path.resolve(options.data), lodopt: path.resolve(options.lodopt), pack: options.pack || 'none', packDir, known,
        concurrency: Number(options.concurrency || 2), validOnly: Boolean(options['valid-only']) });
    if (packDir && !options.out) fs.rmSync(packDir, { recursive: true, force: true });
    const table = markdownTable(result);
    if (options.out) {
        writeFileAtomically(path.join(options.out, 'validate.json'), JSON.stringify(result, null, 1));
        const failing = result.files.filter((f) => f.lodopt.startsWith('failed') && f.validator_errors === 0)
            .map((f) => `| ${f.file} | ${f.validator_errors} | ${f.lodopt_exit} | ${f.lodopt_message.replace(/\|/g, '\\|').slice(0, 200)} |`);
        writeFileAtomically(path.join(options.out, 'validate.md'), `${table}\n\nFiles the validator passes that lodopt fails on:\n\n| file | validator errors | exit | message |\n|---|---|---|---|\n${failing.join('\n')}\n`);
    }
    if (options.json) process.stdout.write(JSON.stringify(result, null, 1) + '\n');
    else {
        process.stdout.write(`${table}\n`);
        for (const v of result.violations) process.stdout.write(`VIOLATION: ${v.file}: validator 0 errors, lodopt exit ${v.lodopt_exit}: ${v.lodopt_message}\n`);
        for (const p of result.problems) process.stdout.write(`packer failed (not counted): ${p}\n`);
        for (const name of result.known_now_passing) process.stdout.write(`now passes, remove from the known list: ${name}\n`);
    }
    return result.violations.length === 0 ? 0 : 1;
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
    // exitCode, not exit(): a large JSON written to a pipe must drain before node ends.
    main().then((code) => { process.exitCode = code; }, (error) => {
        process.stderr.write(`validate_corpus: ${error instanceof UsageError ? error.message : `error: ${error.stack || error.message}`}\n`);
        process.exitCode = error instanceof UsageError ? 2 : 1;
    });
}
