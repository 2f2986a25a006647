// The CAD attribute convention through the .3dm exchange, against the Python reader: every shared
// case of tests/plugin/cad_cases/cases.json is read (1) by the JS reader from plain records, (2) by
// the Python reader from the same records (python3 records.py), (3) from a .3dm file built with
// rhino3dm (blocks as meshes) and (4) again with every block a Brep. (1) must match the case's
// expectations, (2) exactly (messages) and to 1e-9 (model), (3) exactly, (4) in codes and in the
// geometry-free parts of the model. Cases with a closed-form alpha are solved from (3).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { EXCHANGE, REPO, run, tmpDir, solve, rblaExe } from './helpers.mjs';

const { loadRhino, readFile3dm } = await import(path.join(EXCHANGE, 'lib', 'rhino-io.mjs'));
const { documentRecord } = await import(path.join(EXCHANGE, 'lib', 'rhino-records.mjs'));
const { readDocument } = await import(path.join(EXCHANGE, 'lib', 'cad-reader.mjs'));
const { unitNormal } = await import(path.join(EXCHANGE, 'lib', 'cad-geometry.mjs'));

const CASES_DIR = path.join(REPO, 'tests', 'plugin', 'cad_cases');
const CASES = JSON.parse(fs.readFileSync(path.join(CASES_DIR, 'cases.json'), 'utf8')).cases;

function box(x0, x1, y0, y1, z0, z1) {
  const vertices = [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0], [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]];
  const faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
  return { vertices, faces };
}

/** The case's document record (the same as records.py builds). */
function documentOf(c) {
  const objects = c.objects.map((o, i) => {
    const rec = { guid: `guid-${i}`, name: o.name ?? null, layer: o.layer ?? 'Default', hidden: Boolean(o.hidden), user_text: { ...(o.user_text || {}) } };
    if (o.box || o.solid) return { ...rec, type: o.as === 'brep' ? 'Brep' : 'Mesh', shape: 'solid', ...(o.box ? box(...o.box) : o.solid) };
    if (o.pieces) return { ...rec, type: { mesh: 'Mesh', brep: 'Brep', curve: 'PolylineCurve' }[o.as], shape: 'polygons', polygons: o.pieces };
    return { ...rec, type: 'Point', shape: 'point', point: o.point };
  });
  const d = c.document;
  return { name: d.name ?? null, units: d.units, tolerance: d.tolerance, user_text: { ...(d.user_text || {}) }, objects };
}

function near(a, b, where) {
  if (Array.isArray(a)) {
    assert.ok(Array.isArray(b) && a.length === b.length, `${where}: ${JSON.stringify(a)?.slice(0, 200)} vs ${JSON.stringify(b)?.slice(0, 200)}`);
    a.forEach((x, i) => near(x, b[i], `${where}/${i}`));
  } else if (a !== null && typeof a === 'object') {
    assert.ok(b !== null && typeof b === 'object', where);
    assert.deepEqual(Object.keys(a).sort(), Object.keys(b).sort(), `${where}: keys`);
    for (const k of Object.keys(a)) near(a[k], b[k], `${where}/${k}`);
  } else if (typeof a === 'number') {
    assert.ok(typeof b === 'number' && Math.abs(a - b) <= 1e-9 * Math.max(1, Math.abs(a)), `${where}: ${a} vs ${b}`);
  } else assert.equal(a, b, where);
}

/** got contains want (the case's expectation; see test_cad_cases.match). */
function contains(want, got, where) {
  if (Array.isArray(want)) {
    assert.equal(got.length, want.length, `${where} (length)`);
    want.forEach((w, i) => contains(w, got[i], `${where}/${i}`));
  } else if (want !== null && typeof want === 'object') {
    for (const [k, v] of Object.entries(want)) {
      if (k === '$polygon') {
        assert.equal(got.polygon.length, v.corners, `${where}/polygon corners`);
        const area = unitNormal(got.polygon)[1];
        assert.ok(Math.abs(area - v.area) <= (v.area_rel ?? 1e-9) * v.area, `${where}/polygon area ${area}`);
      } else if (k === 'vertices') {
        v.forEach((p, j) => contains(p, got[k][j], `${where}/${k}/${j}`));
      } else {
        assert.ok(k in got, `${where}/${k} missing`);
        contains(v, got[k], `${where}/${k}`);
      }
    }
  } else if (typeof want === 'number') {
    assert.ok(Math.abs(got - want) <= 1e-9 * Math.max(1, Math.abs(want)), `${where}: ${got} vs ${want}`);
  } else assert.equal(got, want, where);
}

const codes = (messages, sev) => messages.filter((m) => m.severity === sev).map((m) => m.code);

// --- .3dm files of the cases ---------------------------------------------------------------------

function layerIndex(rhino, doc, fullPath, cache) {
  if (cache.has(fullPath)) return cache.get(fullPath);
  const parts = fullPath.split('::');
  let parentId = null;
  let index = -1;
  for (let k = 1; k <= parts.length; k++) {
    const p = parts.slice(0, k).join('::');
    if (!cache.has(p)) {
      const layer = new rhino.Layer();
      layer.name = parts[k - 1];
      if (parentId) layer.parentLayerId = parentId;
      cache.set(p, doc.layers().add(layer));
    }
    index = cache.get(p);
    parentId = doc.layers().findIndex(index).id;
  }
  return index;
}

function mesh(rhino, vertices, faces) {
  const m = new rhino.Mesh();
  for (const v of vertices) m.vertices().add(v[0], v[1], v[2]);
  vertices.forEach((v, i) => m.vertices().setPoint3dAt(i, v)); // double precision
  for (const f of faces) {
    if (f.length === 3) m.faces().addTriFace(...f);
    else if (f.length === 4) m.faces().addQuadFace(...f);
    else for (let k = 1; k + 1 < f.length; k++) m.faces().addTriFace(f[0], f[k], f[k + 1]);
  }
  return m;
}

function geometryOf(rhino, o, solidsAs) {
  if (o.solid && solidsAs === 'brep') return rhino.Brep.createFromMesh(mesh(rhino, o.solid.vertices, o.solid.faces), true);
  if (o.box || o.solid) {
    if (o.box && (solidsAs === 'brep' || o.as === 'brep')) return rhino.Brep.createFromBoundingBox(new rhino.BoundingBox([o.box[0], o.box[2], o.box[4]], [o.box[1], o.box[3], o.box[5]]));
    const b = o.box ? box(...o.box) : o.solid;
    return mesh(rhino, b.vertices, b.faces);
  }
  if (o.pieces && o.as === 'curve') return new rhino.PolylineCurve([...o.pieces[0], o.pieces[0][0]]);
  if (o.pieces) {
    const vertices = [], faces = [];
    for (const p of o.pieces) { faces.push(p.map((_, k) => vertices.length + k)); vertices.push(...p); }
    const m = mesh(rhino, vertices, faces);
    return o.as === 'brep' ? rhino.Brep.createFromMesh(m, true) : m;
  }
  return new rhino.Point(o.point);
}

async function file3dmOf(c, solidsAs, dir) {
  const rhino = await loadRhino();
  const doc = new rhino.File3dm();
  doc.settings().modelUnitSystem = rhino.UnitSystem[c.document.units];
  doc.settings().modelAbsoluteTolerance = c.document.tolerance;
  for (const [k, v] of Object.entries(c.document.user_text || {})) doc.strings().set(k, v);
  const layers = new Map();
  for (const o of c.objects) {
    const a = new rhino.ObjectAttributes();
    if (o.name) a.name = o.name;
    for (const [k, v] of Object.entries(o.user_text || {})) a.setUserString(k, v);
    a.layerIndex = layerIndex(rhino, doc, o.layer ?? 'Default', layers);
    if (o.hidden) a.mode = rhino.ObjectMode.Hidden;
    doc.objects().add(geometryOf(rhino, o, solidsAs), a);
  }
  const file = path.join(dir, `${c.name}.${solidsAs}.3dm`);
  fs.writeFileSync(file, doc.toByteArray());
  return file;
}

/** The exchange's reading of a case's .3dm file, with the objects' GUIDs replaced by guid-i. */
async function readThrough3dm(c, solidsAs, dir) {
  const rhino = await loadRhino();
  const file = await file3dmOf(c, solidsAs, dir);
  const doc = await readFile3dm(new Uint8Array(fs.readFileSync(file)));
  const record = documentRecord(rhino, doc, c.document.name);
  const real = new Map(record.objects.map((o, i) => [o.guid, `guid-${i}`]));
  record.objects.forEach((o) => { o.guid = real.get(o.guid); });
  const out = readDocument(record);
  return { model: out.model, messages: out.report.messages };
}

// --- tests --------------------------------------------------------------------------------------------

const python = run(process.env.PYTHON || 'python3', [path.join(CASES_DIR, 'records.py')]);
const PY = python.code === 0 ? new Map(JSON.parse(python.stdout).map((r) => [r.name, r])) : null;

test('the Python reader ran on the shared cases', () => {
  assert.equal(python.code, 0, python.stderr);
  assert.equal(PY.size, CASES.length);
});

test('numbers in messages: the JS reader prints them as Python prints %.12g', async () => {
  const { fmt } = await import(path.join(EXCHANGE, 'lib', 'cad-attributes.mjs'));
  const xs = [0, 0.6, 0.1 + 0.2, 25.4, 1e12, 1e7, 123456789012.5, 123456789013.5, 0.5, 2.5, 1e-5, 0.0001, -3.25e-7, 1e21, 5e-324, 99999999999.95, 999999999999.5, 1 / 3, -0.001, 304.8, 1e100];
  const r = run(process.env.PYTHON || 'python3', ['-c', `import json, sys; print(json.dumps(['%.12g' % x for x in json.load(sys.stdin)]))`], { input: JSON.stringify(xs) });
  assert.equal(r.code, 0, r.stderr);
  assert.deepEqual(xs.map(fmt), JSON.parse(r.stdout));
});

const dir = tmpDir('rbla-cad-cases-');
for (const c of CASES) {
  test(`CAD case ${c.name}: JS reader = expectation = Python reader = .3dm`, async () => {
    const js = readDocument(documentOf(c));
    const messages = js.report.messages;
    assert.deepEqual(codes(messages, 'error'), c.expect.errors, messages.map((m) => m.text).join('\n'));
    assert.deepEqual(codes(messages, 'warning'), c.expect.warnings, messages.map((m) => m.text).join('\n'));
    for (const t of c.expect.texts || []) assert.ok(messages.some((m) => m.text === t), `missing message: ${t}`);
    if (c.expect.errors.length) assert.equal(js.model, null);
    else contains(c.expect.model || {}, js.model, 'model');

    const py = PY.get(c.name);
    assert.deepEqual(messages, py.messages, 'messages of the JS and the Python reader');
    near(js.model, py.model, 'model (JS vs Python)');

    const viaMesh = await readThrough3dm(c, 'mesh', dir);
    if (c.expect.in_3dm) {
      // what a .3dm file cannot hold (an empty value) reads as absent
      assert.deepEqual(codes(viaMesh.messages, 'error'), c.expect.in_3dm.errors);
      assert.deepEqual(codes(viaMesh.messages, 'warning'), c.expect.in_3dm.warnings);
      return;
    }
    assert.deepEqual(viaMesh.messages, messages, 'messages from the .3dm file');
    near(viaMesh.model, js.model, 'model from the .3dm file');

    const viaBrep = await readThrough3dm(c, 'brep', dir);
    assert.deepEqual(codes(viaBrep.messages, 'error'), c.expect.errors);
    assert.deepEqual(codes(viaBrep.messages, 'warning'), c.expect.warnings);
    if (!c.expect.errors.length) {
      const strip = (m) => ({ ...m, blocks: m.blocks.map(({ vertices, faces, ...rest }) => rest), interfaces: (m.interfaces || []).map(({ polygon, ...rest }) => ({ ...rest, corners: polygon.length, area: unitNormal(polygon)[1] })) });
      near(strip(viaBrep.model), strip(js.model), 'model from the .3dm file with Breps (without vertex order)');
    }

    if (c.expect.alpha !== undefined && rblaExe()) {
      const mp = path.join(dir, `${c.name}.json`);
      fs.writeFileSync(mp, JSON.stringify(viaMesh.model));
      const res = solve(mp, path.join(dir, `${c.name}.result.json`));
      assert.ok(Math.abs(res.load_multiplier - c.expect.alpha) <= (c.expect.alpha_rel ?? 1e-5) * c.expect.alpha, `alpha ${res.load_multiplier} vs ${c.expect.alpha}`);
    }
  });
}
