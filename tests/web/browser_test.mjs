// The example page in Debian's Chromium, headless, WebGL through SwiftShader (ctest -L web):
// asset.subd through SubdLoader renders as `subdfit decode`'s glb through three's GLTFLoader
// (PSNR >= 40 dB on the canvas), with no console errors, streamed too (drawn from its first
// bytes, refined to the same); a damaged file fails in one line.
//   WEB=<build/web> ASSETS=<fixture dir> NODE_MODULES=<apps/web/node_modules> node --test browser_test.mjs
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, test } from 'node:test';

const { WEB, ASSETS, NODE_MODULES } = process.env;
const { startServer } = await import(path.join(WEB, 'serve.mjs'));
const { chromium } = await import(path.join(NODE_MODULES, 'playwright-core', 'index.mjs'));
const shots = path.join(path.dirname(ASSETS), 'browser-test');
const SIZE = 384;

// The flags a headless Chromium needs on a machine without a GPU or a network, and a fresh profile.
export const CHROMIUM_FLAGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
                               '--disable-background-networking', '--disable-component-update', '--disable-sync',
                               '--enable-unsafe-swiftshader', '--use-angle=swiftshader'];

let server, url, browser;
before(async () => {
  fs.rmSync(shots, { recursive: true, force: true });
  fs.mkdirSync(shots, { recursive: true });
  ({ server, url } = await startServer({ mounts: { '/': WEB, '/data': ASSETS } }));
  browser = await chromium.launch({ executablePath: '/usr/bin/chromium', args: CHROMIUM_FLAGS });
});
after(async () => {
  await browser?.close();
  server?.close();
});

// Opens the example page with `query`; resolves to its first frame's figures and canvas (PNG),
// and the console errors it printed.
async function show(query) {
  const page = await browser.newPage({ viewport: { width: SIZE, height: SIZE + 64 } });
  const errors = [];
  page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
  page.on('pageerror', (error) => errors.push(String(error)));
  try {
    await page.goto(`${url}/example/?size=${SIZE}&${query}`);
    const figures = await page.evaluate(() => window.subdExample.ready.then((r) => r, (e) => ({ error: e.message })));
    const png = figures.error ? null : await page.locator('canvas').screenshot();
    return { ...figures, png, errors };
  } finally {
    await page.close();
  }
}

// PSNR of two PNGs' RGB over 8 bits, and the fraction of pixels that are not the background,
// measured in the browser (it decodes PNG).
async function compare(a, b) {
  const page = await browser.newPage();
  try {
    return await page.evaluate(async ([a, b]) => {
      const pixels = async (base64) => {
        const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${base64}`)).blob());
        const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
        const context = canvas.getContext('2d');
        context.drawImage(bitmap, 0, 0);
        return context.getImageData(0, 0, bitmap.width, bitmap.height).data;
      };
      const [p, q] = [await pixels(a), await pixels(b)];
      if (p.length !== q.length) return { psnr: -1, covered: 0 };
      let squared = 0, covered = 0;
      for (let i = 0; i < p.length; i += 4) {
        for (let c = 0; c < 3; ++c) squared += (p[i + c] - q[i + c]) ** 2;
        if (Math.abs(p[i] - p[0]) + Math.abs(p[i + 1] - p[1]) + Math.abs(p[i + 2] - p[2]) > 6) ++covered;
      }
      const mse = squared / (3 * p.length / 4);
      return { psnr: mse === 0 ? Infinity : 10 * Math.log10(255 * 255 / mse), covered: covered / (p.length / 4) };
    }, [a.toString('base64'), b.toString('base64')]);
  } finally {
    await page.close();
  }
}

const kinds = fs.readdirSync(ASSETS).filter((name) => fs.existsSync(path.join(ASSETS, name, 'asset.subd')));
for (const kind of kinds) {
  test(`${kind}: SubdLoader draws what GLTFLoader draws of subdfit decode's glb`, async (t) => {
    const subd = await show(`src=/data/${kind}/asset.subd`);
    const glb = await show(`loader=gltf&src=/data/${kind}/native.glb`);
    assert.deepEqual(subd.errors, [], 'console errors with SubdLoader');
    assert.deepEqual(glb.errors, [], 'console errors with GLTFLoader');
    assert.equal(subd.error, undefined, subd.error);
    assert.equal(subd.triangles, glb.triangles);
    fs.writeFileSync(path.join(shots, `${kind}_subd.png`), subd.png);
    fs.writeFileSync(path.join(shots, `${kind}_glb.png`), glb.png);
    const { psnr, covered } = await compare(subd.png, glb.png);
    t.diagnostic(`PSNR ${psnr.toFixed(2)} dB, ${(100 * covered).toFixed(1)} % covered, ${subd.triangles} triangles`);
    assert.ok(covered > 0.05, `the asset covers ${(100 * covered).toFixed(1)} % of the canvas`);
    assert.ok(psnr >= 40, `PSNR ${psnr.toFixed(2)} dB`);
  });
}

test('streamed over a slow network, SubdLoader draws the cage first and refines to the whole file', async (t) => {
  const total = fs.statSync(path.join(ASSETS, 'spot', 'asset.subd')).size;
  const streamed = await show(`stream=1&src=${encodeURIComponent('/data/spot/asset.subd?chunk=2048&ms=40')}`);
  const glb = await show('loader=gltf&src=/data/spot/native.glb');
  assert.deepEqual(streamed.errors, [], 'console errors while streaming');
  assert.equal(streamed.error, undefined, streamed.error);
  const updates = streamed.updates;
  t.diagnostic(updates.map((u) => `${u.bytes} B: ${u.triangles} triangles at ${u.ms.toFixed(0)} ms`).join('; '));
  assert.ok(updates.length >= 3, `${updates.length} refinements`);
  assert.ok(updates[0].bytes < total / 2 && !updates[0].complete, `first drawn at ${updates[0].bytes} of ${total} bytes`);
  for (let k = 1; k < updates.length; ++k) assert.ok(updates[k].bytes > updates[k - 1].bytes);
  assert.ok(updates.at(-1).complete && updates.at(-1).bytes === total && updates.at(-1).total === total);
  assert.ok(updates.at(-1).ms - updates[0].ms > 100, 'the cage is drawn well before the file is in');
  assert.equal(streamed.triangles, glb.triangles);
  fs.writeFileSync(path.join(shots, 'streamed.png'), streamed.png);
  const { psnr } = await compare(streamed.png, glb.png);
  assert.ok(psnr >= 40, `PSNR ${psnr.toFixed(2)} dB against the whole file's glb`);
});

test('a damaged asset.subd fails the load with one line naming the file', async () => {
  const good = fs.readFileSync(path.join(ASSETS, 'spot', 'asset.subd'));
  const bad = Buffer.from(good);
  bad[bad.length >> 1] ^= 0x40;
  fs.writeFileSync(path.join(shots, 'damaged.subd'), bad);
  fs.cpSync(path.join(shots, 'damaged.subd'), path.join(ASSETS, 'damaged.subd'));
  try {
    const shown = await show('src=/data/damaged.subd');
    assert.equal(shown.error, 'damaged.subd: checksum mismatch (damaged or truncated)');
  } finally {
    fs.rmSync(path.join(ASSETS, 'damaged.subd'));
  }
});
