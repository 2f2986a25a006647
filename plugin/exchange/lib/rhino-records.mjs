// rhino3dm objects -> the plain document record that cad-reader.mjs reads (the same record the
// Rhino plugin's adapter builds from RhinoCommon objects; see plugin/rbla_cad/cad_reader.py).
// Only geometry is converted here; every attribute is read by the shared convention.
import { newellNormal, polyhedronMassProps, fmt, sub, dot, norm } from './rbla-geometry.mjs';

export class GeometryError extends Error {}

/** Rhino's name of a unit system value ("Meters", "None", ...). */
export function unitName(rhino, value) {
  for (const k of Object.keys(rhino.UnitSystem)) {
    if (k === 'values' || k === 'argCount') continue;
    if (rhino.UnitSystem[k] === value || rhino.UnitSystem[k]?.value === value?.value) return k;
  }
  return 'None';
}

const surfaceDomain = (srf, i) => { const d = srf.domain(i); return [d[0] ?? d.t0 ?? d.min, d[1] ?? d.t1 ?? d.max]; };

/** Largest distance of polygon corners (and a 3 x 3 grid of samples of a face's surface) from the corners' plane. */
function planeDeviation(pts, face = null) {
  const nrm = newellNormal(pts);
  const nl = norm(nrm);
  if (nl < 1e-300) return { n: null, dev: Infinity };
  const n = nrm.map((x) => x / nl);
  const c = pts.reduce((a, p) => [a[0] + p[0] / pts.length, a[1] + p[1] / pts.length, a[2] + p[2] / pts.length], [0, 0, 0]);
  const off = (p) => Math.abs(dot(sub(p, c), n));
  let dev = Math.max(...pts.map(off));
  if (!face) return { n, dev };
  try {
    const srf = face.underlyingSurface();
    const [u0, u1] = surfaceDomain(srf, 0), [v0, v1] = surfaceDomain(srf, 1);
    if ([u0, u1, v0, v1].every(Number.isFinite)) {
      for (const a of [0.25, 0.5, 0.75]) for (const b of [0.25, 0.5, 0.75]) {
        const p = srf.pointAt(u0 + a * (u1 - u0), v0 + b * (v1 - v0));
        if (p && p.length === 3) dev = Math.max(dev, off(p));
      }
    }
  } catch { /* surface sampling unavailable: corner planarity only */ }
  return { n, dev };
}

/** Outer loop of a planar Brep face as indices into the Brep's vertices, outward; throws GeometryError. */
function faceLoop(brep, fi, tol) {
  const face = brep.faces().get(fi);
  if (face.loops.count !== 1) throw new GeometryError(`face ${fi} has holes (inner trimming loops), which rbla faces cannot represent; split the face`);
  const loop = face.outerLoop();
  const edges = brep.edges();
  const idx = [];
  for (let t = 0; t < loop.trimCount; t++) {
    const trim = loop.trims.get(t);
    if (trim.edgeIndex < 0 || !edges.get(trim.edgeIndex).isLinear()) throw new GeometryError(`is a curved Brep (face ${fi} has a curved edge); rhino3dm cannot mesh curved Breps: mesh it in Rhino (_Mesh) or model it with planar faces`);
    idx.push(trim.startVertexIndex);
  }
  const clean = idx.filter((v, k) => v !== idx[(k + idx.length - 1) % idx.length]);
  if (clean.length < 3) throw new GeometryError(`is a curved Brep (face ${fi} is bounded by fewer than 3 straight edges); rhino3dm cannot mesh curved Breps`);
  const verts = brep.vertices();
  const pts = clean.map((i) => verts.get(i).location);
  const { n, dev } = planeDeviation(pts, face);
  if (n === null) throw new GeometryError(`face ${fi} is degenerate`);
  if (dev > tol) throw new GeometryError(`is a curved Brep (face ${fi} is not planar, deviation ${fmt(dev)} > tolerance ${fmt(tol)}); rhino3dm cannot mesh curved Breps: mesh it in Rhino (_Mesh) or model it with planar faces`);
  // outer loops run counter-clockwise about the surface normal; a reversed face flips it
  try {
    const srf = face.underlyingSurface();
    const [u0, u1] = surfaceDomain(srf, 0), [v0, v1] = surfaceDomain(srf, 1);
    const sn = srf.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1));
    const faceN = face.orientationIsReversed ? sn.map((x) => -x) : sn;
    if (dot(faceN, n) < 0) return [...clean].reverse();
  } catch {
    if (face.orientationIsReversed) return [...clean].reverse();
  }
  return clean;
}

function compact(vertices, faces) {
  const used = [...new Set(faces.flat())].sort((a, b) => a - b);
  const remap = new Map(used.map((old, k) => [old, k]));
  return { vertices: used.map((i) => vertices[i]), faces: faces.map((f) => f.map((i) => remap.get(i))) };
}

function orientOutward(poly) {
  if (polyhedronMassProps(poly.vertices, poly.faces).volume < 0) poly.faces = poly.faces.map((f) => [...f].reverse());
  return poly;
}

function brepSolid(brep, tol) {
  const bv = brep.vertices();
  const vertices = [];
  for (let i = 0; i < bv.count; i++) vertices.push(bv.get(i).location);
  const faces = [];
  for (let fi = 0; fi < brep.faces().count; fi++) faces.push(faceLoop(brep, fi, tol));
  return orientOutward(compact(vertices, faces));
}

function brepPolygons(brep, tol) {
  const bv = brep.vertices();
  const polys = [];
  for (let fi = 0; fi < brep.faces().count; fi++) polys.push(faceLoop(brep, fi, tol).map((i) => bv.get(i).location));
  return polys;
}

function meshVertices(mesh) {
  const vl = mesh.vertices();
  const out = [];
  for (let i = 0; i < vl.count; i++) out.push(vl.point3dAt ? vl.point3dAt(i) : vl.get(i));
  return out;
}

/** A closed mesh as a polyhedron: coincident vertices welded (meshes duplicate them along creases). */
function meshSolid(mesh) {
  const raw = meshVertices(mesh);
  const weld = 1e-9;
  const keyToIdx = new Map();
  const map = [];
  const vertices = [];
  for (const p of raw) {
    const k = p.map((x) => Math.round(x / weld)).join(',');
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
  if (faces.length < 4) throw new GeometryError('the mesh has fewer than 4 faces');
  return orientOutward(compact(vertices, faces));
}

/** An open mesh's faces as polygons (a warped quad as its two triangles). */
function meshPolygons(mesh, tol) {
  const v = meshVertices(mesh);
  const fl = mesh.faces();
  const polys = [];
  for (let i = 0; i < fl.count; i++) {
    const f = fl.get(i);
    if (f[2] === f[3]) { polys.push([v[f[0]], v[f[1]], v[f[2]]]); continue; }
    const quad = [v[f[0]], v[f[1]], v[f[2]], v[f[3]]];
    if (planeDeviation(quad).dev <= tol) polys.push(quad);
    else polys.push([v[f[0]], v[f[1]], v[f[2]]], [v[f[0]], v[f[2]], v[f[3]]]);
  }
  return polys;
}

/** A closed planar polyline curve as one polygon; throws GeometryError. */
function curvePolygon(rhino, g, tol) {
  let pts = null;
  if (g instanceof rhino.PolylineCurve) { pts = []; for (let i = 0; i < g.pointCount; i++) pts.push(g.point(i)); } else if (typeof g.tryGetPolyline === 'function') {
    const pl = g.tryGetPolyline();
    if (pl && pl.count) { pts = []; for (let i = 0; i < pl.count; i++) pts.push(pl.get(i)); }
  }
  if (!pts || !g.isClosed) throw new GeometryError('a curve must be a closed polyline');
  if (pts.length > 1 && norm(sub(pts[0], pts.at(-1))) <= tol) pts.pop();
  if (pts.length < 3) throw new GeometryError('the polyline has fewer than 3 corners');
  if (planeDeviation(pts).dev > tol) throw new GeometryError('the polyline is not planar');
  return [pts];
}

/** The shape part of a record: solid, polygons, point or other (what cannot be converted as `error`). */
function shapeOf(rhino, g, tol) {
  const out = { type: g.constructor?.name || 'object' };
  let convert;
  if (g instanceof rhino.Brep || g instanceof rhino.Extrusion) {
    const brep = g instanceof rhino.Brep ? g : g.toBrep(true);
    out.shape = brep.isSolid ? 'solid' : 'polygons';
    convert = brep.isSolid ? () => brepSolid(brep, tol) : () => ({ polygons: brepPolygons(brep, tol) });
  } else if (g instanceof rhino.Mesh) {
    out.shape = g.isClosed ? 'solid' : 'polygons';
    convert = g.isClosed ? () => meshSolid(g) : () => ({ polygons: meshPolygons(g, tol) });
  } else if (g instanceof rhino.Point) {
    return { ...out, shape: 'point', point: [...g.location] };
  } else if (g instanceof rhino.Curve) {
    out.shape = 'polygons';
    convert = () => ({ polygons: curvePolygon(rhino, g, tol) });
  } else {
    return { ...out, shape: 'other' };
  }
  try {
    Object.assign(out, convert());
  } catch (e) {
    if (!(e instanceof GeometryError)) throw e;
    out.error = e.message;
  }
  return out;
}

function layerInfo(doc) {
  const byIndex = new Map();
  const byId = new Map();
  for (let i = 0; i < doc.layers().count; i++) {
    const l = doc.layers().get(i);
    byIndex.set(l.index, l);
    byId.set(l.id, l);
  }
  const visible = (l) => { for (let x = l, n = 0; x && n < 100; x = byId.get(x.parentLayerId), n++) if (x.visible === false) return false; return true; };
  return (index) => { const l = byIndex.get(index); return l ? { path: l.fullPath, visible: visible(l) } : { path: null, visible: true }; };
}

/** The document record of a File3dm (name: the file name, when known). */
export function documentRecord(rhino, doc, name = null) {
  const strings = doc.strings();
  const userText = {};
  for (let i = 0; i < strings.count; i++) {
    const kv = strings.get(i);
    if (Array.isArray(kv) && kv.length === 2) userText[kv[0]] = kv[1];
  }
  const tol = doc.settings().modelAbsoluteTolerance || 1e-3;
  const layer = layerInfo(doc);
  const objects = [];
  const objs = doc.objects();
  for (let i = 0; i < objs.count; i++) {
    const o = objs.get(i);
    const a = o.attributes();
    const l = layer(a.layerIndex);
    objects.push({
      guid: a.id, name: a.name || null, layer: l.path, hidden: a.mode === rhino.ObjectMode.Hidden || !l.visible,
      user_text: Object.fromEntries(a.getUserStrings()), ...shapeOf(rhino, o.geometry(), tol),
    });
  }
  return { name, units: unitName(rhino, doc.settings().modelUnitSystem), tolerance: tol, user_text: userText, objects };
}
