// Pure geometry helpers shared by the .3dm exchange scripts and the browser viewer.
// No dependencies: this file is bundled into plugin/viewer/dist/viewer.js as well.

export const STATE_COLORS = {
  closed: '#9e9e9e',
  opening: '#d62728',
  sliding: '#1f77b4',
  opening_sliding: '#9467bd',
  hinge: '#ff7f0e',
};
export const STATE_ORDER = ['closed', 'opening', 'sliding', 'opening_sliding', 'hinge'];

export const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
export const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
export const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
export const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
export const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
export const norm = (a) => Math.sqrt(dot(a, a));

export function hexToRgb(hex) {
  const v = parseInt(hex.replace('#', ''), 16);
  return { r: (v >> 16) & 255, g: (v >> 8) & 255, b: v & 255 };
}

/** Newell normal (not normalised; length = 2 x area) of a polygon given as points. */
export function newellNormal(pts) {
  const n = [0, 0, 0];
  for (let i = 0; i < pts.length; i++) {
    const p = pts[i];
    const q = pts[(i + 1) % pts.length];
    n[0] += (p[1] - q[1]) * (p[2] + q[2]);
    n[1] += (p[2] - q[2]) * (p[0] + q[0]);
    n[2] += (p[0] - q[0]) * (p[1] + q[1]);
  }
  return n;
}

/**
 * Triangulate a planar (possibly non-convex) polygon by ear clipping.
 * Returns triangles as index triples into `pts`, with the polygon's orientation.
 */
export function triangulatePolygon(pts) {
  const n = pts.length;
  if (n < 3) return [];
  if (n === 3) return [[0, 1, 2]];
  const nrm = newellNormal(pts);
  const ax = Math.abs(nrm[0]), ay = Math.abs(nrm[1]), az = Math.abs(nrm[2]);
  // project onto the coordinate plane most perpendicular to the normal
  let i0 = 0, i1 = 1, sgn = nrm[2];
  if (ax >= ay && ax >= az) { i0 = 1; i1 = 2; sgn = nrm[0]; } else if (ay >= az) { i0 = 2; i1 = 0; sgn = nrm[1]; }
  const P = pts.map((p) => [p[i0], p[i1]]);
  const orient = sgn >= 0 ? 1 : -1;
  const area2 = (a, b, c) => ((P[b][0] - P[a][0]) * (P[c][1] - P[a][1]) - (P[b][1] - P[a][1]) * (P[c][0] - P[a][0])) * orient;
  const inside = (p, a, b, c) => {
    const eps = -1e-14;
    const d1 = ((P[b][0] - P[a][0]) * (P[p][1] - P[a][1]) - (P[b][1] - P[a][1]) * (P[p][0] - P[a][0])) * orient;
    const d2 = ((P[c][0] - P[b][0]) * (P[p][1] - P[b][1]) - (P[c][1] - P[b][1]) * (P[p][0] - P[b][0])) * orient;
    const d3 = ((P[a][0] - P[c][0]) * (P[p][1] - P[c][1]) - (P[a][1] - P[c][1]) * (P[p][0] - P[c][0])) * orient;
    return d1 > eps && d2 > eps && d3 > eps;
  };
  const idx = [...Array(n).keys()];
  const tris = [];
  let guard = 0;
  while (idx.length > 3 && guard++ < 10 * n * n) {
    let clipped = false;
    for (let k = 0; k < idx.length; k++) {
      const a = idx[(k + idx.length - 1) % idx.length], b = idx[k], c = idx[(k + 1) % idx.length];
      if (area2(a, b, c) <= 0) continue;
      let ok = true;
      for (const p of idx) {
        if (p === a || p === b || p === c) continue;
        if (inside(p, a, b, c)) { ok = false; break; }
      }
      if (!ok) continue;
      tris.push([a, b, c]);
      idx.splice(k, 1);
      clipped = true;
      break;
    }
    if (!clipped) break; // degenerate polygon: fall back to a fan below
  }
  if (idx.length === 3) tris.push([idx[0], idx[1], idx[2]]);
  else for (let k = 1; k + 1 < idx.length; k++) tris.push([idx[0], idx[k], idx[k + 1]]);
  return tris;
}

/** Volume and centroid of a closed polyhedron (faces counter-clockwise seen from outside). Each face
 *  is fanned from the mean of its corners, as the solver's geometry::mass_properties and the Python
 *  core do: a warped face then gives the same surface whichever corner its list starts at. */
export function polyhedronMassProps(vertices, faces) {
  // reference point: vertex average (reduces round-off)
  const ref = [0, 0, 0];
  for (const v of vertices) { ref[0] += v[0]; ref[1] += v[1]; ref[2] += v[2]; }
  ref[0] /= vertices.length; ref[1] /= vertices.length; ref[2] /= vertices.length;
  let vol = 0;
  const c = [0, 0, 0];
  for (const f of faces) {
    const pts = f.map((i) => sub(vertices[i], ref));
    const A = [0, 1, 2].map((k) => pts.reduce((s, p) => s + p[k], 0) / pts.length);
    for (let i = 0; i < pts.length; i++) {
      const B = pts[i], D = pts[(i + 1) % pts.length];
      const v6 = dot(A, cross(B, D));
      vol += v6;
      c[0] += v6 * (A[0] + B[0] + D[0]);
      c[1] += v6 * (A[1] + B[1] + D[1]);
      c[2] += v6 * (A[2] + B[2] + D[2]);
    }
  }
  const volume = vol / 6;
  const centroid = vol !== 0 ? [ref[0] + c[0] / (4 * vol), ref[1] + c[1] / (4 * vol), ref[2] + c[2] / (4 * vol)] : ref;
  return { volume, centroid };
}

/** Rotation matrix (row-major 3x3) of the axis-angle vector w (Rodrigues). */
export function rotationMatrix(w) {
  const th = norm(w);
  if (th < 1e-300) return [[1, 0, 0], [0, 1, 0], [0, 0, 1]];
  const k = scale(w, 1 / th);
  const c = Math.cos(th), s = Math.sin(th), t = 1 - c;
  const [x, y, z] = k;
  return [
    [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
    [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
    [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
  ];
}

export function matVec(R, v) {
  return [
    R[0][0] * v[0] + R[0][1] * v[1] + R[0][2] * v[2],
    R[1][0] * v[0] + R[1][1] * v[1] + R[1][2] * v[2],
    R[2][0] * v[0] + R[2][1] * v[1] + R[2][2] * v[2],
  ];
}

/**
 * Exact rigid motion of a block at amplitude s: p -> g + R(s theta)(p - g) + s u,
 * with g the block centroid, u the centroid translation and theta the rotation vector.
 * Returns a function mapping a point.
 */
export function rigidMotion(g, u, theta, s) {
  const R = rotationMatrix(scale(theta || [0, 0, 0], s));
  const t = scale(u || [0, 0, 0], s);
  return (p) => add(add(g, matVec(R, sub(p, g))), t);
}

/** Index the result's blocks by id. */
export function resultBlockMap(result) {
  const m = new Map();
  for (const b of result.blocks || []) m.set(b.id, b);
  return m;
}

/** The headline number of a result: { kind: 'alpha'|'reaction'|null, value, text }. */
export function headline(result) {
  const f = result.units?.force || 'kN';
  if (typeof result.load_multiplier === 'number') {
    return { kind: 'alpha', value: result.load_multiplier, text: `\u03b1 = ${fmt(result.load_multiplier)}` };
  }
  if (result.base_reaction && typeof result.base_reaction.at_collapse === 'number') {
    return { kind: 'reaction', value: result.base_reaction.at_collapse, text: `R = ${fmt(result.base_reaction.at_collapse)} ${f}` };
  }
  return { kind: null, value: null, text: result.status || 'no result' };
}

export function fmt(x) {
  if (!Number.isFinite(x)) return String(x);
  const a = Math.abs(x);
  if (a !== 0 && (a < 1e-3 || a >= 1e6)) return x.toExponential(4);
  return Number(x.toPrecision(6)).toString();
}

/** Polygon of a result interface (its contact points in order). Two-point (planar) interfaces give a segment. */
export function interfacePolygon(iface) {
  return (iface.points || []).map((p) => p.position);
}
