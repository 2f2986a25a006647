// Browser viewer: served from 127.0.0.1, opened in headless Chromium (playwright-core, Debian's
// chromium), asserted through window.rblaViewer; every request must stay on 127.0.0.1.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { REPO, VIEWER, SAMPLES, ARTIFACTS, tmpDir, solve, rblaExe } from './helpers.mjs';

const CHROMIUM = process.env.RBLA_CHROMIUM || '/usr/bin/chromium';
const ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];
const DOC_SCREENSHOT = path.join(REPO, 'docs', 'images', 'viewer.png');
const DOC_SAMPLE = 'wall_opening';

let skip = false;
if (!fs.existsSync(CHROMIUM)) skip = `chromium not found at ${CHROMIUM} (apt-get install -y chromium)`;
else if (!fs.existsSync(path.join(VIEWER, 'dist', 'viewer.js'))) skip = 'viewer not built (cd plugin/viewer && npm ci && npm run build)';
else if (!rblaExe()) skip = 'no rbla binary (set RBLA_EXE)';

let server, base, dataDir, context, userDir;
const requests = [];

const TYPES = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8', '.json': 'application/json', '.css': 'text/css', '.png': 'image/png', '.map': 'application/json' };
function serveFrom(rootDir, rel, res) {
  const p = path.resolve(rootDir, '.' + path.posix.normalize('/' + rel));
  if (!p.startsWith(rootDir + path.sep) && p !== rootDir) { res.writeHead(403); res.end(); return; }
  fs.readFile(p, (err, buf) => {
    if (err) { res.writeHead(404); res.end('not found'); return; }
    res.writeHead(200, { 'content-type': TYPES[path.extname(p)] || 'application/octet-stream', 'cache-control': 'no-store' });
    res.end(buf);
  });
}

before(async () => {
  if (skip) return;
  dataDir = tmpDir('rbla-viewer-data-');
  for (const s of ['arch', 'wall_opening', 'wall_settlement']) {
    fs.copyFileSync(path.join(SAMPLES, `${s}.json`), path.join(dataDir, `${s}.json`));
    solve(path.join(dataDir, `${s}.json`), path.join(dataDir, `${s}.result.json`));
  }
  server = http.createServer((req, res) => {
    const u = new URL(req.url, 'http://127.0.0.1');
    const rel = decodeURIComponent(u.pathname);
    if (rel.startsWith('/data/')) serveFrom(dataDir, rel.slice('/data/'.length), res);
    else serveFrom(VIEWER, rel === '/' ? 'index.html' : rel.slice(1), res);
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  base = `http://127.0.0.1:${server.address().port}`;
  const { chromium } = await import('playwright-core');
  userDir = tmpDir('rbla-chromium-profile-');
  context = await chromium.launchPersistentContext(userDir, {
    executablePath: CHROMIUM, headless: true, args: ARGS, viewport: { width: 1280, height: 760 },
  });
  // every request the page makes is recorded; anything not on our 127.0.0.1 server is refused
  await context.route('**/*', (route) => {
    const url = route.request().url();
    requests.push(url);
    if (url.startsWith(base + '/')) route.continue(); else route.abort();
  });
  context.on('request', (r) => { if (!requests.includes(r.url())) requests.push(r.url()); });
  fs.mkdirSync(ARTIFACTS, { recursive: true });
});

after(async () => {
  await context?.close();
  server?.close();
  for (const d of [userDir, dataDir]) if (d) fs.rmSync(d, { recursive: true, force: true });
});

const CASES = [
  { sample: 'arch', blocks: 18 },
  { sample: 'wall_opening', blocks: 118 },
  { sample: 'wall_settlement', blocks: 127 },
];
const fmt6 = (x) => Number(x.toPrecision(6)).toString();

for (const { sample, blocks } of CASES) {
  test(`viewer shows ${sample} and its mechanism`, { skip }, async () => {
    const result = JSON.parse(fs.readFileSync(path.join(dataDir, `${sample}.result.json`), 'utf8'));
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
    await page.goto(`${base}/index.html?model=/data/${sample}.json&result=/data/${sample}.result.json`);
    await page.waitForFunction(() => window.rblaViewer && window.rblaViewer.ready, null, { timeout: 20000 });
    const st = await page.evaluate(() => { const v = window.rblaViewer; return { ...v, title: v.title, docTitle: document.title }; });
    assert.equal(st.error, null);
    assert.equal(st.blockCount, blocks);
    assert.equal(st.interfaceCount, result.interfaces.length);
    assert.ok(st.crackedCount > 0, 'some interfaces crack');
    assert.equal(st.crackedCount, result.cracked_interfaces.length);
    const head = typeof result.load_multiplier === 'number'
      ? `\u03b1 = ${fmt6(result.load_multiplier)}`
      : `R = ${fmt6(result.base_reaction.at_collapse)} ${result.units.force}`;
    if (sample !== 'wall_settlement') assert.ok(head.startsWith('\u03b1 = '));
    assert.ok(st.title.includes(head), `title "${st.title}" shows ${head}`);
    assert.equal(st.docTitle, st.title);
    assert.equal(st.verdict, result.verdict);
    assert.ok(Math.abs(st.amplitude - result.mechanism.displacement_scale) < 1e-12, 'starts at the suggested display scale');
    const text = await page.textContent('#headline');
    assert.equal(text, head);
    assert.ok(st.frames > 0, 'WebGL frames rendered');

    // the slider drives the amplitude
    const s2 = st.maxAmplitude * 0.25;
    await page.evaluate((s) => window.rblaViewer.setAmplitude(s), s2);
    assert.ok(Math.abs((await page.evaluate(() => window.rblaViewer.amplitude)) - s2) < 1e-12);
    await page.locator('#amplitude').fill(String(st.maxAmplitude));
    const a3 = await page.evaluate(() => window.rblaViewer.amplitude);
    assert.ok(Math.abs(a3 - st.maxAmplitude) < 1e-9 * (1 + st.maxAmplitude), `slider input sets amplitude (${a3})`);
    await page.evaluate((s) => window.rblaViewer.setAmplitude(s), result.mechanism.displacement_scale);

    // the canvas is not blank
    const shot = await page.screenshot({ path: path.join(ARTIFACTS, `viewer-${sample}.png`) });
    assert.ok(shot.length > 20000, `screenshot size ${shot.length}`);
    const colours = await page.evaluate(() => {
      const c = document.getElementById('view');
      const g = document.createElement('canvas'); g.width = 64; g.height = 64;
      const x = g.getContext('2d'); x.drawImage(c, 0, 0, 64, 64);
      const d = x.getImageData(0, 0, 64, 64).data; const set = new Set();
      for (let i = 0; i < d.length; i += 4) set.add((d[i] >> 4) + ',' + (d[i + 1] >> 4) + ',' + (d[i + 2] >> 4));
      return set.size;
    });
    assert.ok(colours > 8, `canvas shows a drawing (${colours} colours)`);
    if (sample === DOC_SAMPLE && (process.env.RBLA_UPDATE_DOC_SCREENSHOT === '1' || !fs.existsSync(DOC_SCREENSHOT))) {
      fs.mkdirSync(path.dirname(DOC_SCREENSHOT), { recursive: true });
      fs.writeFileSync(DOC_SCREENSHOT, shot);
    }
    assert.deepEqual(errors, [], 'no page errors');
    await page.close();
  });
}

test('viewer: every request goes to 127.0.0.1', { skip }, () => {
  assert.ok(requests.length >= 4, `requests seen: ${requests.length}`);
  const foreign = requests.filter((u) => !u.startsWith(base + '/') && !u.startsWith('data:'));
  assert.deepEqual(foreign, [], 'requests that left 127.0.0.1');
});
