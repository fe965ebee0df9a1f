// End-to-end test of the poinav viewer in Debian's Chromium (headless), driven by Playwright.
//
//   node tests/js/viewer-e2e.mjs URL OUT_DIR TRACE_JSONL
//
// URL: a running `poinav serve --scenario crates/poinav-sim/scenarios/drive.toml` (Robot1 at
// the west end of the corridor facing east, nothing within its 5 m front ray). Writes
// OUT_DIR/viewer.png (the screenshot the README shows) and OUT_DIR/report.json with every
// measured number, and exits 1 when a check fails. crates/poinav/tests/viewer_browser.rs runs it
// and checks the report again.
import { mkdtempSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

const [url, outDir, tracePath] = process.argv.slice(2);
if (!url || !outDir || !tracePath) {
  console.error('usage: node viewer-e2e.mjs URL OUT_DIR TRACE_JSONL');
  process.exit(2);
}
mkdirSync(outDir, { recursive: true });

const report = { url, checks: {} };
const failures = [];
function check(name, ok, measured) {
  report.checks[name] = { ok: !!ok, measured };
  if (!ok) failures.push(`${name}: ${JSON.stringify(measured)}`);
}

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
  const robots = () => page.evaluate(() => window.poinav.robots());
  // Waits at least `min` ms, then until `done()` or 5 s.
  const holdUntil = async (done, min) => {
    await pause(min);
    const t = Date.now();
    while (Date.now() - t < 5000 && !(await done())) await pause(50);
  };

  // 1. The page loads the building and receives live states.
  await page.goto(url);
  await page.waitForFunction(() => window.poinav && window.poinav.ready && window.poinav.states > 10, null, { timeout: 90000 });
  await pause(1500);
  const loaded = await page.evaluate(() => ({ elements: window.poinav.elements, robots: window.poinav.scene.robots.length, errors: window.poinav.errors, frames: window.poinav.frames }));
  check('building loaded', loaded.elements > 10 && loaded.robots === 2, loaded);

  // Rates: states received per second, and frames drawn while nothing moves: none (a frame
  // is drawn only when something changed; software WebGL has no time to spare).
  const r0 = await page.evaluate(() => [window.poinav.frames, window.poinav.states, performance.now()]);
  await pause(3000);
  const r1 = await page.evaluate(() => [window.poinav.frames, window.poinav.states, performance.now()]);
  const secs = (r1[2] - r0[2]) / 1000;
  const rates = { frames_per_s: (r1[0] - r0[0]) / secs, states_per_s: (r1[1] - r0[1]) / secs };
  check('live rates', rates.frames_per_s < 1 && rates.states_per_s > 10, rates);

  // 2. A screenshot shows the building.
  await page.screenshot({ path: join(outDir, 'viewer.png') });
  const coverage = await page.evaluate(() => window.poinav.coverage());
  check('building covers the view', coverage > 0.08, { coverage });

  // 3. Holding ArrowUp moves Robot1 (its reported pose changes); Robot2 stays.
  // Held until the robot has moved (at most 5 s): a loaded machine may step slowly.
  // Frames are drawn while it moves.
  const before = await robots();
  const f0 = await page.evaluate(() => [window.poinav.frames, performance.now()]);
  await page.keyboard.down('ArrowUp');
  await holdUntil(() => robots().then((r) => Math.hypot(r[0].x - before[0].x, r[0].y - before[0].y) > 0.4), 400);
  await page.keyboard.up('ArrowUp');
  const f1 = await page.evaluate(() => [window.poinav.frames, performance.now()]);
  await pause(500);
  const after = await robots();
  const moved = Math.hypot(after[0].x - before[0].x, after[0].y - before[0].y);
  const other = Math.hypot(after[1].x - before[1].x, after[1].y - before[1].y);
  const driving = (f1[0] - f0[0]) / ((f1[1] - f0[1]) / 1000);
  check('ArrowUp moves Robot1', moved > 0.3 && other < 1e-6 && driving > 1,
    { moved_m: moved, robot2_moved_m: other, frames_per_s: driving, before: before[0], after: after[0] });

  // 4. Driving Robot1 at the corridor's end wall turns its forward ray red.
  const startRay = (await robots())[0].rays[0];
  check('forward ray clear at first', startRay.hit === null && startRay.colour === '#22c55e', startRay);
  await page.keyboard.down('ArrowUp');
  let front = startRay;
  const t0 = Date.now();
  while (Date.now() - t0 < 15000) {
    front = (await robots())[0].rays[0];
    if (front.hit !== null && front.d < 0.6) break;
    await pause(50);
  }
  await page.keyboard.up('ArrowUp');
  await pause(300);
  front = (await robots())[0].rays[0];
  const hitClass = await page.evaluate(() => window.poinav.lastState.robots[0].rays[0].class);
  check('forward ray red at the wall', front.hit !== null && /^IfcWall/.test(hitClass) && front.colour === '#ef4444' && front.d < 0.8, { ...front, hitClass });

  // 5. W A S D drive Robot2; its rays hit in blue.
  const r2a = (await robots())[1];
  await page.keyboard.down('w');
  await holdUntil(() => robots().then((r) => Math.hypot(r[1].x - r2a.x, r[1].y - r2a.y) > 0.25), 300);
  await page.keyboard.up('w');
  await pause(300);
  const r2b = (await robots())[1];
  const hitColours2 = r2b.rays.filter((r) => r.hit !== null).map((r) => r.colour);
  check('W moves Robot2, hits in blue', Math.hypot(r2b.x - r2a.x, r2b.y - r2a.y) > 0.2 && hitColours2.length > 0 && hitColours2.every((c) => c === '#3b82f6'),
    { moved_m: Math.hypot(r2b.x - r2a.x, r2b.y - r2a.y), hitColours2 });

  // 6. The brush button toggles Robot1's brush, which rotates.
  await page.click('#brush-0');
  await pause(500);
  const b1 = await page.evaluate(() => window.poinav.lastState.robots[0].brush);
  await pause(300);
  const b2 = await page.evaluate(() => window.poinav.lastState.robots[0].brush);
  check('brush on and rotating', b1.on && b2.on && b1.angle_deg !== b2.angle_deg, { b1, b2 });

  // 7. The camera key switches to the top-down view and back.
  const m0 = await page.evaluate(() => window.poinav.cameraMatrix());
  const px0 = await page.evaluate(() => window.poinav.thumbnail());
  await page.keyboard.press('c');
  await pause(500);
  const cam1 = await page.evaluate(() => window.poinav.camera);
  const m1 = await page.evaluate(() => window.poinav.cameraMatrix());
  const px1 = await page.evaluate(() => window.poinav.thumbnail());
  let differ = 0;
  for (let i = 0; i < px0.length; i += 4) {
    if (Math.abs(px0[i] - px1[i]) + Math.abs(px0[i + 1] - px1[i + 1]) + Math.abs(px0[i + 2] - px1[i + 2]) > 24) differ += 1;
  }
  const viewChanged = differ / (px0.length / 4);
  await page.screenshot({ path: join(outDir, 'viewer-top.png') });
  const changed = m0.some((v, i) => Math.abs(v - m1[i]) > 1e-6);
  check('camera key switches to top-down', cam1 === 'top' && changed && viewChanged > 0.1, { camera: cam1, pixels_changed: viewChanged });

  // 8. A click on a wall (top-down view) shows its GlobalId, class and roles.
  const target = await page.evaluate(() => window.poinav.screenPoint('IfcWall'));
  await page.mouse.click(target.x, target.y);
  await page.waitForFunction(() => window.poinav.inspected, null, { timeout: 10000 });
  const inspected = await page.evaluate(() => window.poinav.inspected);
  check('click shows the element', inspected.id === target.id && /^IfcWall/.test(inspected.rows.Class) && (inspected.rows.POI_PrimaryRoles || '').includes('A-1'), { target, inspected });

  // 9. POI colours: Room 2's door (0.80 m) is RESTRICTED, coloured amber.
  await page.check('#poi-colours');
  await pause(300);
  const door = await page.evaluate(() => window.poinav.elementColour('Door Room 2'));
  check('POI colours doors by status', door && door.status === 'RESTRICTED' && door.colour === '#f59e0b', door);
  await page.uncheck('#poi-colours');
  await page.keyboard.press('c');
  await pause(300);

  // 10. Reset, then both robots driven towards each other in the corridor (C-1): the panel
  // lists C-2 as it happens, with the zone's SPEED_REDUCTION.
  await page.click('#reset');
  await pause(500);
  await page.keyboard.down('ArrowUp');
  await page.keyboard.down('w');
  const t1 = Date.now();
  let c2 = [];
  while (Date.now() - t1 < 15000 && c2.length === 0) {
    await pause(100);
    c2 = await page.$$eval('#events li', (lis) => lis.map((li) => li.textContent).filter((t) => t.includes('C-2 active')));
  }
  await page.keyboard.up('ArrowUp');
  await page.keyboard.up('w');
  check('C-2 listed as it happens', c2.length > 0 && c2.every((t) => t.includes('SPEED_REDUCTION: speed reduced')), { c2 });

  // 11. Playback of a scenario trace reaches its end.  // 10. Playback of a scenario trace reaches its end.
  await page.setInputFiles('#trace-file', tracePath);
  await page.waitForFunction(() => window.poinav.playback && window.poinav.playback(), null, { timeout: 10000 });
  await page.click('#play');
  await page.waitForFunction(() => window.poinav.playback().ended, null, { timeout: 60000 });
  const pb = await page.evaluate(() => window.poinav.playback());
  const shown = await robots();
  check('playback reaches the end', pb.ended && pb.index === pb.frames - 1 && pb.t === pb.end && pb.frames > 100 && shown.length === 2, { ...pb, shown: shown.map((r) => [r.name, r.x, r.y]) });

  const errors = consoleErrors.concat(await page.evaluate(() => window.poinav.errors));
  check('no console errors', errors.length === 0, errors);
} catch (err) {
  failures.push(`exception: ${err.stack || err}`);
} finally {
  await context.close();
}
report.failures = failures;
writeFileSync(join(outDir, 'report.json'), JSON.stringify(report, null, 2));
console.log(JSON.stringify(report, null, 2));
process.exit(failures.length ? 1 : 0);
