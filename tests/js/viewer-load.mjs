// How fast the viewer shows a big building, in Debian's Chromium (headless, software WebGL)
// with Playwright: a benchmark, not a test (no thresholds; the caller compares).
//
//   node tests/js/viewer-load.mjs URL OUT_DIR [RUNS]
//
// URL: a running `poinav serve FILE.ifc` (no scenario: two key-driven robots). For each of
// RUNS fresh page loads (default 3) measures, from the start of navigation: the first frame
// (the storey and its robots), the simulated storey's part of the building loaded and first
// drawn, the whole building loaded (every GLB part downloaded, parsed and merged) and first
// drawn; then the frames per second while ArrowUp drives Robot1 for 3 s with the building in
// view (frames drawn while it moved, per second it moved), and the time one frame takes
// (everything drawn again; only the robots moved). Writes OUT_DIR/report.json (every run, the
// medians, the GLB parts' sizes, the load average) and OUT_DIR/building.png; exits 1 on a
// page error.
import { mkdtempSync, writeFileSync, mkdirSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
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
  const scene = await (await fetch(new URL('/api/scene', url))).json();
  report.glb_bytes = scene.model.reduce((n, p) => n + p.bytes, 0);
  report.glb_parts = scene.model.length;
  report.current_part_bytes = scene.model.filter((p) => p.storey === scene.current).reduce((n, p) => n + p.bytes, 0);
  for (let k = 0; k < runs; k += 1) {
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    // A fresh load each run: nothing from the cache.
    await page.route('**/api/model/*.glb', (route) => route.continue({ headers: { ...route.request().headers(), 'cache-control': 'no-cache' } }));
    await page.goto(url);
    await page.waitForFunction(() => window.poinav && window.poinav.ready && window.poinav.buildingFrameMs !== null, null, { timeout: 180000 });
    const t = await page.evaluate(() => ({
      first_frame_ms: window.poinav.firstFrameMs,
      storey_ms: window.poinav.storeyMs,
      storey_frame_ms: window.poinav.storeyFrameMs,
      building_ms: window.poinav.buildingMs,
      building_frame_ms: window.poinav.buildingFrameMs,
      elements: window.poinav.elements,
    }));
    // Frames while Robot1 drives, the perspective camera on the storey with the building.
    await page.waitForFunction(() => window.poinav.states > 10, null, { timeout: 60000 });
    await page.click('#reset');
    await page.waitForTimeout(500);
    const f0 = await page.evaluate(() => ({ ...window.poinav.motion }));
    await page.keyboard.down('ArrowUp');
    await page.waitForTimeout(3000);
    await page.keyboard.up('ArrowUp');
    const f1 = await page.evaluate(() => ({ ...window.poinav.motion }));
    t.frames_per_s = (f1.frames - f0.frames) / ((f1.ms - f0.ms) / 1000);
    t.moving_s = (f1.ms - f0.ms) / 1000;
    t.render_ms = await page.evaluate(() => window.poinav.renderTime(10));
    t.robots_ms = await page.evaluate(() => window.poinav.renderTime(10, false));
    t.draw_calls = await page.evaluate(() => window.poinav.renderInfo().calls);
    t.load_average = loadavg();
    if (k === runs - 1) await page.screenshot({ path: join(outDir, 'building.png'), timeout: 120000 });
    errors.push(...await page.evaluate(() => window.poinav.errors));
    if (errors.length) report.failures.push(...errors);
    report.runs.push(t);
    await page.close();
  }
  for (const key of ['first_frame_ms', 'storey_ms', 'storey_frame_ms', 'building_ms', 'building_frame_ms', 'frames_per_s', 'render_ms', 'robots_ms']) {
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
