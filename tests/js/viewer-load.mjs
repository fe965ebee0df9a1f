// How fast the viewer shows a big building, in Debian's Chromium (headless, software WebGL)
// with Playwright: a benchmark, not a test (no thresholds; the caller compares).
//
//   node tests/js/viewer-load.mjs URL OUT_DIR [RUNS]
//
// URL: a running `poinav serve FILE.ifc` (no scenario: two key-driven robots). For each of
// RUNS fresh page loads (default 3) measures, from the start of navigation: the first frame
// (the storey and its robots), the building loaded (GLB downloaded and parsed) and the first
// frame with the building; then the frames per second while ArrowUp drives Robot1 for 3 s
// with the building in view. Writes OUT_DIR/report.json (every run, the medians, the GLB's
// size) and OUT_DIR/building.png; exits 1 on a page error.
import { mkdtempSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [url, outDir, runsArg] = process.argv.slice(2);
if (!url || !outDir) {
  console.error('usage: node viewer-load.mjs URL OUT_DIR [RUNS]');
  process.exit(2);
}
const runs = Number(runsArg || 3);
mkdirSync(outDir, { recursive: true });
const report = { url, runs: [], failures: [] };
const median = (xs) => { const s = [...xs].sort((a, b) => a - b); return s[Math.floor(s.length / 2)]; };

const context = await chromium.launchPersistentContext(mkdtempSync(join(tmpdir(), 'poinav-chromium-')), {
  executablePath: process.env.POINAV_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1280, height: 800 },
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
try {
  const head = await fetch(new URL('/api/model.glb', url));
  report.glb_bytes = (await head.arrayBuffer()).byteLength;
  for (let k = 0; k < runs; k += 1) {
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    // A fresh load each run: nothing from the cache.
    await page.route('**/api/model.glb', (route) => route.continue({ headers: { ...route.request().headers(), 'cache-control': 'no-cache' } }));
    await page.goto(url);
    await page.waitForFunction(() => window.poinav && window.poinav.ready && window.poinav.buildingFrameMs !== null, null, { timeout: 180000 });
    const t = await page.evaluate(() => ({
      first_frame_ms: window.poinav.firstFrameMs,
      building_ms: window.poinav.buildingMs,
      building_frame_ms: window.poinav.buildingFrameMs,
      elements: window.poinav.elements,
    }));
    // Frames while Robot1 drives, the perspective camera on the storey with the building.
    await page.waitForFunction(() => window.poinav.states > 10, null, { timeout: 60000 });
    const f0 = await page.evaluate(() => [window.poinav.frames, performance.now()]);
    await page.keyboard.down('ArrowUp');
    await page.waitForTimeout(3000);
    await page.keyboard.up('ArrowUp');
    const f1 = await page.evaluate(() => [window.poinav.frames, performance.now()]);
    t.frames_per_s = (f1[0] - f0[0]) / ((f1[1] - f0[1]) / 1000);
    if (k === runs - 1) await page.screenshot({ path: join(outDir, 'building.png'), timeout: 120000 });
    errors.push(...await page.evaluate(() => window.poinav.errors));
    if (errors.length) report.failures.push(...errors);
    report.runs.push(t);
    await page.close();
  }
  for (const key of ['first_frame_ms', 'building_ms', 'building_frame_ms', 'frames_per_s']) {
    report[key] = median(report.runs.map((r) => r[key]));
  }
} catch (err) {
  report.failures.push(`exception: ${err.stack || err}`);
} finally {
  await context.close();
}
writeFileSync(join(outDir, 'report.json'), JSON.stringify(report, null, 2));
console.log(JSON.stringify(report, null, 2));
process.exit(report.failures.length ? 1 : 0);
