// A CAD document read into an rbla model by the attribute convention
// (plugin/rbla_cad/data/cad_attributes.json). The same steps, in the same order and with the same
// messages, as plugin/rbla_cad/cad_reader.py, which documents the document record this takes;
// tests/plugin/cad_cases run both readers on the same records and compare models and messages.
import { DATA, KEYS, TRUE, Report, Bad, readKeys, normalise, parseValue, q, fmt, whoObject } from './cad-attributes.mjs';
import { mergeCoplanar, planeTolerance, boundingBox, surfaceDistance, contains } from './cad-geometry.mjs';
import { polyhedronMassProps, norm } from './rbla-geometry.mjs';

const SEARCH_FACTOR = DATA.interface_search.factor;
const MERGE_RELATIVE = DATA.interface_merge.relative;
const DEFAULT_FRICTION = KEYS.document.get('rbla.default_friction').default;
const SCHEMA_VERSION = '1.0.0';

/** The model as plugin/rbla_cad/model.py's ModelBuilder writes it (the parts the reader uses). */
class Draft {
  constructor(length, scale, ds, title) {
    Object.assign(this, { length, scale, title });
    this.force = ds['rbla.force_unit'] ?? 'kN';
    this.unitWeightUnit = ds['rbla.unit_weight_unit'] ?? 'kN/m3';
    this.gravity = ds['rbla.gravity'] ?? '-z';
    this.defaultUnitWeight = ds['rbla.default_unit_weight'];
    this.defaultFriction = ds['rbla.default_friction'];
    this.blocks = [];
    this.blockFriction = new Map();
    this.interfaces = [];
    this.dead = [];
    this.live = [];
    this.analysis = {};
    this.detection = {};
  }

  p(v) { return this.scale !== 1 ? v.map((x) => x * this.scale) : v.map(Number); }

  addBlock(id, vertices, faces, { role, unitWeight, label, centroid, volume, friction }) {
    const verts = vertices.map((v) => this.p(v));
    const mp = polyhedronMassProps(verts, faces);
    if (!(mp.volume > 0)) throw new Error(`block ${q(id)} has ${mp.volume < 0 ? 'inward faces (negative volume)' : 'zero volume'}`);
    const b = { id };
    if (label) b.label = String(label).slice(0, 1000);
    Object.assign(b, { role, vertices: verts, faces: faces.map((f) => [...f]) });
    b.centroid = centroid ? this.p(centroid) : mp.centroid;
    b.volume = volume !== undefined && volume !== null ? volume * this.scale ** 3 : mp.volume;
    if (unitWeight !== undefined) b.unit_weight = unitWeight;
    if (friction !== undefined) this.blockFriction.set(id, friction);
    this.blocks.push(b);
  }

  addInterface(blocks, polygon, { id, label, friction }) {
    const itf = {};
    if (id !== undefined && id !== null) itf.id = String(id);
    if (label) itf.label = String(label).slice(0, 1000);
    itf.blocks = [String(blocks[0]), String(blocks[1])];
    itf.polygon = polygon.map((p) => this.p(p));
    if (friction !== undefined && friction !== null) itf.friction = friction;
    this.interfaces.push(itf);
  }

  addLoad(kind, block, force, point, moment) {
    const load = { block: String(block), force: force.map(Number), point: this.p(point) };
    if (moment) load.moment = moment.map((c) => c * this.scale);
    (kind === 'live' ? this.live : this.dead).push(load);
    if (kind === 'live') this.analysis.type = 'load_multiplier';
  }

  detects() {
    const mode = this.detection.mode || (this.interfaces.length ? 'merge' : 'auto');
    return mode === 'merge' || (mode === 'auto' && !this.interfaces.length);
  }

  /** [mu, base]: friction of the detected interfaces and the default (see ModelBuilder). */
  detectedFriction() {
    const base = this.defaultFriction ?? DEFAULT_FRICTION;
    if (!this.blockFriction.size || !this.detects()) return [base, base];
    return [Math.min(base, ...this.blockFriction.values()), base];
  }

  toModel() {
    const [mu, base] = this.detectedFriction();
    const doc = { schema_version: SCHEMA_VERSION };
    if (this.title) doc.title = this.title.slice(0, 1000);
    doc.units = { length: this.length, force: this.force, unit_weight: this.unitWeightUnit };
    doc.gravity = this.gravity;
    const defaults = {};
    if (this.defaultUnitWeight !== undefined) defaults.unit_weight = this.defaultUnitWeight;
    if (mu < base || this.defaultFriction !== undefined) defaults.friction = mu;
    if (Object.keys(defaults).length) doc.defaults = defaults;
    doc.blocks = this.blocks.map((b) => ({ ...b }));
    if (this.interfaces.length) doc.interfaces = this.interfaces.map((itf) => this.interfaceOut(itf, mu < base, base));
    const detection = { ...this.detection };
    if (this.interfaces.length && !('mode' in detection)) detection.mode = 'merge';
    if (Object.keys(detection).length) doc.detection = detection;
    const loads = {};
    if (this.dead.length) loads.dead = this.dead.map((x) => ({ ...x }));
    if (this.live.length) loads.live = this.live.map((x) => ({ ...x }));
    if (Object.keys(loads).length) doc.loads = loads;
    if (Object.keys(this.analysis).length) doc.analysis = JSON.parse(JSON.stringify(this.analysis));
    return doc;
  }

  interfaceOut(itf, lowered, base) {
    const out = { ...itf };
    if (!('friction' in out)) {
      const mus = (out.blocks || []).filter((b) => this.blockFriction.has(b)).map((b) => this.blockFriction.get(b));
      if (mus.length) out.friction = Math.min(...mus);
      else if (lowered) out.friction = base;
    }
    return out;
  }
}

// --- document level ---------------------------------------------------------------------------------

function units(name, rep) {
  const table = new Map(Object.entries(DATA.length_units).filter(([k]) => !k.startsWith('$')).map(([k, v]) => [k.toLowerCase(), v]));
  let key = String(name || 'None').trim();
  if (key.toLowerCase().startsWith('unitsystem.')) key = key.slice('unitsystem.'.length);
  if (!table.has(key.toLowerCase())) { rep.add('unsupported_units', null, null, { unit: q(key) }); return null; }
  const [length, scale] = table.get(key.toLowerCase());
  if (key.toLowerCase() === 'none') rep.add('units_assumed');
  else if (scale !== 1) rep.add('units_converted', null, null, { unit: q(key), scale: fmt(scale), length });
  return [length, scale];
}

function onResultLayer(layer) {
  const l = layer || '';
  const rl = DATA.result_layers;
  return rl.exact.some((x) => l === x || l.startsWith(`${x}::`)) || rl.prefix.some((x) => l.startsWith(x));
}

const who = (rec) => whoObject(rec.name, rec.guid);

function ignored(rec, keys, rep) {
  const text = keys['rbla.ignore'] || '';
  if (!text) return false;
  try { return parseValue(KEYS.block.get('rbla.ignore'), text); } catch (e) {
    if (!(e instanceof Bad)) throw e;
    rep.add(e.code, rec.guid ?? null, 'rbla.ignore', { who: who(rec), value: q(text) });
    return true;
  }
}

function classify(objects, rep) {
  const kinds = { block: [], interface: [], load: [] };
  const hidden = [];
  for (const rec of objects) {
    if (onResultLayer(rec.layer)) continue;
    const keys = normalise(rec.user_text);
    if (ignored(rec, keys, rep)) continue;
    if (rec.hidden) { hidden.push(rec.name ? q(rec.name) : rec.guid); continue; }
    const shape = rec.shape;
    if ('rbla.load' in keys || (Object.keys(keys).length && shape === 'point')) kinds.load.push(rec);
    else if ('rbla.interface' in keys) kinds.interface.push(rec);
    else if (shape === 'solid') kinds.block.push(rec);
    else if (Object.keys(keys).length) rep.add('not_a_solid', rec.guid ?? null, null, { who: who(rec), type: rec.type ?? shape });
    else if (shape === 'polygons') rep.add('not_a_block', rec.guid ?? null, null, { who: who(rec), type: rec.type ?? shape });
  }
  if (hidden.length) rep.add('hidden_skipped', null, null, { count: hidden.length, names: hidden.slice(0, 10).join(', ') + (hidden.length > 10 ? ', ...' : '') });
  return kinds;
}

// --- blocks -----------------------------------------------------------------------------------------

function blockIds(recs, attrs, rep) {
  const count = new Map();
  recs.forEach((rec, i) => { if (!('rbla.id' in attrs[i]) && rec.name) count.set(rec.name, (count.get(rec.name) || 0) + 1); });
  const warned = new Set();
  return recs.map((rec, i) => {
    const name = rec.name;
    if ('rbla.id' in attrs[i]) return attrs[i]['rbla.id'];
    if (name && count.get(name) === 1) return name;
    if (name && !warned.has(name)) {
      warned.add(name);
      rep.add('duplicate_name', rec.guid ?? null, null, { count: count.get(name), name: q(name) });
    }
    return rec.guid;
  });
}

function blocks(recs, draft, rep, blockObjects) {
  const attrs = recs.map((rec) => readKeys('block', rec.user_text, who(rec), rep, rec.guid ?? null));
  const ids = blockIds(recs, attrs, rep);
  const solids = new Map();
  const first = new Map();
  recs.forEach((rec, i) => {
    const a = attrs[i], bid = ids[i], w = who(rec);
    if (first.has(bid)) { rep.add('duplicate_id', rec.guid ?? null, 'rbla.id', { who: w, what: 'block', id: q(bid), other: first.get(bid) }); return; }
    first.set(bid, w);
    if (rec.error) { rep.add('block_geometry', rec.guid ?? null, null, { who: w, detail: rec.error }); return; }
    const label = a['rbla.label'] || (rec.name && rec.name !== bid ? rec.name : null) || rec.layer || null;
    const role = a['rbla.role'] ?? 'free';
    try {
      draft.addBlock(bid, rec.vertices, rec.faces, { role, unitWeight: a['rbla.unit_weight'], label, centroid: rec.centroid, volume: rec.volume, friction: a['rbla.friction'] });
    } catch (e) { rep.add('block_geometry', rec.guid ?? null, null, { who: w, detail: e.message }); return; }
    solids.set(bid, [rec.vertices, rec.faces, role, ...boundingBox(rec.vertices)]);
    blockObjects.set(bid, rec.guid);
  });
  return solids;
}

// --- interfaces ---------------------------------------------------------------------------------------

/** p within margin of the box (a cheap test before the exact ones). */
const inBox = (p, lo, hi, margin) => [0, 1, 2].every((c) => lo[c] - margin <= p[c] && p[c] <= hi[c] + margin);

const foundText = (ids) => (ids.length ? `${ids.length} blocks: ${ids.slice(0, 5).map(q).join(', ')}${ids.length > 5 ? ', ...' : ''}` : 'no block');

function interfacePair(rec, a, polys, solids, tol, rep) {
  if ('rbla.blocks' in a) {
    const missing = a['rbla.blocks'].filter((b) => !solids.has(b));
    for (const b of missing) rep.add('unknown_block', rec.guid ?? null, 'rbla.blocks', { who: who(rec), id: q(b) });
    return missing.length ? null : [...a['rbla.blocks']];
  }
  const near = planeTolerance(polys, SEARCH_FACTOR * tol, MERGE_RELATIVE);
  const corners = polys.flat();
  const found = [...solids.entries()].filter(([, [v, f, , lo, hi]]) => corners.every((p) => inBox(p, lo, hi, near)) && corners.every((p) => surfaceDistance(p, v, f) <= near)).map(([bid]) => bid);
  if (found.length !== 2) { rep.add('interface_blocks', rec.guid ?? null, null, { who: who(rec), found: foundText(found) }); return null; }
  return found;
}

/** The value of rbla.interface, or the object name when the value says only 'yes'. */
const interfaceLabel = (value, name) => (!value || TRUE.includes(value.trim().toLowerCase()) ? name || null : value);

function interfaceItems(recs, solids, tol, rep) {
  const items = [];
  for (const rec of recs) {
    const w = who(rec);
    const a = readKeys('interface', rec.user_text, w, rep, rec.guid ?? null);
    if (rec.shape !== 'polygons' || rec.error) {
      const detail = rec.error || `got ${rec.shape === 'solid' ? 'a closed solid' : (rec.type ?? '?')}`;
      rep.add('interface_geometry', rec.guid ?? null, null, { who: w, detail });
      continue;
    }
    const pair = interfacePair(rec, a, rec.polygons, solids, tol, rep);
    if (pair === null || !('rbla.interface' in a)) continue;
    items.push({ rec, who: w, pair, label: interfaceLabel(a['rbla.interface'], rec.name), friction: a['rbla.friction'] ?? null, id: a['rbla.id'] ?? null, polygons: rec.polygons });
  }
  return items;
}

function interfaces(recs, solids, draft, tol, rep) {
  const buckets = [];
  const index = new Map();
  interfaceItems(recs, solids, tol, rep).forEach((it, n) => {
    const key = JSON.stringify([[...it.pair].sort(), it.label, it.friction, it.id !== null ? n : null]);
    if (!index.has(key)) { index.set(key, buckets.length); buckets.push([]); }
    buckets[index.get(key)].push(it);
  });
  const ids = new Map();
  for (const bucket of buckets) {
    const pieces = [], owner = [];
    for (const it of bucket) for (const poly of it.polygons) { pieces.push(poly); owner.push(it); }
    const groups = mergeCoplanar(pieces, tol, MERGE_RELATIVE);
    const head = bucket[0];
    const obj = head.rec.guid ?? null;
    if (!groups.length) { rep.add('interface_geometry', obj, null, { who: head.who, detail: 'its pieces have no area' }); continue; }
    if (head.id !== null) {
      if (groups.length > 1) { rep.add('interface_split', obj, 'rbla.id', { who: head.who, count: groups.length }); continue; }
      if (ids.has(head.id)) { rep.add('duplicate_id', obj, 'rbla.id', { who: head.who, what: 'interface', id: q(head.id), other: ids.get(head.id) }); continue; }
      ids.set(head.id, head.who);
    }
    for (const g of groups) {
      const it = owner[g.pieces[0]];
      if (g.hull) rep.add('interface_hull', it.rec.guid ?? null, null, { who: it.who });
      draft.addInterface(it.pair, g.polygon, { id: it.id, label: it.label, friction: it.friction });
    }
  }
}

// --- loads --------------------------------------------------------------------------------------------

function loadBlock(rec, a, point, solids, tol, rep) {
  const obj = rec.guid ?? null;
  let bid;
  if ('rbla.block' in a) {
    bid = a['rbla.block'];
    if (!solids.has(bid)) { rep.add('unknown_block', obj, 'rbla.block', { who: who(rec), id: q(bid) }); return null; }
  } else {
    const found = [...solids.entries()].filter(([, [v, f, , lo, hi]]) => inBox(point, lo, hi, tol) && contains(point, v, f, tol)).map(([b]) => b);
    if (found.length !== 1) { rep.add('load_block', obj, null, { who: who(rec), found: foundText(found) }); return null; }
    bid = found[0];
  }
  if (solids.get(bid)[2] !== 'free') { rep.add('load_on_support', obj, null, { who: who(rec), id: q(bid) }); return null; }
  return bid;
}

function loads(recs, solids, draft, tol, rep) {
  let live = 0;
  for (const rec of recs) {
    const w = who(rec), obj = rec.guid ?? null;
    const a = readKeys('load', rec.user_text, w, rep, obj);
    if (rec.shape !== 'point') { rep.add('load_not_point', obj, null, { who: w, type: rec.type ?? rec.shape }); continue; }
    if (!('rbla.load' in a)) {
      if (!('rbla.load' in normalise(rec.user_text))) rep.add('load_no_kind', obj, null, { who: w });
      continue;
    }
    if (a['rbla.load'] === 'live') live += 1;
    if (!('rbla.force' in a) && !('rbla.moment' in a)) { rep.add('load_no_force', obj, null, { who: w }); continue; }
    const bid = loadBlock(rec, a, rec.point, solids, tol, rep);
    if (bid === null) continue;
    draft.addLoad(a['rbla.load'], bid, a['rbla.force'] ?? [0, 0, 0], rec.point, a['rbla.moment']);
  }
  return live;
}

function legacyJson(ds, draft) {
  const l = ds['rbla.loads'] || {};
  if (Array.isArray(l.dead)) draft.dead.push(...l.dead);
  const live = Array.isArray(l.live) ? l.live : [];
  draft.live.push(...live);
  draft.interfaces.push(...(ds['rbla.interfaces'] || []));
  return live.length;
}

// --- analysis -----------------------------------------------------------------------------------------

function excluded(ds, name, rep) {
  const bad = KEYS.document.get(name).json_excludes.filter((k) => k in ds);
  for (const k of bad) rep.add('conflict', null, name, { who: 'document', other: k });
  return bad.length > 0;
}

function seismicDirection(userText, ds, gravity, rep) {
  const axis = 'xyz'.indexOf(gravity[1]);
  let d = ds['rbla.seismic_direction'];
  if (d === undefined) d = axis === 0 ? [0, 1, 0] : KEYS.document.get('rbla.seismic_direction').default.map(Number);
  if (Math.abs(d[axis]) > 1e-9 * norm(d)) {
    const text = normalise(userText)['rbla.seismic_direction'] ?? '';
    rep.add('not_horizontal', null, 'rbla.seismic_direction', { who: 'document', gravity, value: q(text) });
    return null;
  }
  return d;
}

function setAnalysisOptions(draft, ds) {
  const a = draft.analysis;
  for (const [key, field] of [['rbla.friction_model', 'friction_model'], ['rbla.cone', 'cone'], ['rbla.pyramid_faces', 'pyramid_faces'], ['rbla.formulation', 'formulation'], ['rbla.time_limit', 'time_limit']]) {
    if (ds[key] !== undefined) a[field] = ds[key];
  }
}

function analysis(userText, ds, draft, live, rep) {
  const an = ds['rbla.analysis'];
  let kind;
  if (an !== null && typeof an === 'object') {
    if (!excluded(ds, 'rbla.analysis', rep)) draft.analysis = { ...an };
    kind = an.type === 'settlement' ? 'settlement' : (an.type ?? 'load_multiplier');
    if (live && kind === 'settlement') rep.add('live_loads_not_used', null, null, { count: live, analysis: kind });
  } else {
    kind = an ?? (live ? 'live' : 'seismic');
    const a = draft.analysis;
    if (kind === 'seismic') {
      const d = seismicDirection(userText, ds, draft.gravity, rep);
      if (d !== null) { a.type = 'load_multiplier'; a.seismic = { direction: d }; delete a.settlement; }
    } else if (kind === 'live') {
      a.type = 'load_multiplier'; delete a.settlement;
      if (!live) rep.add('no_live_loads');
    } else {
      a.type = 'settlement'; delete a.seismic;
      if (ds['rbla.settlement_direction'] !== undefined) a.settlement = { direction: ds['rbla.settlement_direction'] };
      else delete a.settlement;
    }
    if (live && kind !== 'live') rep.add('live_loads_not_used', null, null, { count: live, analysis: kind });
    setAnalysisOptions(draft, ds);
  }
  const roles = draft.blocks.map((b) => b.role);
  if (kind === 'settlement' && !roles.includes('moving_support')) rep.add('no_moving_support');
  const held = draft.blocks.filter((b) => b.role === 'moving_support').map((b) => b.id);
  if (held.length && kind !== 'settlement') rep.add('moving_support_held', null, null, { count: held.length, analysis: kind, ids: held.slice(0, 5).map(q).join(', ') + (held.length > 5 ? ', ...' : '') });
}

function detection(ds, draft, rep) {
  const det = ds['rbla.detection'];
  if (det !== null && typeof det === 'object') {
    if (!excluded(ds, 'rbla.detection', rep)) draft.detection = { ...det };
    return;
  }
  if (det !== undefined) draft.detection.mode = det;
  if (ds['rbla.distance_tolerance'] !== undefined) draft.detection.distance_tolerance = ds['rbla.distance_tolerance'] * draft.scale;
  if (ds['rbla.angle_tolerance'] !== undefined) draft.detection.angle_tolerance = ds['rbla.angle_tolerance'];
}

function modelChecks(draft, rep, anyBlockObject) {
  // only asked when nothing else is wrong (see cad_reader._model_checks)
  if (!anyBlockObject || !draft.blocks.length || rep.errors.length) return;
  const roles = draft.blocks.map((b) => b.role);
  if (!roles.includes('fixed') && !roles.includes('moving_support')) rep.add('no_support');
  if (!roles.includes('free')) rep.add('no_free_block');
}

function frictionWarning(draft, rep) {
  const [mu, base] = draft.detectedFriction();
  if (!draft.blockFriction.size || !draft.detects()) return;
  const why = mu < base ? `the smallest block value, below rbla.default_friction = ${fmt(base)}` : 'rbla.default_friction; no block value is smaller';
  const values = [...new Set(draft.blockFriction.values())].sort((x, y) => x - y).map(fmt).join(', ');
  rep.add('block_friction', null, null, { count: draft.blockFriction.size, mu: fmt(mu), why, values });
}

/**
 * Read a document record (see plugin/rbla_cad/cad_reader.py) into
 * { model (null when there is an error), report, blockObjects: Map(id -> guid), settings }.
 */
export function readDocument(doc, host = 'exchange') {
  const rep = new Report();
  const out = { model: null, report: rep, blockObjects: new Map(), settings: {} };
  const u = units(doc.units, rep);
  if (u === null) return out;
  const [length, scale] = u;
  const tol = Number(doc.tolerance || 0.001);
  const ds = readKeys('document', doc.user_text, 'document', rep, null, host);
  out.settings = ds;
  const draft = new Draft(length, scale, ds, ds['rbla.title'] || doc.name || '');
  const kinds = classify(doc.objects || [], rep);
  const solids = blocks(kinds.block, draft, rep, out.blockObjects);
  if (!kinds.block.length) rep.add('no_blocks');
  interfaces(kinds.interface, solids, draft, tol, rep);
  let live = loads(kinds.load, solids, draft, tol, rep);
  live += legacyJson(ds, draft);
  analysis(doc.user_text, ds, draft, live, rep);
  detection(ds, draft, rep);
  modelChecks(draft, rep, kinds.block.length > 0);
  frictionWarning(draft, rep);
  if (!rep.errors.length) out.model = draft.toModel();
  return out;
}
