// Minimal argument parsing shared by the exchange command-line scripts.
import fs from 'node:fs';
export function parseArgs(argv, spec) {
  // spec: { positional: n, options: { '-o': 'out', '--amplitude': 'amplitude', ... }, flags: {...} }
  const out = { _: [] };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i];
    if (a === '-h' || a === '--help') { out.help = true; continue; }
    const eq = a.startsWith('--') ? a.indexOf('=') : -1;
    const key = eq > 0 ? a.slice(0, eq) : a;
    if (spec.options && key in spec.options) {
      const val = eq > 0 ? a.slice(eq + 1) : argv[++i];
      if (val === undefined) throw new Error(`option ${key} needs a value`);
      out[spec.options[key]] = val;
    } else if (spec.flags && key in spec.flags) {
      out[spec.flags[key]] = true;
    } else if (a.startsWith('-') && a.length > 1 && !/^-\d/.test(a)) {
      throw new Error(`unknown option ${a}`);
    } else out._.push(a);
  }
  return out;
}

export function numberOpt(v, name) {
  if (v === undefined) return undefined;
  const x = Number(v);
  if (!Number.isFinite(x)) throw new Error(`${name} must be a number, got "${v}"`);
  return x;
}

export async function main(fn, usage) {
  try {
    const code = await fn();
    process.exitCode = code ?? 0;
  } catch (e) {
    if (e && e.usage) { process.stderr.write(`${e.message}\n${usage}\n`); process.exitCode = 2; return; }
    process.stderr.write(`error: ${e && e.message ? e.message : e}\n`);
    process.exitCode = 1;
  }
}

export function usageError(msg) { const e = new Error(msg); e.usage = true; return e; }

/** Write a file whole or not at all: a temporary file next to it, renamed into place. */
export function writeFileAtomic(file, data) {
  const tmp = `${file}.tmp${process.pid}`;
  try {
    fs.writeFileSync(tmp, data);
    fs.renameSync(tmp, file);
  } catch (e) {
    try { fs.unlinkSync(tmp); } catch { /* nothing was written */ }
    throw e;
  }
}
