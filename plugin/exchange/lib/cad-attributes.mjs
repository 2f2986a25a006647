// CAD attributes (User Text) read by the convention in plugin/rbla_cad/data/cad_attributes.json,
// the single source that the Rhino plugin's Python core (plugin/rbla_cad/usertext.py) reads too.
// Nothing about the keys is written here: this module implements the value types and the
// message formatting exactly as usertext.py does (tests/plugin/cad_cases run both on the same
// cases and compare their output), so the two readers cannot drift.
import fs from 'node:fs';

export const DATA_URL = new URL('../../rbla_cad/data/cad_attributes.json', import.meta.url);
export const DATA = JSON.parse(fs.readFileSync(DATA_URL, 'utf8'));
export const PREFIX = DATA.prefix;
export const KINDS = Object.keys(DATA.objects);
export const KEYS = Object.fromEntries(KINDS.map((k) => [k, new Map(DATA.objects[k].keys.map((e) => [e.key, e]))]));
export const ALIASES = Object.fromEntries(KINDS.map((k) => [k, new Map(DATA.objects[k].keys.flatMap((e) => (e.aliases || []).map((a) => [a, e.key])))]));
export const MESSAGES = Object.fromEntries(Object.entries(DATA.messages).filter(([k]) => !k.startsWith('$')));
export const TRUE = DATA.booleans.true;
const FALSE = DATA.booleans.false;
const NUMBER = /^[+-]?([0-9]+(\.[0-9]*)?|\.[0-9]+)([eE][+-]?[0-9]+)?$/;

// --- messages -------------------------------------------------------------------------------------

/** A value quoted as in every message of both readers (a JSON string). */
export const q = (text) => JSON.stringify(String(text));

/** A number as both readers print it: C's %.12g (what Python's '%.12g' gives). */
export function fmt(x) {
  if (x === 0) return Object.is(x, -0) ? '-0' : '0';
  if (!Number.isFinite(x)) return String(x);
  const sign = x < 0 ? '-' : '';
  const [m, e] = Math.abs(x).toExponential(11).split('e');
  let digits = m.replace('.', ''); // 12 significant digits; toExponential rounds exact ties up
  const [xm, xe] = Math.abs(x).toExponential(100).split('e');
  const exact = xm.replace('.', '');
  // C rounds an exact tie to even: keep the 12 digits when the 12th is even
  if (xe === e && exact[12] === '5' && /^0*$/.test(exact.slice(13)) && Number(exact[11]) % 2 === 0) digits = exact.slice(0, 12);
  const E = parseInt(e, 10);
  const strip = (t) => (t.includes('.') ? t.replace(/0+$/, '').replace(/\.$/, '') : t);
  if (E < -4 || E >= 12) return `${sign}${strip(`${digits[0]}.${digits.slice(1)}`)}e${E < 0 ? '-' : '+'}${String(Math.abs(E)).padStart(2, '0')}`;
  const fixed = E >= 0 ? `${digits.slice(0, E + 1)}.${digits.slice(E + 1)}` : `0.${'0'.repeat(-E - 1)}${digits}`;
  return sign + strip(fixed);
}

/** How messages name an object: object "Stone 7", or unnamed object <guid>. */
export const whoObject = (name, guid) => (name ? `object ${q(name)}` : `unnamed object ${guid}`);

export class Report {
  constructor() { this.messages = []; }

  add(code, obj = null, key = null, fields = {}) {
    const spec = MESSAGES[code];
    const f = key !== null && !('key' in fields) ? { ...fields, key } : fields;
    const text = spec.text.replace(/\{(\w+)\}/g, (_, name) => String(f[name]));
    const msg = { code, severity: spec.severity, text, object: obj, key };
    this.messages.push(msg);
    return msg;
  }

  get errors() { return this.messages.filter((m) => m.severity === 'error'); }

  get warnings() { return this.messages.filter((m) => m.severity === 'warning'); }
}

// --- values ---------------------------------------------------------------------------------------

export class Bad extends Error {
  constructor(code, fields = {}) { super(code); this.code = code; this.fields = fields; }
}

/** {lower-cased rbla.* key: trimmed value}; other keys are dropped. */
export function normalise(userText) {
  const out = {};
  for (const [k, v] of Object.entries(userText || {})) {
    const key = String(k).trim().toLowerCase();
    if (key.startsWith(PREFIX)) out[key] = v === null || v === undefined ? '' : String(v).trim();
  }
  return out;
}

const choiceKey = (text) => text.trim().toLowerCase().replace(/\s+/g, '_').replace(/(?<=\w)-(?=\w)/g, '_');

export function parseNumber(text, decimalComma = true) {
  let t = text.trim();
  if (decimalComma && t.split(',').length === 2 && !t.includes('.')) t = t.replace(',', '.');
  if (!NUMBER.test(t)) throw new Bad('bad_number');
  const x = Number(t);
  if (!Number.isFinite(x)) throw new Bad('bad_number');
  return x;
}

export function rangeText(e) {
  const parts = [];
  if ('minimum' in e) parts.push(`>= ${fmt(e.minimum)}`);
  if ('exclusive_minimum' in e) parts.push(`> ${fmt(e.exclusive_minimum)}`);
  if ('maximum' in e) parts.push(`<= ${fmt(e.maximum)}`);
  return parts.join(' and ');
}

const inRange = (x, e) => !(('minimum' in e && x < e.minimum) || ('exclusive_minimum' in e && x <= e.exclusive_minimum) || ('maximum' in e && x > e.maximum));

export function parseVector(text) {
  let t = text.trim();
  if (t.length >= 2 && ((t[0] === '[' && t.at(-1) === ']') || (t[0] === '(' && t.at(-1) === ')'))) t = t.slice(1, -1);
  let parts, comma;
  if (t.includes(';')) { parts = t.split(';').map((p) => p.trim()); comma = true; } else { parts = t.trim().split(/[,\s]+/).filter((p) => p); comma = false; }
  if (parts.length !== 3) throw new Bad('bad_vector');
  try { return parts.map((p) => parseNumber(p, comma)); } catch { throw new Bad('bad_vector'); }
}

function parseChoice(e, text) {
  const k = choiceKey(text);
  for (const v of e.values) if (choiceKey(v) === k) return v;
  for (const [s, v] of Object.entries(e.synonyms || {})) if (choiceKey(s) === k) return v;
  throw new Bad('bad_choice', { allowed: e.values.join(', ') });
}

function jsonExpected(e) {
  const what = `a JSON ${e.json} (model schema ${e.model})`;
  return e.type === 'choice_or_json' ? `one of ${e.values.join(', ')}, or ${what}` : what;
}

function parseJson(e, text) {
  let v;
  try { v = JSON.parse(text); } catch { v = undefined; }
  const ok = e.json === 'object' ? v !== null && typeof v === 'object' && !Array.isArray(v) : Array.isArray(v);
  if (!ok) throw new Bad('bad_json', { expected: jsonExpected(e) });
  return v;
}

/** The value of one key from its (non-empty) text; throws Bad. */
export function parseValue(e, text) {
  const t = e.type;
  if (t === 'number' || t === 'integer') {
    const x = parseNumber(text);
    if (t === 'integer' && x !== Math.floor(x)) throw new Bad('bad_integer');
    if (!inRange(x, e)) throw new Bad('out_of_range', { range: rangeText(e) });
    return x;
  }
  if (t === 'vector') {
    const v = parseVector(text);
    if (e.nonzero && !v.some((c) => c !== 0)) throw new Bad('zero_vector');
    return v;
  }
  if (t === 'choice') return parseChoice(e, text);
  if (t === 'choice_or_json') {
    if (['{', '['].includes(text.trimStart().slice(0, 1))) return parseJson(e, text);
    try { return parseChoice(e, text); } catch { throw new Bad('bad_json', { expected: jsonExpected(e) }); }
  }
  if (t === 'json') return parseJson(e, text);
  if (t === 'boolean') {
    const low = text.trim().toLowerCase();
    if (TRUE.includes(low)) return true;
    if (FALSE.includes(low)) return false;
    throw new Bad('bad_boolean');
  }
  if (t === 'pair') {
    const ids = text.split(text.includes(';') ? ';' : ',').map((s) => s.trim());
    if (ids.length !== 2 || !ids[0] || !ids[1] || ids[0] === ids[1]) throw new Bad('bad_pair');
    return ids;
  }
  if (t === 'text' || t === 'id') {
    const limit = e.maximum_length ?? 1000000;
    if ([...text].length > limit || (t === 'id' && !text)) throw new Bad('bad_text', { maximum: limit, length: [...text].length });
    return text;
  }
  throw new Error(`cad_attributes.json: unknown type ${t} of ${e.key}`);
}

/** What a reader uses when the key is absent (for messages). */
export function defaultText(e) {
  if ('default_text' in e) return e.default_text;
  if (!('default' in e)) return 'none';
  const d = e.default;
  if (typeof d === 'boolean') return d ? 'true' : 'false';
  if (Array.isArray(d)) return d.map(fmt).join(', ');
  if (typeof d === 'number') return fmt(d);
  return String(d);
}

// --- key reading ----------------------------------------------------------------------------------

function editDistance(a, b) {
  let prev = [...Array(b.length + 1).keys()];
  for (let i = 1; i <= a.length; i++) {
    const cur = [i];
    for (let j = 1; j <= b.length; j++) cur.push(Math.min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] !== b[j - 1] ? 1 : 0)));
    prev = cur;
  }
  return prev[b.length];
}

/** '; did you mean rbla.x?' for the closest known key at most 2 edits away (this kind first). */
function hint(key, kind) {
  for (const kinds of [[kind], KINDS.filter((k) => k !== kind)]) {
    let best = null, dist = 3;
    for (const k of kinds) {
      for (const name of [...KEYS[k].keys(), ...ALIASES[k].keys()]) {
        const d = editDistance(key, name);
        if (d < dist) { best = ALIASES[k].get(name) ?? name; dist = d; }
      }
    }
    if (best) return `; did you mean ${best}?`;
  }
  return '';
}

const kindOfKey = (key) => KINDS.find((k) => KEYS[k].has(key) || ALIASES[k].has(key)) ?? null;

/**
 * Parse an object's (or the document's) rbla.* keys of `kind`: returns {key: value} for the keys
 * given with a readable value; messages go to `report` (see usertext.read_keys).
 */
export function readKeys(kind, userText, who, report, obj = null, host = null) {
  const ut = normalise(userText);
  const out = {};
  for (const key of Object.keys(ut).sort()) {
    const text = ut[key];
    let name = key;
    if (ALIASES[kind].has(key)) {
      name = ALIASES[kind].get(key);
      if (name in ut) { report.add('conflict', obj, key, { who, other: name }); continue; }
      report.add('old_key', obj, key, { who, new: name });
    }
    const e = KEYS[kind].get(name);
    if (!e) {
      if (kindOfKey(key) !== null) report.add('misplaced_key', obj, key, { who, kind });
      else report.add('unknown_key', obj, key, { who, hint: hint(key, kind) });
      continue;
    }
    if (host !== null && !(e.hosts || [host]).includes(host)) continue;
    if (e.ignored) continue;
    if (text === '' && !e.empty_allowed) {
      if (e.marker) report.add('bad_choice', obj, name, { who, value: q(text), allowed: e.values.join(', ') });
      else report.add('empty_value', obj, name, { who, used: defaultText(e) });
      continue;
    }
    try {
      out[name] = text || !e.empty_allowed ? parseValue(e, text) : '';
    } catch (err) {
      if (!(err instanceof Bad)) throw err;
      report.add(err.code, obj, name, { who, value: q(text), ...err.fields });
    }
  }
  return out;
}
