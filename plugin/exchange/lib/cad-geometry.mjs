// Planar pieces of interface objects and points near blocks: the same steps, in the same order, as
// plugin/rbla_cad/polygons.py (see there for the method), so that both readers give the same
// interface polygons to the last bits. tests/plugin/cad_cases run both and compare.
import { sub, dot, cross, norm, newellNormal } from './rbla-geometry.mjs';

/** [unit normal, area] of a polygon by Newell's method; [[0, 0, 0], 0] when degenerate. */
export function unitNormal(points) {
  const n = newellNormal(points).map((x) => 0.5 * x);
  const a = norm(n);
  if (a === 0) return [[0, 0, 0], 0];
  return [[n[0] / a, n[1] / a, n[2] / a], a];
}

function mean(points) {
  const k = points.length;
  let x = 0, y = 0, z = 0;
  for (const p of points) x += p[0];
  for (const p of points) y += p[1];
  for (const p of points) z += p[2];
  return [x / k, y / k, z / k];
}

/** Two unit vectors u, v with (u, v, n) right-handed; the same choice as polygons.plane_basis. */
export function planeBasis(n) {
  const e = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
  const d = dot(e, n);
  let u = [e[0] - d * n[0], e[1] - d * n[1], e[2] - d * n[2]];
  const lu = norm(u);
  u = [u[0] / lu, u[1] / lu, u[2] / lu];
  return [u, cross(n, u)];
}

function clusterPlanes(pieces, tol) {
  const planes = [];
  pieces.forEach((pts, i) => {
    const [n, area] = unitNormal(pts);
    if (area === 0) return;
    for (const plane of planes) {
      const [pn, po, members] = plane;
      if (pts.every((p) => Math.abs(dot(sub(p, po), pn)) <= tol)) {
        members.push([i, dot(n, pn) >= 0 ? [...pts] : [...pts].reverse()]);
        return;
      }
    }
    planes.push([n, mean(pts), [[i, [...pts]]]]);
  });
  return planes.map((p) => p[2]);
}

/** [unit normal, origin]: the area-weighted normal and the mean corner of the pieces. */
function fittedPlane(members) {
  const s = [0, 0, 0];
  const corners = [];
  for (const [, pts] of members) {
    const a = newellNormal(pts).map((x) => 0.5 * x);
    for (let c = 0; c < 3; c++) s[c] += a[c];
    corners.push(...pts);
  }
  const ln = norm(s);
  return [[s[0] / ln, s[1] / ln, s[2] / ln], mean(corners)];
}

/** [low corner, high corner] of the points' axis-aligned bounding box. */
export function boundingBox(points) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (const p of points) for (let c = 0; c < 3; c++) { lo[c] = Math.min(lo[c], p[c]); hi[c] = Math.max(hi[c], p[c]); }
  return [lo, hi];
}

/** max(tol, relative x the diagonal of the pieces' bounding box). */
export function planeTolerance(pieces, tol, relative) {
  const [lo, hi] = boundingBox(pieces.flat());
  return Math.max(tol, relative * norm(sub(hi, lo)));
}

function snap(members, origin, u, v, tol) {
  const pts2 = [];
  const loops = [];
  for (const [, pts] of members) {
    const loop = [];
    for (const p of pts) {
      const d = sub(p, origin);
      const q = [dot(d, u), dot(d, v)];
      let k = -1;
      for (let j = 0; j < pts2.length; j++) {
        const dx = q[0] - pts2[j][0], dy = q[1] - pts2[j][1];
        if (Math.sqrt(dx * dx + dy * dy) <= tol) { k = j; break; }
      }
      if (k < 0) { k = pts2.length; pts2.push(q); }
      if (!loop.length || loop.at(-1) !== k) loop.push(k);
    }
    while (loop.length > 1 && loop[0] === loop.at(-1)) loop.pop();
    loops.push(loop);
  }
  return [pts2, loops];
}

function segmentParam(p, a, b) {
  const dx = b[0] - a[0], dy = b[1] - a[1];
  const ll = dx * dx + dy * dy;
  let t = ll > 0 ? ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / ll : 0;
  t = Math.min(1, Math.max(0, t));
  const ex = p[0] - (a[0] + t * dx), ey = p[1] - (a[1] + t * dy);
  return [t, Math.sqrt(ex * ex + ey * ey)];
}

function splitTJunctions(pts2, loops, tol) {
  return loops.map((loop) => {
    const out = [];
    const m = loop.length;
    for (let j = 0; j < m; j++) {
      const a = loop[j], b = loop[(j + 1) % m];
      out.push(a);
      const inner = [];
      pts2.forEach((p, k) => {
        if (k === a || k === b) return;
        const [t, dist] = segmentParam(p, pts2[a], pts2[b]);
        if (t > 0 && t < 1 && dist <= tol) inner.push([t, k]);
      });
      inner.sort((x, y) => x[0] - y[0] || x[1] - y[1]);
      for (const [, k] of inner) out.push(k);
    }
    return out;
  });
}

function area2(pts2, loop) {
  let s = 0;
  const m = loop.length;
  for (let j = 0; j < m; j++) {
    const a = pts2[loop[j]], b = pts2[loop[(j + 1) % m]];
    s += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * s;
}

function inside2(p, pts2, loop, tol) {
  const m = loop.length;
  let inside = false;
  for (let j = 0; j < m; j++) {
    const a = pts2[loop[j]], b = pts2[loop[(j + 1) % m]];
    if (segmentParam(p, a, b)[1] <= tol) return false;
    if ((a[1] > p[1]) !== (b[1] > p[1])) {
      const x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
      if (p[0] < x) inside = !inside;
    }
  }
  return inside;
}

const cross2 = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);

function edgesCross(pts2, la, lb) {
  for (let j = 0; j < la.length; j++) {
    const ja = la[j], jb = la[(j + 1) % la.length];
    const a = pts2[ja], b = pts2[jb];
    for (let k = 0; k < lb.length; k++) {
      const ka = lb[k], kb = lb[(k + 1) % lb.length];
      if (new Set([ja, jb, ka, kb]).size < 4) continue;
      const c = pts2[ka], d = pts2[kb];
      const d1 = cross2(a, b, c), d2 = cross2(a, b, d), d3 = cross2(c, d, a), d4 = cross2(c, d, b);
      if (((d1 > 0) !== (d2 > 0)) && ((d3 > 0) !== (d4 > 0)) && d1 !== 0 && d2 !== 0 && d3 !== 0 && d4 !== 0) return true;
    }
  }
  return false;
}

function overlap(pts2, la, lb, tol) {
  if (la.some((k) => !lb.includes(k) && inside2(pts2[k], pts2, lb, tol))) return true;
  if (lb.some((k) => !la.includes(k) && inside2(pts2[k], pts2, la, tol))) return true;
  return edgesCross(pts2, la, lb);
}

function components(pts2, loops, tol) {
  const n = loops.length;
  const parent = [...Array(n).keys()];
  const find = (i) => { while (parent[i] !== i) { parent[i] = parent[parent[i]]; i = parent[i]; } return i; };
  const join = (i, j) => { const a = find(i), b = find(j); if (a !== b) parent[Math.max(a, b)] = Math.min(a, b); };
  const seen = new Map();
  const over = new Set();
  loops.forEach((loop, i) => {
    const m = loop.length;
    for (let j = 0; j < m; j++) {
      const e = [loop[j], loop[(j + 1) % m]];
      const key = `${Math.min(...e)},${Math.max(...e)}`;
      for (const [i2, e2] of seen.get(key) || []) {
        join(i, i2);
        if (e2[0] === e[0] && e2[1] === e[1]) over.add(i);
      }
      if (!seen.has(key)) seen.set(key, []);
      seen.get(key).push([i, e]);
    }
  });
  for (let i = 0; i < n; i++) {
    for (let k = i + 1; k < n; k++) {
      if (find(i) !== find(k) && overlap(pts2, loops[i], loops[k], tol)) { join(i, k); over.add(i); }
    }
  }
  const groups = new Map();
  for (let i = 0; i < n; i++) {
    const r = find(i);
    if (!groups.has(r)) groups.set(r, []);
    groups.get(r).push(i);
  }
  return [...groups.keys()].sort((a, b) => a - b).map((r) => [groups.get(r), groups.get(r).some((i) => over.has(i))]);
}

function trace(loops, members) {
  const net = new Map();
  for (const i of members) {
    const loop = loops[i];
    const m = loop.length;
    for (let j = 0; j < m; j++) {
      const a = loop[j], b = loop[(j + 1) % m];
      const key = `${Math.min(a, b)},${Math.max(a, b)}`;
      if (!net.has(key)) net.set(key, [Math.min(a, b), Math.max(a, b), 0]);
      net.get(key)[2] += a < b ? 1 : -1;
    }
  }
  const nxt = new Map();
  let first = null;
  for (const [lo, hi, c] of net.values()) {
    if (c === 0) continue;
    if (Math.abs(c) > 1) return null;
    const [a, b] = c > 0 ? [lo, hi] : [hi, lo];
    if (nxt.has(a)) return null;
    nxt.set(a, b);
    if (first === null) first = a;
  }
  if (first === null) return null;
  const loop = [first];
  for (;;) {
    const b = nxt.get(loop.at(-1));
    if (b === undefined) return null;
    if (b === first) break;
    if (loop.length > nxt.size) return null;
    loop.push(b);
  }
  return loop.length === nxt.size ? loop : null;
}

function dropCollinear(pts2, loop, tol) {
  let changed = true;
  while (changed && loop.length > 3) {
    changed = false;
    const m = loop.length;
    for (let j = 0; j < m; j++) {
      const a = pts2[loop[(j - 1 + m) % m]], b = pts2[loop[j]], c = pts2[loop[(j + 1) % m]];
      if (segmentParam(b, a, c)[1] <= tol) { loop.splice(j, 1); changed = true; break; }
    }
  }
  return loop;
}

function hull(pts2, members, loops) {
  const idx = [...new Set(members.flatMap((i) => loops[i]))].sort((a, b) => pts2[a][0] - pts2[b][0] || pts2[a][1] - pts2[b][1]);
  if (idx.length < 3) return idx;
  const half = (seq) => {
    const h = [];
    for (const k of seq) {
      while (h.length >= 2 && cross2(pts2[h.at(-2)], pts2[h.at(-1)], pts2[k]) <= 0) h.pop();
      h.push(k);
    }
    return h;
  };
  const lower = half(idx), upper = half([...idx].reverse());
  return [...lower.slice(0, -1), ...upper.slice(0, -1)];
}

/**
 * Merge planar pieces (arrays of 3-D points) into interfaces: [{polygon, pieces, hull}], one per
 * group of coplanar pieces that share an edge or overlap (see polygons.merge_coplanar; relative:
 * the plane tolerance relative to the pieces' size).
 */
export function mergeCoplanar(pieces, tol, relative = 0) {
  const out = [];
  if (!pieces.length) return out;
  const ptol = planeTolerance(pieces, tol, relative);
  for (const allMembers of clusterPlanes(pieces, ptol)) {
    const [n, origin] = fittedPlane(allMembers);
    const [u, v] = planeBasis(n);
    const [pts2, rawLoops] = snap(allMembers, origin, u, v, tol);
    const keep = rawLoops.map((loop, j) => j).filter((j) => rawLoops[j].length >= 3 && Math.abs(area2(pts2, rawLoops[j])) > tol * tol);
    const members = keep.map((j) => allMembers[j]);
    const loops = splitTJunctions(pts2, keep.map((j) => rawLoops[j]), tol);
    for (const [group, over] of components(pts2, loops, tol)) {
      let loop = over ? null : trace(loops, group);
      if (loop !== null) {
        let total = 0;
        for (const i of group) total += Math.abs(area2(pts2, loops[i]));
        if (Math.abs(Math.abs(area2(pts2, loop)) - total) > 1e-9 * total + tol * tol) loop = null;
      }
      const isHull = loop === null;
      loop = isHull ? hull(pts2, group, loops) : dropCollinear(pts2, loop, ptol);
      const polygon = loop.map((k) => [0, 1, 2].map((c) => origin[c] + pts2[k][0] * u[c] + pts2[k][1] * v[c]));
      out.push({ polygon, pieces: group.map((i) => members[i][0]), hull: isHull });
    }
  }
  return out;
}

// --- points and block surfaces ----------------------------------------------------------------------

/** Distance from a 3-D point to a planar polygon (any simple polygon). */
export function pointPolygonDistance(p, polygon) {
  const [n, area] = unitNormal(polygon);
  if (area === 0) return Math.min(...polygon.map((q) => norm(sub(p, q))));
  const o = polygon[0];
  const [u, v] = planeBasis(n);
  const h = dot(sub(p, o), n);
  const pts2 = polygon.map((q) => [dot(sub(q, o), u), dot(sub(q, o), v)]);
  const d = sub(p, o);
  const q = [dot(d, u), dot(d, v)];
  const loop = pts2.map((_, j) => j);
  let edge = Infinity;
  for (const j of loop) edge = Math.min(edge, segmentParam(q, pts2[j], pts2[(j + 1) % pts2.length])[1]);
  if (inside2(q, pts2, loop, 0)) return Math.abs(h);
  return Math.sqrt(h * h + edge * edge);
}

export function surfaceDistance(p, vertices, faces) {
  let best = Infinity;
  for (const f of faces) best = Math.min(best, pointPolygonDistance(p, f.map((i) => vertices[i])));
  return best;
}

/** Generalised winding number of a closed outward polyhedron about p (van Oosterom & Strackee). */
export function windingNumber(p, vertices, faces) {
  let total = 0;
  for (const f of faces) {
    const a = sub(vertices[f[0]], p);
    for (let k = 1; k + 1 < f.length; k++) {
      const b = sub(vertices[f[k]], p), c = sub(vertices[f[k + 1]], p);
      const la = norm(a), lb = norm(b), lc = norm(c);
      const num = dot(a, cross(b, c));
      const den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
      total += 2 * Math.atan2(num, den);
    }
  }
  return total / (4 * Math.PI);
}

export const contains = (p, vertices, faces, tol) => surfaceDistance(p, vertices, faces) <= tol || windingNumber(p, vertices, faces) > 0.5;
