// The viewer on a real multi-storey building, in Debian's Chromium (headless) with Playwright.
//
//   node tests/js/viewer-storeys.mjs URL OUT_DIR
//
// URL: a running `poinav serve FILE.ifc` (no scenario: two key-driven robots on the default
// storey). Checks that from straight above the robots' rays and the doors' status colours are
// visible on the simulated storey (nothing above it hides them), that switching the storey
// moves the robots and the section plane there, and that ArrowUp drives Robot1 at least 1 m in
// 2.5 s without touching Robot2; that the building arrives in parts, the simulated storey's
// first, merged into few draw calls; that nothing is redrawn while nothing moves; and that the
// X-ray view keeps the storey cut (only what is above the cut turns translucent). Measures the
// first frame, the simulated storey's and the whole building's load times, the frame rate
// while Robot1 drives, the time one frame takes and the load average. Writes
// OUT_DIR/report.json and OUT_DIR/top.png; exits 1 when a check fails.
// crates/poinav/tests/viewer_storeys.rs runs it on the corpus's multi-storey models.
import { mkdtempSync, writeFileSync, mkdirSync } from 'node:fs';
import { loadavg, tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [url, outDir] = process.argv.slice(2);
if (!url || !outDir) {
  console.error('usage: node viewer-storeys.mjs URL OUT_DIR');
  process.exit(2);
}
mkdirSync(outDir, { recursive: true });
const report = { url, checks: {} };
const failures = [];
function check(name, ok, measured) {
  report.checks[name] = { ok: !!ok, measured };
  if (!ok) failures.push(`${name}: ${JSON.stringify(measured)}`);
}
const STATUS = { FULL_ACCESS: '#16a34a', RESTRICTED: '#f59e0b', BLOCKED: '#dc2626', PENDING_VALIDATION: '#94a3b8' };

const context = await chromium.launchPersistentContext(mkdtempSync(join(tmpdir(), 'poinav-chromium-')), {
  executablePath: process.env.POINAV_CHROMIUM || '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1280, height: 800 },
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
const consoleErrors = [];
try {
  const page = context.pages()[0] || await context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(String(e)));
  const pause = (ms) => page.waitForTimeout(ms);
  const hook = (f, arg) => page.evaluate(f, arg);
  const robots = () => hook(() => window.poinav.robots());

  await page.goto(url);
  await page.waitForFunction(() => window.poinav && window.poinav.ready && window.poinav.states > 10, null, { timeout: 120000 });
  const times = await hook(() => ({
    first_frame_ms: window.poinav.firstFrameMs, storey_ms: window.poinav.storeyMs, storey_frame_ms: window.poinav.storeyFrameMs,
    building_ms: window.poinav.buildingMs, building_frame_ms: window.poinav.buildingFrameMs,
  }));
  const scene = await hook(() => window.poinav.scene);
  const current = scene.current;
  const storeys = scene.storeys.map((s, i) => ({ i, name: s.storey, elevation_m: s.elevation_m, robots: s.robots.length, doors: s.doors.length }));
  check('scene lists the storeys', storeys.length >= 2 && storeys[current].robots === 2, { current, storeys });
  check('first frame drawn', times.first_frame_ms !== null && times.building_ms !== null, times);
  // The building arrives in parts (one per storey), the simulated storey's first; every
  // element of every part is there, merged into few draw calls.
  const parts = await hook(() => window.poinav.parts);
  const elements = await hook(() => window.poinav.elements);
  const wanted = scene.model.reduce((n, p) => n + p.elements, 0);
  check('simulated storey loads first', parts.length === scene.model.length && scene.model[parts[0]].storey === current && elements === wanted,
    { parts, storeys: parts.map((k) => scene.model[k].storey), elements, wanted });

  // Top-down view of the cut storey: rays and door passages are visible.
  await hook(() => window.poinav.showTop());
  await pause(800);
  await page.screenshot({ path: join(outDir, 'top.png') });
  const st = scene.storeys[current];
  const statuses = [...new Set(st.doors.filter((d) => d.ring && d.ring.length >= 3).map((d) => d.status))];
  const rayColours = ['#22c55e', '#ef4444', '#3b82f6'];
  const counts = await hook(([c, tol]) => window.poinav.countColours(c, tol), [rayColours.concat(statuses.map((s) => STATUS[s])), 30]);
  const rayPixels = counts.slice(0, 3).reduce((a, b) => a + b, 0);
  const doorPixels = Object.fromEntries(statuses.map((s, k) => [s, counts[3 + k]]));
  check('rays visible from above', rayPixels > 50, { ray_pixels: rayPixels, cut_at: await hook(() => window.poinav.cutAt()) });
  const cost = await hook(() => window.poinav.renderInfo());
  report.draw_calls = cost.calls;
  report.triangles = cost.triangles;
  check('few draw calls', cost.calls <= 40 + 2 * scene.model.length, cost);

  // Nothing moves: nothing is redrawn.
  const idle0 = await hook(() => window.poinav.frames);
  await pause(1500);
  const idle1 = await hook(() => window.poinav.frames);
  check('no frames while nothing moves', idle1 === idle0, { frames: idle1 - idle0 });

  // X-ray: what is above the cut turns translucent; the storey stays cut and opaque (the same
  // triangles drawn opaque, under the same plane), and the robots' rays still show (tinted by
  // the translucent storeys above, so counted with a wider tolerance).
  await page.check('#xray');
  await pause(800);
  const xrayRays = (await hook(([c, tol]) => window.poinav.countColours(c, tol), [rayColours, 120])).reduce((a, b) => a + b, 0);
  const xrayCost = await hook(() => window.poinav.renderInfo());
  const xrayCut = await hook(() => window.poinav.cutAt());
  await page.uncheck('#xray');
  await pause(300);
  check('X-ray keeps the storey cut', xrayRays > 50 && xrayCost.building.solid === cost.building.solid && cost.building.xray === 0
    && xrayCost.building.xray > 0 && Math.abs(xrayCut - (st.elevation_m + 1.5)) < 1e-6,
    { ray_pixels: xrayRays, opaque_triangles: [cost.building.solid, xrayCost.building.solid], translucent_triangles: [cost.building.xray, xrayCost.building.xray], cut_at: xrayCut });
  // Every door of the storey is drawn in its status colour; together they cover > 50 pixels.
  const doors = await hook(() => window.poinav.doors());
  const wrong = doors.filter((d) => d.colour !== STATUS[d.status]);
  const total = Object.values(doorPixels).reduce((a, b) => a + b, 0);
  check('door colours visible from above', doors.length > 0 && wrong.length === 0 && total > 50, { door_pixels: doorPixels, doors: doors.length, wrong });

  // ArrowUp for 2.5 s: Robot1 moves at least 1 m, Robot2 stays and is not touched.
  const f0 = await hook(() => ({ ...window.poinav.motion }));
  const before = await robots();
  await page.keyboard.down('ArrowUp');
  await pause(2500);
  await page.keyboard.up('ArrowUp');
  await pause(400);
  const f1 = await hook(() => ({ ...window.poinav.motion }));
  // What the robots' frames showed (under software WebGL: the kept picture with the robots
  // drawn over it) is what drawing the whole view shows.
  const still = await hook(() => window.poinav.stillDiff());
  const after = await robots();
  const moved = Math.hypot(after[0].x - before[0].x, after[0].y - before[0].y);
  const other = Math.hypot(after[1].x - before[1].x, after[1].y - before[1].y);
  const apart = Math.hypot(after[0].x - after[1].x, after[0].y - after[1].y);
  const contacts = await page.$$eval('#events li', (lis) => lis.map((li) => li.textContent).filter((t) => t.includes('contact with Robot')));
  check('ArrowUp drives Robot1 without touching Robot2', moved >= 1 && other < 1e-6 && contacts.length === 0 && apart > 0.8,
    { moved_m: moved, robot2_moved_m: other, apart_m: apart, contacts });
  check('robots drawn over the kept picture as in a whole drawing', still.differ <= still.pixels * 0.001, still);
  // Frames drawn while the robots moved, per second they moved (a robot at a wall stops, and
  // nothing is drawn then).
  report.frames_per_s = (f1.frames - f0.frames) / ((f1.ms - f0.ms) / 1000);
  report.moving_s = (f1.ms - f0.ms) / 1000;
  await hook(() => window.poinav.showTop());
  report.render_ms = await hook(() => window.poinav.renderTime(5));
  report.robots_ms = await hook(() => window.poinav.renderTime(5, false));

  // Switching the storey moves the robots and the section plane there.
  const target = storeys.find((s) => s.i !== current && s.robots > 0);
  if (target) {
    await page.selectOption('#storey', String(target.i));
    await page.waitForFunction((i) => window.poinav.storey === i && window.poinav.lastState.storey === i, target.i, { timeout: 20000 });
    await pause(300);
    const there = await robots();
    const starts = scene.storeys[target.i].robots.map((r) => r.start);
    const cutAt = await hook(() => window.poinav.cutAt());
    const offStart = Math.max(...there.map((r, k) => Math.hypot(r.x - starts[k][0], r.y - starts[k][1])));
    check('storey switch moves robots and cut', Math.abs(cutAt - (target.elevation_m + 1.5)) < 1e-6 && offStart < 0.05 && there.length === starts.length,
      { storey: target, cut_at: cutAt, off_start_m: offStart });
    await page.selectOption('#storey', String(current));
    await page.waitForFunction((i) => window.poinav.lastState.storey === i, current, { timeout: 20000 });
  } else {
    check('storey switch moves robots and cut', false, { reason: 'no other storey with robots', storeys });
  }
  const errors = consoleErrors.concat(await hook(() => window.poinav.errors));
  check('no console errors', errors.length === 0, errors);
  Object.assign(report, times);
  report.load_average = loadavg();
} catch (err) {
  failures.push(`exception: ${err.stack || err}`);
} finally {
  await context.close();
}
report.failures = failures;
writeFileSync(join(outDir, 'report.json'), JSON.stringify(report, null, 2));
console.log(JSON.stringify(report, null, 2));
process.exit(failures.length ? 1 : 0);
