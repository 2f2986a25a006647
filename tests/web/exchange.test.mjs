// .3dm exchange: sample -> model-to-3dm -> 3dm-to-model -> same geometry, valid model -> rbla solve
// -> result-to-3dm -> read back with rhino3dm (layers, object counts, colours); curved Breps rejected.
import { test, before } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { EXCHANGE, SAMPLES, node, readJson, tmpDir, validators, solve, rblaExe } from './helpers.mjs';

const { loadRhino, readFile3dm } = await import(path.join(EXCHANGE, 'lib', 'rhino-io.mjs'));
const G = await import(path.join(EXCHANGE, 'lib', 'rbla-geometry.mjs'));

let dir;
before(() => { dir = tmpDir('rbla-exchange-'); });

const canonFace = (f) => { const k = f.indexOf(Math.min(...f)); return [...f.slice(k), ...f.slice(0, k)].join(','); };

function assertSameGeometry(orig, back) {
  assert.equal(back.blocks.length, orig.blocks.length, 'block count');
  assert.equal(back.units.length, orig.units.length, 'length unit');
  for (let i = 0; i < orig.blocks.length; i++) {
    const a = orig.blocks[i], b = back.blocks[i];
    assert.equal(b.id, a.id, 'block id');
    assert.equal(b.role || 'free', a.role || 'free', `role of ${a.id}`);
    assert.equal(b.vertices.length, a.vertices.length, `vertex count of ${a.id}`);
    for (let k = 0; k < a.vertices.length; k++) for (let c = 0; c < 3; c++) {
      assert.ok(Math.abs(a.vertices[k][c] - b.vertices[k][c]) <= 1e-9, `${a.id} vertex ${k}: ${a.vertices[k]} vs ${b.vertices[k]}`);
    }
    assert.deepEqual(b.faces.map(canonFace).sort(), a.faces.map(canonFace).sort(), `faces of ${a.id} (same loops, same orientation)`);
  }
}

async function read3dm(p) { return readFile3dm(new Uint8Array(fs.readFileSync(p))); }

const CASES = [
  { sample: 'arch', as: 'brep' },
  { sample: 'wall_opening', as: 'mesh' },
  { sample: 'wall_settlement', as: 'brep' },
];

for (const { sample, as } of CASES) {
  test(`exchange round trip: ${sample} (${as})`, { skip: rblaExe() ? false : 'no rbla binary (set RBLA_EXE)' }, async () => {
    const V = validators();
    const src = path.join(SAMPLES, `${sample}.json`);
    const orig = readJson(src);
    const f3dm = path.join(dir, `${sample}.3dm`);
    const back = path.join(dir, `${sample}.back.json`);
    let r = node('model-to-3dm.mjs', [src, '-o', f3dm, '--as', as]);
    assert.equal(r.code, 0, r.stderr);
    r = node('3dm-to-model.mjs', [f3dm, '-o', back]);
    assert.equal(r.code, 0, r.stderr);
    const model = readJson(back);
    assertSameGeometry(orig, model);
    const vm = V.model(model);
    assert.ok(vm.ok, `round-tripped model invalid:\n${vm.errors}`);
    assert.deepEqual(model.analysis, orig.analysis, 'analysis kept in document User Text');

    // same answer from the original and the round-tripped model
    const res0 = solve(src, path.join(dir, `${sample}.orig.result.json`));
    const resPath = path.join(dir, `${sample}.result.json`);
    const res = solve(back, resPath);
    const vr = V.result(res);
    assert.ok(vr.ok, `result invalid:\n${vr.errors}`);
    assert.equal(res.status, 'collapse');
    const h0 = G.headline(res0), h = G.headline(res);
    assert.ok(Math.abs(h.value - h0.value) <= 1e-6 * Math.max(1, Math.abs(h0.value)), `${h.text} vs ${h0.text}`);

    // result -> .3dm, read back
    const out = path.join(dir, `${sample}.result.3dm`);
    const amp = 0.5;
    r = node('result-to-3dm.mjs', [back, resPath, '-o', out, '--amplitude', String(amp)]);
    assert.equal(r.code, 0, r.stderr);
    const rhino = await loadRhino();
    const doc = await read3dm(out);
    const layers = [];
    for (let i = 0; i < doc.layers().count; i++) layers.push(doc.layers().get(i));
    const paths = layers.map((l) => l.fullPath);
    const parent = paths[0];
    assert.match(parent, /^rbla run \d{4}-\d\d-\d\dT\d{6}Z$/);
    for (const sub of ['blocks', 'displaced', 'interfaces', 'labels', ...G.STATE_ORDER.map((s) => `interfaces::${s}`)]) {
      assert.ok(paths.includes(`${parent}::${sub}`), `layer ${parent}::${sub} in ${paths.join(' | ')}`);
    }
    const byLayer = new Map(paths.map((p) => [p, []]));
    for (let i = 0; i < doc.objects().count; i++) {
      const o = doc.objects().get(i);
      const a = o.attributes();
      byLayer.get(layers.find((l) => l.index === a.layerIndex).fullPath).push(o);
    }
    const on = (sub) => byLayer.get(`${parent}::${sub}`);
    assert.equal(on('blocks').length, model.blocks.length, 'original blocks');
    const nFixed = model.blocks.filter((b) => b.role === 'fixed').length;
    assert.equal(on('displaced').length, model.blocks.length - nFixed, 'displaced blocks (all but fixed)');
    const counts = Object.fromEntries(G.STATE_ORDER.map((s) => [s, 0]));
    for (const i of res.interfaces) counts[i.state || 'closed']++;
    for (const st of G.STATE_ORDER) {
      const objs = on(`interfaces::${st}`);
      assert.equal(objs.length, counts[st], `interfaces in state ${st}`);
      const want = G.hexToRgb(G.STATE_COLORS[st]);
      const lay = layers.find((l) => l.fullPath === `${parent}::interfaces::${st}`);
      assert.deepEqual({ r: lay.color.r, g: lay.color.g, b: lay.color.b }, want, `layer colour of ${st}`);
      for (const o of objs) {
        const c = o.attributes().objectColor;
        assert.deepEqual({ r: c.r, g: c.g, b: c.b }, want, `object colour of a ${st} interface`);
        assert.ok(o.geometry() instanceof rhino.Mesh);
      }
    }
    assert.ok(res.cracked_interfaces.length > 0);
    const dots = on('labels').map((o) => o.geometry()).filter((g) => g instanceof rhino.TextDot);
    const cracked = res.interfaces.filter((i) => i.cracked).length;
    assert.ok(dots.length >= 1 + cracked, 'headline dot + one dot per cracked interface');
    assert.ok(dots.some((d) => d.text === h.text), `a text dot reads "${h.text}"`);
    assert.ok(h.kind === (sample === 'wall_settlement' ? 'reaction' : 'alpha'));

    // displaced blocks follow the exact rigid motion p -> g + R(s theta)(p - g) + s u
    const rb = G.resultBlockMap(res);
    let checked = 0;
    for (const o of on('displaced')) {
      const id = o.attributes().name;
      const b = model.blocks.find((x) => x.id === id);
      const rbk = rb.get(id);
      if (!rbk || G.norm(rbk.rotation) === 0) continue;
      const { centroid } = G.polyhedronMassProps(b.vertices, b.faces);
      const mv = G.rigidMotion(centroid, rbk.translation, rbk.rotation, amp);
      const vl = o.geometry().vertices();
      const got = [];
      for (let k = 0; k < vl.count; k++) got.push(vl.point3dAt(k));
      for (const p of b.vertices) {
        const q = mv(p);
        assert.ok(got.some((g) => Math.hypot(g[0] - q[0], g[1] - q[1], g[2] - q[2]) < 1e-9), `${id}: displaced vertex ${q}`);
      }
      // rigidity: pairwise distances preserved
      const d = (x, y) => Math.hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]);
      const moved = b.vertices.map(mv);
      for (let k = 1; k < moved.length; k++) assert.ok(Math.abs(d(moved[0], moved[k]) - d(b.vertices[0], b.vertices[k])) < 1e-12 * (1 + d(b.vertices[0], b.vertices[k])));
      if (++checked >= 5) break;
    }
    assert.ok(checked > 0, 'some displaced block rotates');
  });
}

/** model -> model-to-3dm -> 3dm-to-model (with extra arguments): { src, out, back, stderr }. */
function roundTrip(model, name, args = []) {
  const src = path.join(dir, `${name}.json`);
  fs.writeFileSync(src, JSON.stringify(model));
  const f3dm = path.join(dir, `${name}.3dm`);
  let r = node('model-to-3dm.mjs', [src, '-o', f3dm]);
  assert.equal(r.code, 0, r.stderr);
  const out = path.join(dir, `${name}.back.json`);
  r = node('3dm-to-model.mjs', [f3dm, '-o', out, ...args]);
  assert.equal(r.code, 0, r.stderr);
  return { src, out, back: readJson(out), stderr: r.stderr };
}

test('document units: millimetres survive the round trip', async () => {
  const orig = readJson(path.join(SAMPLES, 'column.json'));
  const mm = { ...orig, units: { ...orig.units, length: 'mm' }, blocks: orig.blocks.map((b) => ({ ...b, vertices: b.vertices.map((p) => p.map((x) => x * 1000)), centroid: undefined, volume: undefined })) };
  const { back } = roundTrip(mm, 'column_mm', ['--friction', '0.5', '--unit-weight', '20']);
  assert.equal(back.units.length, 'mm');
  assert.deepEqual(back.defaults, { unit_weight: 20, friction: 0.5 });
  assertSameGeometry(mm, back);
  assert.ok(validators().model(back).ok);
});

test('User Text and extrusions: roles, unit weight, label, friction from object attributes', async () => {
  const rhino = await loadRhino();
  const doc = new rhino.File3dm();
  doc.settings().modelUnitSystem = rhino.UnitSystem.Centimeters;
  const base = new rhino.ObjectAttributes();
  base.name = 'ground';
  base.setUserString('rbla.role', 'fixed');
  doc.objects().add(rhino.Brep.createFromBoundingBox(new rhino.BoundingBox([-100, -50, -20], [100, 50, 0])), base);
  const top = new rhino.ObjectAttributes();
  top.name = 'stone';
  top.setUserString('rbla.unit_weight', '22');
  top.setUserString('rbla.friction', '0.7');
  top.setUserString('rbla.label', 'lintel stone');
  const ext = rhino.Extrusion.createBoxExtrusion(new rhino.Box(new rhino.BoundingBox([-20, -20, 0], [20, 20, 80])), true);
  doc.objects().add(ext || rhino.Brep.createFromBoundingBox(new rhino.BoundingBox([-20, -20, 0], [20, 20, 80])), top);
  // a pentagonal prism (extrusion of a closed polyline): 5-gon caps must stay single faces
  const pl = new rhino.Polyline();
  for (const p of [[50, -20, 0], [90, -20, 0], [90, 10, 0], [70, 30, 0], [50, 10, 0], [50, -20, 0]]) pl.add(...p);
  const penta = rhino.Extrusion.create(pl.toNurbsCurve(), 60, true);
  assert.ok(penta instanceof rhino.Extrusion);
  const pa = new rhino.ObjectAttributes();
  pa.name = 'pentagon';
  doc.objects().add(penta, pa);
  const f = path.join(dir, 'usertext.3dm');
  fs.writeFileSync(f, doc.toByteArray());
  const out = path.join(dir, 'usertext.json');
  const r = node('3dm-to-model.mjs', [f, '-o', out]);
  assert.equal(r.code, 0, r.stderr);
  const m = readJson(out);
  assert.equal(m.units.length, 'cm');
  assert.deepEqual(m.blocks.map((b) => [b.id, b.role]), [['ground', 'fixed'], ['stone', 'free'], ['pentagon', 'free']]);
  const pent = m.blocks[2];
  assert.equal(pent.vertices.length, 10);
  assert.deepEqual(pent.faces.map((f) => f.length).sort(), [4, 4, 4, 4, 4, 5, 5]);
  assert.ok(Math.abs(pent.volume - (40 * 30 + 0.5 * 40 * 20) * 60) < 1e-6, `pentagon volume ${pent.volume}`);
  assert.equal(m.blocks[1].unit_weight, 22);
  assert.equal(m.blocks[1].label, 'lintel stone');
  // a block's friction cannot reach the interfaces rbla detects (the model has one friction for
  // them): they take the smallest of the default (0.6) and the block values, with a warning
  assert.equal(m.defaults?.friction, undefined);
  assert.match(r.stderr, /warning \[block_friction\]: 1 block\(s\) carry rbla.friction \(0.7\).* all use 0.6/);
  assert.ok(Math.abs(m.blocks[1].volume - 40 * 40 * 80) < 1e-6);
  assert.ok(validators().model(m).ok);
});

/** A .3dm of a base and a 1 x 0.5 x 2 block, with the given document and object User Text. */
async function twoBlocks3dm(file, { docText = {}, baseText = {}, blockText = {}, extra = null } = {}) {
  const rhino = await loadRhino();
  const doc = new rhino.File3dm();
  doc.settings().modelUnitSystem = rhino.UnitSystem.Meters;
  for (const [k, v] of Object.entries(docText)) doc.strings().set(k, v);
  const attr = (name, text) => { const a = new rhino.ObjectAttributes(); a.name = name; for (const [k, v] of Object.entries(text)) a.setUserString(k, v); return a; };
  doc.objects().add(rhino.Brep.createFromBoundingBox(new rhino.BoundingBox([-2, -2, -0.5], [2, 2, 0])), attr('base', baseText));
  doc.objects().add(rhino.Brep.createFromBoundingBox(new rhino.BoundingBox([-0.5, -0.25, 0], [0.5, 0.25, 2])), attr('block', blockText));
  if (extra) extra(rhino, doc, attr);
  fs.writeFileSync(file, doc.toByteArray());
}

test('the reported case through the command line: seismic along +y, default friction, support, rbla.id, rbla.ignore', { skip: rblaExe() ? false : 'no rbla binary (set RBLA_EXE)' }, async () => {
  const f = path.join(dir, 'issue.3dm');
  await twoBlocks3dm(f, {
    docText: { 'rbla.analysis': 'seismic', 'rbla.seismic_direction': '0, 1, 0', 'rbla.default_friction': '0.3' },
    baseText: { 'rbla.role': 'support' },
    blockText: { 'rbla.id': 'B1' },
    extra: (rhino, doc, attr) => doc.objects().add(rhino.Brep.createFromBoundingBox(new rhino.BoundingBox([5, 5, 0], [6, 6, 1])), attr('scrap', { 'rbla.ignore': 'true' })),
  });
  const out = path.join(dir, 'issue.json');
  const r = node('3dm-to-model.mjs', [f, '-o', out]);
  assert.equal(r.code, 0, r.stderr);
  assert.doesNotMatch(r.stderr, /warning|not valid JSON/);
  const m = readJson(out);
  assert.deepEqual(m.analysis, { type: 'load_multiplier', seismic: { direction: [0, 1, 0] } });
  assert.deepEqual(m.defaults, { friction: 0.3 });
  assert.deepEqual(m.blocks.map((b) => [b.id, b.role]), [['base', 'fixed'], ['B1', 'free']]);
  assert.equal(m.title, 'issue');
  // rocking about a y edge: alpha = b / h = 0.5 / 2 (sliding would need alpha > mu = 0.3)
  const res = solve(out, path.join(dir, 'issue.result.json'));
  assert.ok(Math.abs(res.load_multiplier - 0.25) < 1e-6, `alpha ${res.load_multiplier}`);
});

test('unreadable attributes: every error listed with its code, nothing written, an existing file kept', async () => {
  const f = path.join(dir, 'bad.3dm');
  await twoBlocks3dm(f, { docText: { 'rbla.seismic_direction': '0, 0, 1' }, baseText: { 'rbla.role': 'floating' }, blockText: { 'rbla.friction': 'high', 'rbla.rol': 'x' } });
  const out = path.join(dir, 'bad.json');
  fs.writeFileSync(out, 'keep me');
  const r = node('3dm-to-model.mjs', [f, '-o', out]);
  assert.equal(r.code, 1);
  assert.match(r.stderr, /error \[bad_choice\]: object "base": rbla.role must be one of free, fixed, moving_support, got "floating"/);
  assert.match(r.stderr, /error \[bad_number\]: object "block": rbla.friction must be a number, got "high"/);
  assert.match(r.stderr, /error \[not_horizontal\]: document: rbla.seismic_direction must be perpendicular to gravity/);
  assert.match(r.stderr, /warning \[unknown_key\]: object "block": unknown key rbla.rol ignored; did you mean rbla.role\?/);
  assert.match(r.stderr, /3 error\(s\); no model written/);
  assert.equal(fs.readFileSync(out, 'utf8'), 'keep me');
  assert.deepEqual(fs.readdirSync(dir).filter((x) => x.startsWith('bad.json.tmp')), []);
});

test('model -> .3dm -> model keeps given interfaces, loads, analysis and detection settings', { skip: rblaExe() ? false : 'no rbla binary (set RBLA_EXE)' }, async () => {
  const orig = readJson(path.join(SAMPLES, 'column.json'));
  const top = orig.blocks.at(-1);
  const zTop = Math.max(...top.vertices.map((v) => v[2]));
  const below = orig.blocks.at(-2);
  const zJoint = Math.min(...top.vertices.map((v) => v[2]));
  const xs = top.vertices.map((v) => v[0]), ys = top.vertices.map((v) => v[1]);
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const model = {
    ...orig,
    interfaces: [{ id: 'J1', label: 'top joint', blocks: [below.id, top.id], friction: 0.5, polygon: [[x0, y0, zJoint], [x1, y0, zJoint], [x1, y1, zJoint], [x0, y1, zJoint]] }],
    detection: { mode: 'merge', angle_tolerance: 2 },
    loads: { live: [{ block: top.id, force: [1, 0, 0], point: [(x0 + x1) / 2, (y0 + y1) / 2, zTop] }], dead: [{ block: top.id, force: [0, 0, -3] }] },
    analysis: { type: 'load_multiplier', cone: 'pyramid_inscribed', pyramid_faces: 16 },
  };
  const { src, out, back, stderr } = roundTrip(model, 'column_loads');
  assert.doesNotMatch(stderr, /warning/);
  assert.deepEqual(back.interfaces, model.interfaces);
  assert.deepEqual(back.detection, model.detection);
  assert.deepEqual(back.analysis, model.analysis);
  assert.deepEqual(back.loads.live, model.loads.live);
  const g = G.polyhedronMassProps(top.vertices, top.faces).centroid; // a dead load without a point acts at the centroid
  assert.equal(back.loads.dead[0].block, top.id);
  for (let c = 0; c < 3; c++) assert.ok(Math.abs(back.loads.dead[0].point[c] - g[c]) < 1e-9);
  assert.ok(validators().model(back).ok);
  const a0 = solve(src, path.join(dir, 'cl0.result.json')).load_multiplier;
  const a1 = solve(out, path.join(dir, 'cl1.result.json')).load_multiplier;
  assert.ok(Math.abs(a0 - a1) <= 1e-6 * Math.abs(a0), `${a0} vs ${a1}`);
});

test('a curved Brep (sphere) is rejected by name with a non-zero exit', async () => {
  const rhino = await loadRhino();
  const doc = new rhino.File3dm();
  doc.settings().modelUnitSystem = rhino.UnitSystem.Meters;
  const box = new rhino.ObjectAttributes();
  box.name = 'plinth';
  doc.objects().add(rhino.Brep.createFromBoundingBox(new rhino.BoundingBox([-1, -1, -1], [1, 1, 0])), box);
  const ball = new rhino.ObjectAttributes();
  ball.name = 'dome_ball';
  doc.objects().add(rhino.Brep.createFromSphere(new rhino.Sphere([0, 0, 1], 1)), ball);
  const f = path.join(dir, 'sphere.3dm');
  fs.writeFileSync(f, doc.toByteArray());
  const out = path.join(dir, 'sphere.json');
  const r = node('3dm-to-model.mjs', [f, '-o', out]);
  assert.notEqual(r.code, 0);
  assert.match(r.stderr, /"dome_ball"/);
  assert.match(r.stderr, /curved Brep/);
  assert.ok(!fs.existsSync(out), 'no model written');
});
