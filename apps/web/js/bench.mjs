#!/usr/bin/env node
// The web decoder's figures (docs/web.md): its download size next to three.js's Draco and
// meshopt decoders, decode times in Node (beside `subdfit decode`'s, measured in the same run),
// and the example page's time from request to first frame in headless Chromium.
//   node bench.mjs --out DIR [--subdfit PATH] [--repeat N] [--triangles N] [--page] [--node-modules DIR] ASSET.subd ...
// Prints a table and writes DIR/web_bench.csv (section, subject, metric, value, unit).
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import zlib from 'node:zlib';
import { createDecoderInstance } from './subd_core.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const options = { out: null, subdfit: null, repeat: 5, triangles: 0, page: false, nodeModules: path.resolve(here, '../../apps/web/node_modules'), assets: [] };
const args = process.argv.slice(2);
for (let k = 0; k < args.length; ++k) {
  const flag = args[k];
  if (flag === '--out') options.out = args[++k];
  else if (flag === '--subdfit') options.subdfit = args[++k];
  else if (flag === '--repeat') options.repeat = Math.max(1, Number(args[++k]));
  else if (flag === '--triangles') options.triangles = Math.max(0, Math.round(Number(args[++k])));
  else if (flag === '--page') options.page = true;
  else if (flag === '--node-modules') options.nodeModules = args[++k];
  else if (flag.startsWith('-')) {
    process.stderr.write(`bench.mjs: unknown option ${flag}\n`);
    process.exit(1);
  } else options.assets.push(flag);
}
if (!options.out) {
  process.stderr.write('usage: node bench.mjs --out DIR [--subdfit PATH] [--repeat N] [--triangles N] [--page] [--node-modules DIR] ASSET.subd ...\n');
  process.exit(1);
}

const rows = [];
const record = (section, subject, metric, value, unit) => {
  rows.push([section, subject, metric, value, unit]);
  process.stdout.write(`${section.padEnd(8)} ${subject.padEnd(44)} ${metric.padEnd(22)} ${String(value).padStart(12)} ${unit}\n`);
};
const median = (values) => [...values].sort((a, b) => a - b)[values.length >> 1];
const gzipped = (file) => zlib.gzipSync(fs.readFileSync(file), { level: 9 }).length;
const brotli = (file) => zlib.brotliCompressSync(fs.readFileSync(file), { params: { [zlib.constants.BROTLI_PARAM_QUALITY]: 11 } }).length;

// 1. Sizes: what a page downloads to decode (three.js itself not counted), and three's decoders.
const decoder = ['subd_decoder_wasm.wasm', 'subd_decoder_wasm.mjs', 'subd_core.mjs', 'subd_worker.mjs', 'subd_decoder.mjs',
                 'subd_loader.mjs'].map((name) => path.join(here, name));
let decoderGzip = 0, decoderBrotli = 0;
for (const file of decoder) {
  record('size', path.basename(file), 'raw', fs.statSync(file).size, 'bytes');
  record('size', path.basename(file), 'gzip -9', gzipped(file), 'bytes');
  decoderGzip += gzipped(file);
  decoderBrotli += brotli(file);
}
record('size', 'subdfit web decoder (all of the above)', 'gzip -9', decoderGzip, 'bytes');
record('size', 'subdfit web decoder (all of the above)', 'brotli 11', decoderBrotli, 'bytes');
const libs = path.join(options.nodeModules, 'three/examples/jsm');
const others = {
  'three Draco decoder (draco_decoder.wasm + wrapper)': ['libs/draco/draco_decoder.wasm', 'libs/draco/draco_wasm_wrapper.js'],
  'three Draco decoder, glTF build (gltf/)': ['libs/draco/gltf/draco_decoder.wasm', 'libs/draco/gltf/draco_wasm_wrapper.js'],
  'three meshopt decoder (meshopt_decoder.module.js)': ['libs/meshopt_decoder.module.js'],
  // What a page loading glTF adds to three.js, and SubdLoader does not need.
  'three GLTFLoader (+ BufferGeometryUtils, SkeletonUtils)': ['loaders/GLTFLoader.js', 'utils/BufferGeometryUtils.js', 'utils/SkeletonUtils.js'],
  'three DRACOLoader': ['loaders/DRACOLoader.js'],
};
for (const [subject, files] of Object.entries(others)) {
  const present = files.map((f) => path.join(libs, f)).filter((f) => fs.existsSync(f));
  if (present.length !== files.length) continue;
  record('size', subject, 'raw', present.reduce((s, f) => s + fs.statSync(f).size, 0), 'bytes');
  record('size', subject, 'gzip -9', present.reduce((s, f) => s + gzipped(f), 0), 'bytes');
  record('size', subject, 'brotli 11', present.reduce((s, f) => s + brotli(f), 0), 'bytes');
}

// 2. Decoding in Node: compiling the module once, then each asset at its default density (or
// --triangles).
const wasm = fs.readFileSync(path.join(here, 'subd_decoder_wasm.wasm'));
let start = performance.now();
const instance = await createDecoderInstance(wasm);
record('node', 'subd_decoder_wasm.wasm', 'compile + instantiate', (performance.now() - start).toFixed(1), 'ms');
for (const asset of options.assets) {
  const bytes = new Uint8Array(fs.readFileSync(asset));
  const density = options.triangles ? ` at ~${options.triangles} triangles` : '';
  const subject = `${path.basename(path.dirname(path.resolve(asset)))}/${path.basename(asset)} (${bytes.length} B)${density}`;
  // Wall and CPU (user + system) milliseconds: on a shared machine the CPU time is the figure
  // to compare, the wall time says how busy the machine was.
  const walls = [], cpus = [];
  let decoded;
  for (let r = 0; r < options.repeat; ++r) {
    const [wall, cpu] = [performance.now(), process.cpuUsage()];
    decoded = instance.decode(bytes, { name: asset, triangles: options.triangles });
    const used = process.cpuUsage(cpu);
    walls.push(performance.now() - wall);
    cpus.push((used.user + used.system) / 1000);
  }
  record('node', subject, 'triangles', decoded.indices.length / 3, '');
  record('node', subject, 'decode (wasm), CPU', median(cpus).toFixed(0), 'ms');
  record('node', subject, 'decode (wasm), wall', median(walls).toFixed(0), 'ms');
  // Both command lines whole (read, decode, write the glb), one after the other; their CPU time
  // through /usr/bin/time where it is installed.
  const timer = fs.existsSync('/usr/bin/time') ? ['/usr/bin/time', '-f', '%U %S'] : [];
  const cli = (command) => {
    const walls = [], cpus = [];
    for (let r = 0; r < options.repeat; ++r) {
      const t = performance.now();
      const run = spawnSync(timer[0] ?? command[0], [...timer.slice(1), ...command].slice(timer.length ? 0 : 1),
                            { stdio: ['ignore', 'ignore', 'pipe'], encoding: 'utf8' });
      if (run.status !== 0) throw new Error(`${command.join(' ')}: ${run.stderr}`);
      walls.push(performance.now() - t);
      const times = run.stderr.trim().split('\n').pop().split(' ').map(Number);
      if (timer.length) cpus.push(1000 * (times[0] + times[1]));
    }
    return { wall: median(walls), cpu: cpus.length ? median(cpus) : NaN };
  };
  const glb = path.join(options.out, 'bench.glb');
  const triangles = options.triangles ? ['--triangles', String(options.triangles)] : [];
  fs.mkdirSync(options.out, { recursive: true });
  const commands = { 'decode.mjs to .glb': [process.execPath, path.join(here, 'decode.mjs'), asset, glb, ...triangles] };
  if (options.subdfit) commands['subdfit decode to .glb'] = [options.subdfit, 'decode', asset, '--out', glb, ...triangles];
  for (const [name, command] of Object.entries(commands)) {
    const { wall, cpu } = cli(command);
    if (!Number.isNaN(cpu)) record('node', subject, `${name}, CPU`, cpu.toFixed(0), 'ms');
    record('node', subject, `${name}, wall`, wall.toFixed(0), 'ms');
  }
  fs.rmSync(glb, { force: true });
  record('page', subject, 'bytes downloaded', decoderGzip + bytes.length, 'bytes (decoder gzip + asset)');
}

// 3. The example page in headless Chromium (SwiftShader): request to first frame.
if (options.page && options.assets.length > 0) {
  const { startServer } = await import('./serve.mjs');
  const { chromium } = await import(path.join(options.nodeModules, 'playwright-core', 'index.mjs'));
  const browser = await chromium.launch({
    executablePath: '/usr/bin/chromium',
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
  });
  try {
    for (const asset of options.assets) {
      const { server, url } = await startServer({ mounts: { '/': here, '/asset': path.dirname(path.resolve(asset)) } });
      const subject = `${path.basename(path.dirname(path.resolve(asset)))}/${path.basename(asset)}${options.triangles ? ` at ~${options.triangles} triangles` : ''}`;
      const times = [];
      for (let r = 0; r < options.repeat; ++r) {
        const page = await browser.newPage({ viewport: { width: 512, height: 576 } });
        await page.goto(`${url}/example/?size=512&triangles=${options.triangles}&src=/asset/${path.basename(asset)}`);
        const figures = await page.evaluate(() => window.subdExample.ready);
        times.push(figures.firstFrameMs);
        await page.close();
      }
      record('page', subject, 'request to first frame', median(times).toFixed(0), 'ms (SwiftShader)');
      server.close();
    }
  } finally {
    await browser.close();
  }
}

fs.mkdirSync(options.out, { recursive: true });
const csv = ['section,subject,metric,value,unit', ...rows.map((row) => row.map((v) => `"${String(v).replaceAll('"', '""')}"`).join(','))];
fs.writeFileSync(path.join(options.out, 'web_bench.csv'), `${csv.join('\n')}\n`);
process.stdout.write(`${path.join(options.out, 'web_bench.csv')}\n`);
