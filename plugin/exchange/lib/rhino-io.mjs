// rbla <-> Rhino .3dm exchange on top of rhino3dm (openNURBS compiled to WebAssembly).
// No Rhino installation is needed.
import rhino3dm from 'rhino3dm';
import {
  STATE_COLORS, STATE_ORDER, hexToRgb, triangulatePolygon, polyhedronMassProps,
  rigidMotion, resultBlockMap, headline, norm, interfacePolygon,
} from './rbla-geometry.mjs';
import { documentRecord } from './rhino-records.mjs';
import { readDocument } from './cad-reader.mjs';
import { ALIASES } from './cad-attributes.mjs';

let rhinoPromise = null;
export function loadRhino() {
  if (!rhinoPromise) rhinoPromise = rhino3dm();
  return rhinoPromise;
}

export class ExchangeError extends Error {}

const RBLA_TO_RHINO = { mm: 'Millimeters', cm: 'Centimeters', m: 'Meters' };

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

const num = (x) => String(x);
const vec = (v) => v.map(num).join(', ');
const pairText = (ids) => ids.join(ids.some((b) => b.includes(',')) ? '; ' : ', ');

/** Analysis settings as convention keys, or null when the model's analysis needs the JSON form. */
function analysisKeys(a, hasLive) {
  const plain = ['type', 'seismic', 'settlement', 'friction_model', 'cone', 'pyramid_faces', 'formulation', 'time_limit'];
  if (Object.keys(a).some((k) => !plain.includes(k))) return null;
  const out = {};
  if (a.type === 'settlement') {
    out['rbla.analysis'] = 'settlement';
    if (a.settlement?.direction) out['rbla.settlement_direction'] = vec(a.settlement.direction);
  } else if (a.seismic) {
    out['rbla.analysis'] = 'seismic';
    out['rbla.seismic_direction'] = vec(a.seismic.direction);
  } else if (hasLive) {
    out['rbla.analysis'] = 'live';
  } else return null;
  for (const k of plain.slice(3)) if (a[k] !== undefined) out[`rbla.${k}`] = num(a[k]);
  return out;
}

/** Detection settings as convention keys (or the JSON form for settings without a key). */
function detectionKeys(d, hasInterfaces) {
  const out = {};
  const det = { ...(d || {}) };
  if (hasInterfaces && !det.mode) det.mode = 'auto'; // the model's default; the reader's would be merge
  if (Object.keys(det).some((k) => !['mode', 'distance_tolerance', 'angle_tolerance'].includes(k))) return { 'rbla.detection': JSON.stringify(det) };
  if (det.mode) out['rbla.detection'] = det.mode;
  if (det.distance_tolerance !== undefined) out['rbla.distance_tolerance'] = num(det.distance_tolerance);
  if (det.angle_tolerance !== undefined) out['rbla.angle_tolerance'] = num(det.angle_tolerance);
  return out;
}

/** The Document User Text that says what the model says (the CAD attribute convention). */
export function documentUserText(model) {
  const out = {};
  if (model.title) out['rbla.title'] = model.title;
  if (model.units?.force) out['rbla.force_unit'] = model.units.force;
  if (model.units?.unit_weight) out['rbla.unit_weight_unit'] = model.units.unit_weight;
  if (model.gravity) out['rbla.gravity'] = model.gravity;
  if (model.defaults?.unit_weight !== undefined) out['rbla.default_unit_weight'] = num(model.defaults.unit_weight);
  if (model.defaults?.friction !== undefined) out['rbla.default_friction'] = num(model.defaults.friction);
  if (model.analysis) {
    const keys = analysisKeys(model.analysis, (model.loads?.live || []).length > 0);
    Object.assign(out, keys ?? { 'rbla.analysis': JSON.stringify(model.analysis) });
  }
  Object.assign(out, detectionKeys(model.detection, (model.interfaces || []).length > 0));
  return out;
}

function addLayers(rhino, doc, spec) {
  const out = {};
  for (const [key, name, hex] of spec) {
    const layer = new rhino.Layer();
    layer.name = name;
    layer.color = colorObj(hex);
    out[key] = doc.layers().add(layer);
  }
  return out;
}

function userAttr(rhino, layerIndex, name, keys) {
  const attr = new rhino.ObjectAttributes();
  if (name) attr.name = name;
  attr.layerIndex = layerIndex;
  for (const [k, v] of Object.entries(keys)) attr.setUserString(k, v);
  return attr;
}

function addInterfaceObjects(rhino, doc, model, layer) {
  for (const itf of model.interfaces || []) {
    const keys = { 'rbla.interface': itf.label || '', 'rbla.blocks': pairText(itf.blocks) };
    if (itf.id !== undefined) keys['rbla.id'] = itf.id;
    if (itf.friction !== undefined) keys['rbla.friction'] = num(itf.friction);
    const crv = new rhino.PolylineCurve([...itf.polygon, itf.polygon[0]]);
    doc.objects().add(crv, userAttr(rhino, layer, null, keys));
  }
}

function addLoadPoints(rhino, doc, model, layer) {
  const byId = new Map(model.blocks.map((b) => [b.id, b]));
  for (const kind of ['dead', 'live']) {
    for (const load of model.loads?.[kind] || []) {
      const b = byId.get(load.block);
      const point = load.point || (b ? polyhedronMassProps(b.vertices, b.faces).centroid : [0, 0, 0]);
      const keys = { 'rbla.load': kind, 'rbla.block': load.block, 'rbla.force': vec(load.force || [0, 0, 0]) };
      if (load.moment) keys['rbla.moment'] = vec(load.moment);
      doc.objects().add(new rhino.Point(point), userAttr(rhino, layer, null, keys));
    }
  }
}

/**
 * Build a File3dm from a model JSON by the CAD attribute convention: blocks become closed Breps
 * (planar faces; default) or closed meshes (`as: 'mesh'`) named by block id with User Text
 * rbla.role / rbla.unit_weight / rbla.label; given interfaces become closed polylines with
 * rbla.interface; loads become points with rbla.load; model-wide settings go to the Document
 * User Text (documentUserText). Reading the file back gives the same model.
 */
export async function modelTo3dm(model, { as = 'brep' } = {}) {
  const rhino = await loadRhino();
  const doc = new rhino.File3dm();
  const len = model.units?.length || 'm';
  doc.settings().modelUnitSystem = rhino.UnitSystem[RBLA_TO_RHINO[len]];
  doc.settings().modelAbsoluteTolerance = { m: 1e-4, cm: 1e-2, mm: 0.1 }[len];
  for (const [k, v] of Object.entries(documentUserText(model))) doc.strings().set(k, v);
  const layer = addLayers(rhino, doc, [['free', 'rbla free', '#c8b496'], ['fixed', 'rbla fixed', '#505050'],
    ['moving_support', 'rbla moving_support', '#2ca02c'], ['interface', 'rbla interfaces', '#1f77b4'], ['load', 'rbla loads', '#d62728']]);
  for (const b of model.blocks) {
    const role = b.role || 'free';
    const keys = { 'rbla.role': role };
    if (b.unit_weight !== undefined) keys['rbla.unit_weight'] = num(b.unit_weight);
    if (b.label !== undefined) keys['rbla.label'] = b.label;
    const attr = userAttr(rhino, layer[role], b.id, keys);
    const mesh = meshFromPolyhedron(rhino, b.vertices, b.faces);
    if (as === 'mesh') {
      doc.objects().add(mesh, attr);
    } else {
      const brep = rhino.Brep.createFromMesh(mesh, true);
      if (!brep) throw new ExchangeError(`block ${b.id}: could not build a Brep`);
      doc.objects().add(brep, attr);
    }
  }
  addInterfaceObjects(rhino, doc, model, layer.interface);
  addLoadPoints(rhino, doc, model, layer.load);
  return doc;
}

/**
 * Read a File3dm into a model JSON by the CAD attribute convention (cad-reader.mjs). Options
 * override Document User Text: unitWeight (rbla.default_unit_weight), friction
 * (rbla.default_friction), title (rbla.title); name: the file name (the default title).
 * Returns { model (null when there are errors), messages, errors, warnings } (messages:
 * {code, severity, text, object, key}).
 */
export async function file3dmToModel(doc, opts = {}) {
  const rhino = await loadRhino();
  const record = documentRecord(rhino, doc, opts.name ?? null);
  const override = (key, value) => {
    if (value === undefined) return;
    for (const k of Object.keys(record.user_text)) {
      const low = k.trim().toLowerCase();
      if (low === key || ALIASES.document.get(low) === key) delete record.user_text[k];
    }
    record.user_text[key] = String(value);
  };
  override('rbla.default_unit_weight', opts.unitWeight);
  override('rbla.default_friction', opts.friction);
  override('rbla.title', opts.title);
  const { model, report } = readDocument(record, 'exchange');
  return { model, messages: report.messages, errors: report.errors, warnings: report.warnings };
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
      a2.setUserString('rbla.block', b.id);
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
    attr.setUserString('rbla.blocks', pairText(iface.blocks));
    if (iface.label) attr.setUserString('rbla.interface', iface.label);
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
