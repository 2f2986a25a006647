// rbla <-> Rhino .3dm exchange on top of rhino3dm (openNURBS compiled to WebAssembly).
// No Rhino installation is needed.
import rhino3dm from 'rhino3dm';
import {
  STATE_COLORS, STATE_ORDER, hexToRgb, newellNormal, triangulatePolygon, polyhedronMassProps,
  rigidMotion, resultBlockMap, headline, fmt, sub, dot, cross, norm, interfacePolygon,
} from './rbla-geometry.mjs';

let rhinoPromise = null;
export function loadRhino() {
  if (!rhinoPromise) rhinoPromise = rhino3dm();
  return rhinoPromise;
}

export class ExchangeError extends Error {}

// --- units ----------------------------------------------------------------------------------
const UNIT_TO_METRES = {
  Millimeters: 1e-3, Centimeters: 1e-2, Meters: 1, Decimeters: 0.1, Kilometers: 1e3,
  Microns: 1e-6, Inches: 0.0254, Feet: 0.3048, Yards: 0.9144,
};
const RBLA_UNITS = { Millimeters: 'mm', Centimeters: 'cm', Meters: 'm' };
const RBLA_TO_RHINO = { mm: 'Millimeters', cm: 'Centimeters', m: 'Meters' };

function unitName(rhino, value) {
  for (const k of Object.keys(rhino.UnitSystem)) {
    if (k === 'values' || k === 'argCount') continue;
    if (rhino.UnitSystem[k] === value || rhino.UnitSystem[k]?.value === value?.value) return k;
  }
  return 'None';
}

const colorObj = (hex, a = 255) => ({ ...hexToRgb(hex), a });

// --- model -> .3dm ------------------------------------------------------------------------------
function meshFromPolyhedron(rhino, vertices, faces) {
  const mesh = new rhino.Mesh();
  const vl = mesh.vertices();
  for (const v of vertices) vl.add(v[0], v[1], v[2]);
  vertices.forEach((v, i) => vl.setPoint3dAt(i, v)); // keep double precision
  for (const f of faces) {
    if (f.length === 3) mesh.faces().addTriFace(f[0], f[1], f[2]);
    else if (f.length === 4) mesh.faces().addQuadFace(f[0], f[1], f[2], f[3]);
    else {
      const pts = f.map((i) => vertices[i]);
      for (const [a, b, c] of triangulatePolygon(pts)) mesh.faces().addTriFace(f[a], f[b], f[c]);
    }
  }
  mesh.normals().computeNormals?.();
  mesh.compact();
  return mesh;
}

/**
 * Build a File3dm from a model JSON. Blocks become closed Breps (planar faces; default) or closed
 * meshes (`as: 'mesh'`), named by block id, with User Text rbla.role / rbla.unit_weight / rbla.label.
 * Model-wide settings go to the document User Text (rbla.* keys).
 */
export async function modelTo3dm(model, { as = 'brep' } = {}) {
  const rhino = await loadRhino();
  const doc = new rhino.File3dm();
  const len = model.units?.length || 'm';
  doc.settings().modelUnitSystem = rhino.UnitSystem[RBLA_TO_RHINO[len]];
  doc.settings().modelAbsoluteTolerance = { m: 1e-4, cm: 1e-2, mm: 0.1 }[len];
  const strings = doc.strings();
  strings.set('rbla.schema_version', model.schema_version || '1.0.0');
  if (model.title) strings.set('rbla.title', model.title);
  if (model.units?.force) strings.set('rbla.units.force', model.units.force);
  if (model.units?.unit_weight) strings.set('rbla.units.unit_weight', model.units.unit_weight);
  if (model.gravity) strings.set('rbla.gravity', model.gravity);
  if (model.defaults?.unit_weight !== undefined) strings.set('rbla.unit_weight', String(model.defaults.unit_weight));
  if (model.defaults?.friction !== undefined) strings.set('rbla.friction', String(model.defaults.friction));
  for (const key of ['analysis', 'loads', 'detection', 'interfaces']) {
    if (model[key] !== undefined) strings.set(`rbla.${key}`, JSON.stringify(model[key]));
  }
  const roleLayer = {};
  const roleColors = { free: '#c8b496', fixed: '#505050', moving_support: '#2ca02c' };
  for (const role of ['free', 'fixed', 'moving_support']) {
    const layer = new rhino.Layer();
    layer.name = `rbla ${role}`;
    layer.color = colorObj(roleColors[role]);
    roleLayer[role] = doc.layers().add(layer);
  }
  for (const b of model.blocks) {
    const role = b.role || 'free';
    const attr = new rhino.ObjectAttributes();
    attr.name = b.id;
    attr.layerIndex = roleLayer[role];
    attr.setUserString('rbla.role', role);
    if (b.unit_weight !== undefined) attr.setUserString('rbla.unit_weight', String(b.unit_weight));
    if (b.label !== undefined) attr.setUserString('rbla.label', b.label);
    const mesh = meshFromPolyhedron(rhino, b.vertices, b.faces);
    if (as === 'mesh') {
      doc.objects().add(mesh, attr);
    } else {
      const brep = rhino.Brep.createFromMesh(mesh, true);
      if (!brep) throw new ExchangeError(`block ${b.id}: could not build a Brep`);
      doc.objects().add(brep, attr);
    }
  }
  return doc;
}

// --- .3dm -> model ------------------------------------------------------------------------------
function weldKey(p, tol) {
  return p.map((x) => Math.round(x / tol)).join(',');
}

/** Extract {vertices, faces} from a closed planar-faced Brep, or throw an ExchangeError naming it. */
function polyhedronFromBrep(rhino, brep, name, tol) {
  const bverts = brep.vertices();
  const vertices = [];
  for (let i = 0; i < bverts.count; i++) vertices.push(bverts.get(i).location);
  if (!brep.isSolid) throw new ExchangeError(`object "${name}": the Brep is not closed (not a solid); close it (Cap/Join) or export it as a closed mesh`);
  const edges = brep.edges();
  const faces = [];
  const fl = brep.faces();
  for (let fi = 0; fi < fl.count; fi++) {
    const face = fl.get(fi);
    const loops = face.loops;
    if (loops.count !== 1) throw new ExchangeError(`object "${name}": face ${fi} has holes (inner trimming loops), which rbla faces cannot represent; split the face`);
    const loop = face.outerLoop();
    const idx = [];
    for (let t = 0; t < loop.trimCount; t++) {
      const trim = loop.trims.get(t);
      if (trim.edgeIndex < 0) throw new ExchangeError(`object "${name}" is a curved Brep (singular trim on face ${fi}); rhino3dm cannot mesh curved Breps: mesh it in Rhino (_Mesh) or model it with planar faces`);
      const edge = edges.get(trim.edgeIndex);
      if (!edge.isLinear()) throw new ExchangeError(`object "${name}" is a curved Brep (face ${fi} has a curved edge); rhino3dm cannot mesh curved Breps: mesh it in Rhino (_Mesh) or model it with planar faces`);
      idx.push(trim.startVertexIndex);
    }
    // drop repeated consecutive vertices
    const clean = idx.filter((v, k) => v !== idx[(k + idx.length - 1) % idx.length]);
    if (clean.length < 3) throw new ExchangeError(`object "${name}" is a curved Brep (face ${fi} is bounded by fewer than 3 straight edges); rhino3dm cannot mesh curved Breps`);
    const pts = clean.map((i) => vertices[i]);
    // planarity: loop vertices and a grid of surface samples must lie on the polygon plane
    const nrm = newellNormal(pts);
    const nl = norm(nrm);
    if (nl < 1e-300) throw new ExchangeError(`object "${name}": face ${fi} is degenerate`);
    const n = nrm.map((x) => x / nl);
    const c = pts.reduce((a, p) => [a[0] + p[0] / pts.length, a[1] + p[1] / pts.length, a[2] + p[2] / pts.length], [0, 0, 0]);
    const off = (p) => Math.abs(dot(sub(p, c), n));
    let maxOff = Math.max(...pts.map(off));
    const srf = face.underlyingSurface();
    try {
      const du = srf.domain(0), dv = srf.domain(1);
      const u0 = du[0] ?? du.t0 ?? du.min, u1 = du[1] ?? du.t1 ?? du.max;
      const v0 = dv[0] ?? dv.t0 ?? dv.min, v1 = dv[1] ?? dv.t1 ?? dv.max;
      if ([u0, u1, v0, v1].every(Number.isFinite)) {
        for (const a of [0.25, 0.5, 0.75]) for (const b of [0.25, 0.5, 0.75]) {
          const p = srf.pointAt(u0 + a * (u1 - u0), v0 + b * (v1 - v0));
          if (p && p.length === 3) maxOff = Math.max(maxOff, off(p));
        }
      }
    } catch { /* surface sampling unavailable: vertex planarity only */ }
    if (maxOff > tol) throw new ExchangeError(`object "${name}" is a curved Brep (face ${fi} is not planar, deviation ${fmt(maxOff)} > tolerance ${fmt(tol)}); rhino3dm cannot mesh curved Breps: mesh it in Rhino (_Mesh) or model it with planar faces`);
    // outer loops run counter-clockwise about the surface normal; a reversed face flips it
    let poly = clean;
    try {
      const sn = srf.normalAt(0.5 * (srf.domain(0)[0] + srf.domain(0)[1]), 0.5 * (srf.domain(1)[0] + srf.domain(1)[1]));
      const faceN = face.orientationIsReversed ? sn.map((x) => -x) : sn;
      if (dot(faceN, n) < 0) poly = [...clean].reverse();
    } catch {
      if (face.orientationIsReversed) poly = [...clean].reverse();
    }
    faces.push(poly);
  }
  return compactPolyhedron(vertices, faces);
}

function compactPolyhedron(vertices, faces) {
  const used = new Map();
  const outV = [];
  const outF = faces.map((f) => f.map((i) => {
    if (!used.has(i)) { used.set(i, outV.length); outV.push(vertices[i]); }
    return used.get(i);
  }));
  // keep original vertex order where possible: renumber in order of first appearance in the vertex list
  const order = [...used.keys()].sort((a, b) => a - b);
  const remap = new Map(order.map((old, k) => [old, k]));
  return { vertices: order.map((i) => vertices[i]), faces: faces.map((f) => f.map((i) => remap.get(i))) };
}

function polyhedronFromMesh(mesh, name, tol) {
  if (!mesh.isClosed) throw new ExchangeError(`object "${name}": the mesh is not closed`);
  const vl = mesh.vertices();
  const raw = [];
  for (let i = 0; i < vl.count; i++) raw.push(vl.point3dAt ? vl.point3dAt(i) : vl.get(i));
  // weld coincident vertices (meshes often duplicate them along creases)
  const keyToIdx = new Map();
  const map = [];
  const vertices = [];
  for (const p of raw) {
    const k = weldKey(p, tol);
    if (!keyToIdx.has(k)) { keyToIdx.set(k, vertices.length); vertices.push(p); }
    map.push(keyToIdx.get(k));
  }
  const faces = [];
  const fl = mesh.faces();
  for (let i = 0; i < fl.count; i++) {
    const f = fl.get(i).map((j) => map[j]);
    const poly = f[2] === f[3] ? [f[0], f[1], f[2]] : f;
    const clean = poly.filter((v, k) => v !== poly[(k + poly.length - 1) % poly.length]);
    if (clean.length >= 3) faces.push(clean);
  }
  if (faces.length < 4) throw new ExchangeError(`object "${name}": the mesh has fewer than 4 faces`);
  return compactPolyhedron(vertices, faces);
}

function orientOutward(poly) {
  const { volume } = polyhedronMassProps(poly.vertices, poly.faces);
  if (volume < 0) poly.faces = poly.faces.map((f) => [...f].reverse());
  return poly;
}

function parseNumber(str, what, name) {
  const x = Number(str);
  if (!Number.isFinite(x)) throw new ExchangeError(`object "${name}": ${what} "${str}" is not a number`);
  return x;
}

/**
 * Convert a File3dm to a model JSON. Options: unitWeight, friction (override defaults),
 * title. Returns { model, warnings }. Throws ExchangeError (naming the object) on unsupported geometry.
 */
export async function file3dmToModel(doc, opts = {}) {
  const rhino = await loadRhino();
  const warnings = [];
  const strings = doc.strings();
  const dget = (k) => { try { const v = strings.getvalue(k); return v === '' || v == null ? undefined : v; } catch { return undefined; } };
  const unit = unitName(rhino, doc.settings().modelUnitSystem);
  let length = RBLA_UNITS[unit];
  let factor = 1;
  if (!length) {
    if (unit === 'None') { length = 'm'; warnings.push('document has no unit system: assuming metres'); }
    else if (UNIT_TO_METRES[unit]) { length = 'm'; factor = UNIT_TO_METRES[unit]; warnings.push(`document units ${unit} converted to metres`); }
    else throw new ExchangeError(`document unit system ${unit} is not supported (use mm, cm or m)`);
  }
  const absTol = (doc.settings().modelAbsoluteTolerance || 1e-3);
  const model = { schema_version: dget('rbla.schema_version') || '1.0.0' };
  const title = opts.title ?? dget('rbla.title');
  if (title) model.title = title;
  model.units = { length };
  const fu = dget('rbla.units.force'); if (fu) model.units.force = fu;
  const wu = dget('rbla.units.unit_weight'); if (wu) model.units.unit_weight = wu;
  const grav = dget('rbla.gravity'); if (grav) model.gravity = grav;
  const defaults = {};
  const duw = opts.unitWeight ?? (dget('rbla.unit_weight') !== undefined ? Number(dget('rbla.unit_weight')) : undefined);
  const dfr = opts.friction ?? (dget('rbla.friction') !== undefined ? Number(dget('rbla.friction')) : undefined);
  if (duw !== undefined) defaults.unit_weight = duw;
  if (dfr !== undefined) defaults.friction = dfr;
  model.defaults = defaults;
  model.blocks = [];

  const layerPath = (idx) => { try { return doc.layers().findIndex(idx)?.fullPath; } catch { return undefined; } };
  const ids = new Set();
  const frictions = new Set();
  const objs = doc.objects();
  for (let i = 0; i < objs.count; i++) {
    const o = objs.get(i);
    const g = o.geometry();
    const a = o.attributes();
    const ot = g.objectType;
    const type = g.constructor?.name;
    const name = a.name || `B${i}`;
    let poly;
    const tol = Math.max(absTol, 1e-9) ;
    if (g instanceof rhino.Brep) poly = polyhedronFromBrep(rhino, g, name, tol);
    else if (g instanceof rhino.Extrusion) poly = polyhedronFromBrep(rhino, g.toBrep(true), name, tol);
    else if (g instanceof rhino.Mesh) poly = polyhedronFromMesh(g, name, Math.min(tol, 1e-9) || 1e-9);
    else { warnings.push(`object "${name}" (${type || ot}) skipped: not a Brep, extrusion or mesh`); continue; }
    orientOutward(poly);
    if (factor !== 1) poly.vertices = poly.vertices.map((p) => p.map((x) => x * factor));
    let id = a.name || `B${i}`;
    if (ids.has(id)) {
      let k = 2; while (ids.has(`${id}_${k}`)) k++;
      warnings.push(`duplicate object name "${id}": block renamed "${id}_${k}"`);
      id = `${id}_${k}`;
    }
    ids.add(id);
    const block = { id };
    const label = a.getUserString('rbla.label') || layerPath(a.layerIndex);
    if (label) block.label = label;
    const role = a.getUserString('rbla.role') || 'free';
    if (!['free', 'fixed', 'moving_support'].includes(role)) throw new ExchangeError(`object "${name}": rbla.role "${role}" must be free, fixed or moving_support`);
    block.role = role;
    block.vertices = poly.vertices;
    block.faces = poly.faces;
    const mp = polyhedronMassProps(poly.vertices, poly.faces);
    if (!(mp.volume > 0)) throw new ExchangeError(`object "${name}": zero volume`);
    block.centroid = mp.centroid;
    block.volume = mp.volume;
    const uw = a.getUserString('rbla.unit_weight');
    if (uw) block.unit_weight = parseNumber(uw, 'rbla.unit_weight', name);
    const fr = a.getUserString('rbla.friction');
    if (fr) frictions.add(parseNumber(fr, 'rbla.friction', name));
    model.blocks.push(block);
  }
  if (frictions.size > 0 && opts.friction === undefined) {
    const mu = Math.min(...frictions);
    if (frictions.size > 1) warnings.push(`objects carry different rbla.friction values (${[...frictions].join(', ')}); model schema 1.x has no per-block friction: using the smallest, ${mu}, for all interfaces`);
    model.defaults.friction = mu;
  }
  if (Object.keys(model.defaults).length === 0) delete model.defaults;
  for (const key of ['loads', 'detection', 'interfaces', 'analysis']) {
    const v = dget(`rbla.${key}`);
    if (v) { try { model[key] = JSON.parse(v); } catch { warnings.push(`document User Text rbla.${key} is not valid JSON: ignored`); } }
  }
  if (model.blocks.length === 0) throw new ExchangeError('the .3dm file contains no closed Brep, extrusion or mesh');
  return { model, warnings };
}

// --- result -> .3dm -----------------------------------------------------------------------------
function addLayer(rhino, doc, name, hex, parentId) {
  const layer = new rhino.Layer();
  layer.name = name;
  layer.color = colorObj(hex);
  if (parentId) layer.parentLayerId = parentId;
  const idx = doc.layers().add(layer);
  const added = doc.layers().findIndex(idx);
  return { index: idx, id: added.id };
}

function coloredAttr(rhino, layerIndex, hex, name) {
  const attr = new rhino.ObjectAttributes();
  attr.layerIndex = layerIndex;
  attr.colorSource = rhino.ObjectColorSource.ColorFromObject;
  attr.objectColor = colorObj(hex);
  if (name) attr.name = name;
  return attr;
}

export function runLayerName(date = new Date()) {
  return `rbla run ${date.toISOString().replace(/\.\d+Z$/, 'Z').replace(/:/g, '')}`;
}

/**
 * Build the result .3dm: under a parent layer "rbla run <timestamp>", sublayers
 *   blocks (original), displaced (rigid motion at amplitude s), interfaces::<state> (contact
 *   polygons coloured by state), labels (text dots).
 */
export async function resultTo3dm(model, result, { amplitude, runName, date } = {}) {
  const rhino = await loadRhino();
  const doc = new rhino.File3dm();
  const len = model.units?.length || result.units?.length || 'm';
  doc.settings().modelUnitSystem = rhino.UnitSystem[RBLA_TO_RHINO[len]];
  const s = amplitude ?? result.mechanism?.displacement_scale ?? 1;
  const parentName = runName || runLayerName(date);
  const parent = addLayer(rhino, doc, parentName, '#000000');
  const Lblocks = addLayer(rhino, doc, 'blocks', '#c8b496', parent.id);
  const Ldisp = addLayer(rhino, doc, 'displaced', '#8c564b', parent.id);
  const Lif = addLayer(rhino, doc, 'interfaces', '#9e9e9e', parent.id);
  const Lstate = {};
  for (const st of STATE_ORDER) Lstate[st] = addLayer(rhino, doc, st, STATE_COLORS[st], Lif.id);
  const Llab = addLayer(rhino, doc, 'labels', '#000000', parent.id);

  const rb = resultBlockMap(result);
  const roleHex = { free: '#c8b496', fixed: '#505050', moving_support: '#2ca02c' };
  let zmax = -Infinity, xmid = 0, ymid = 0, n = 0;
  const centroids = new Map();
  for (const b of model.blocks) {
    const role = b.role || 'free';
    const mp = polyhedronMassProps(b.vertices, b.faces);
    centroids.set(b.id, mp.centroid);
    for (const v of b.vertices) { zmax = Math.max(zmax, v[2]); xmid += v[0]; ymid += v[1]; n++; }
    const mesh = meshFromPolyhedron(rhino, b.vertices, b.faces);
    const a1 = coloredAttr(rhino, Lblocks.index, roleHex[role], b.id);
    a1.setUserString('rbla.role', role);
    doc.objects().add(mesh, a1);
    const r = rb.get(b.id);
    const moves = r && (norm(r.translation || [0, 0, 0]) > 0 || norm(r.rotation || [0, 0, 0]) > 0);
    if (moves || role !== 'fixed') {
      const motion = rigidMotion(mp.centroid, r?.translation, r?.rotation, r ? s : 0);
      const moved = b.vertices.map(motion);
      const m2 = meshFromPolyhedron(rhino, moved, b.faces);
      const a2 = coloredAttr(rhino, Ldisp.index, r?.falling ? '#d62728' : roleHex[role], b.id);
      a2.setUserString('rbla.amplitude', String(s));
      doc.objects().add(m2, a2);
    }
  }
  const counts = Object.fromEntries(STATE_ORDER.map((k) => [k, 0]));
  for (const iface of result.interfaces || []) {
    const st = STATE_ORDER.includes(iface.state) ? iface.state : 'closed';
    counts[st]++;
    const poly = interfacePolygon(iface);
    const attr = coloredAttr(rhino, Lstate[st].index, STATE_COLORS[st], iface.id);
    attr.setUserString('rbla.state', st);
    attr.setUserString('rbla.blocks', iface.blocks.join(' | '));
    if (iface.resultant) attr.setUserString('rbla.normal_force', String(iface.resultant.normal_force));
    if (poly.length >= 3) {
      const mesh = new rhino.Mesh();
      poly.forEach((p, i) => { mesh.vertices().add(p[0], p[1], p[2]); });
      poly.forEach((p, i) => mesh.vertices().setPoint3dAt(i, p));
      for (const [a, b, c] of triangulatePolygon(poly)) mesh.faces().addTriFace(a, b, c);
      doc.objects().add(mesh, attr);
    } else if (poly.length === 2) {
      doc.objects().addLine(poly[0], poly[1], attr);
    }
  }
  // text dots: headline value, and the state of every cracked interface
  const h = headline(result);
  const top = [xmid / Math.max(n, 1), ymid / Math.max(n, 1), zmax];
  const dotText = h.kind ? h.text : `${result.status}`;
  const dot1 = new rhino.TextDot(dotText, top);
  dot1.secondaryText = result.verdict || '';
  doc.objects().add(dot1, coloredAttr(rhino, Llab.index, '#000000', 'rbla headline'));
  for (const iface of result.interfaces || []) {
    if (!iface.cracked || !iface.points?.length) continue;
    const c = iface.points.reduce((a, p) => [a[0] + p.position[0] / iface.points.length, a[1] + p.position[1] / iface.points.length, a[2] + p.position[2] / iface.points.length], [0, 0, 0]);
    const d = new rhino.TextDot(iface.state || 'cracked', c);
    d.fontHeight = 10;
    doc.objects().add(d, coloredAttr(rhino, Llab.index, STATE_COLORS[iface.state] || '#000000', iface.id));
  }
  if (result.base_reaction?.moving_blocks) {
    for (const id of result.base_reaction.moving_blocks) {
      const c = centroids.get(id);
      if (c) doc.objects().add(new rhino.TextDot(`${h.text} (${id})`, c), coloredAttr(rhino, Llab.index, '#2ca02c', `reaction ${id}`));
    }
  }
  const strings = doc.strings();
  strings.set('rbla.verdict', result.verdict || '');
  strings.set('rbla.status', result.status || '');
  strings.set('rbla.amplitude', String(s));
  if (h.kind) strings.set(h.kind === 'alpha' ? 'rbla.load_multiplier' : 'rbla.base_reaction', String(h.value));
  return { doc, parentName, amplitude: s, counts };
}

export async function readFile3dm(bytes) {
  const rhino = await loadRhino();
  const doc = rhino.File3dm.fromByteArray(bytes);
  if (!doc) throw new ExchangeError('not a readable .3dm file');
  return doc;
}
