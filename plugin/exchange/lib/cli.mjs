// Minimal argument parsing shared by the exchange command-line scripts.
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
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

/** What a system error says, without Node's code and syscall ("no such file or directory"). */
function reason(e) {
  const m = e && e.code ? /^[A-Z0-9_]+: (.*?)(?:, \w+(?: '.*')?)?$/s.exec(e.message) : null;
  return m ? m[1] : String(e && e.message ? e.message : e);
}

// ---- Inputs, read by the solver's rules (solver/src/io/input_file.hpp) ----------------------------
// A regular file or a FIFO; a directory, a device (/dev/zero would never end) or a socket is refused
// before it is read, and so is anything above the limit (a FIFO has no size: it is read with it).

/** The solver's --max-input-bytes default (solver/src/io/input_limits.hpp): 256 MiB. */
export const MAX_INPUT_BYTES = 256 * 1024 * 1024;

/** A --max-input-bytes value: a whole number of bytes, or with K, M or G (binary, as the solver's). */
export function byteCount(v, name) {
  const m = /^(\d+)\s*([kmg])?(?:i?b)?$/i.exec(String(v).trim());
  const scale = { k: 2 ** 10, m: 2 ** 20, g: 2 ** 30 }[(m?.[2] || '').toLowerCase()] || 1;
  const n = m ? Number(m[1]) * scale : NaN;
  if (!Number.isSafeInteger(n) || n < 1) throw usageError(`${name} must be a positive number of bytes (e.g. 1000000, 512M, 1G), got "${v}"`);
  return n;
}

/** The input limit of a script: its --max-input-bytes value (args.maxInputBytes), else the default. */
export function inputLimit(args) {
  return args.maxInputBytes === undefined ? MAX_INPUT_BYTES : byteCount(args.maxInputBytes, '--max-input-bytes');
}

function refuseInput(file, why) { throw new Error(`cannot read '${file}': ${why}`); }

function checkReadable(file, st, maxBytes) {
  if (!st.isFile() && !st.isFIFO()) refuseInput(file, `${kindOf(st)}; give a file or a pipe`);
  if (st.size > maxBytes) refuseInput(file, `it is ${st.size} bytes, more than the input limit of ${maxBytes} (--max-input-bytes)`);
}

/** The bytes of a regular file or FIFO, refused (an Error naming the path) before reading when it
 *  is anything else or larger than maxBytes, and as soon as a FIFO gives more. */
export function readInput(file, maxBytes = MAX_INPUT_BYTES) {
  let st;
  try { st = fs.statSync(file); } catch (e) { refuseInput(file, reason(e)); }
  checkReadable(file, st, maxBytes);
  let fd;
  try { fd = fs.openSync(file, 'r'); } catch (e) { refuseInput(file, reason(e)); }
  try {
    checkReadable(file, fs.fstatSync(fd), maxBytes);  // what was opened: it may have been swapped
    const chunks = [];
    let total = 0;
    for (;;) {
      const chunk = Buffer.allocUnsafe(Math.min(1 << 20, maxBytes - total + 1));
      const n = fs.readSync(fd, chunk, 0, chunk.length, null);
      if (n === 0) return Buffer.concat(chunks, total);
      total += n;
      if (total > maxBytes) refuseInput(file, `more than ${maxBytes} bytes (the input limit, --max-input-bytes)`);
      chunks.push(chunk.subarray(0, n));
    }
  } catch (e) {
    if (e.code) refuseInput(file, reason(e));
    throw e;
  } finally { fs.closeSync(fd); }
}

/** A JSON input parsed (readInput's rules); a file that is not JSON is refused naming it. */
export function readJsonInput(file, maxBytes = MAX_INPUT_BYTES) {
  const text = readInput(file, maxBytes).toString('utf8');
  try { return JSON.parse(text); } catch (e) { return refuseInput(file, `not JSON: ${e.message}`); }
}

// ---- Outputs, written by the solver's rules (solver/src/io/atomic_file.hpp) -------------------
// '-' is standard output; a FIFO or a character device (a pipe, a terminal, /dev/null) is written
// into, never replaced; a regular file (or nothing yet) is written to a temporary file in its
// folder and renamed over it (atomic), keeping the old file's permission bits (and owner and group
// where the system allows); a symbolic link is followed and its target written; a directory, block
// device or socket is refused, and so is a file or folder we may not write. An output that is one
// of the inputs is refused. On failure, SIGINT, SIGTERM or SIGHUP included, the temporary file is
// removed and what was there is left as it was.

function refuse(file, target, why) {
  const link = target && target !== file ? ` (a link to '${target}')` : '';
  throw new Error(`cannot write '${file}'${link}: ${why}`);
}

function kindOf(st) {
  if (st.isDirectory()) return 'it is a directory';
  if (st.isBlockDevice()) return 'it is a block device';
  if (st.isSocket()) return 'it is a socket';
  if (st.isCharacterDevice()) return 'it is a character device';
  return 'it is not a regular file';
}

/** The path a chain of symbolic links ends at, whether or not something is there. */
function followLinks(file) {
  let current = file;
  for (let hops = 0; hops < 40; hops++) {
    const st = fs.lstatSync(current, { throwIfNoEntry: false });
    if (!st || !st.isSymbolicLink()) return current;
    const to = fs.readlinkSync(current);
    current = path.isAbsolute(to) ? to : path.join(path.dirname(current), to);
  }
  refuse(file, current, 'too many levels of symbolic links');
}

/** Where an output path leads: { file, kind: 'stdout' | 'stream' | 'replace', target, identity }.
 *  Call it before the work, so a wrong -o is refused before anything is read or written. */
export function resolveOutput(file) {
  if (file === '-') return { file, kind: 'stdout' };
  if (!file) throw new Error('cannot write to an empty path');
  // What the system reaches through the path: a pipe behind /dev/stdout is a link whose text
  // ("pipe:[123]") names no file, so pipes and devices are judged from here.
  let st;
  try { st = fs.statSync(file, { throwIfNoEntry: false }); } catch { st = undefined; }
  if (st && !st.isFile()) {
    if (st.isFIFO() || st.isCharacterDevice()) return { file, kind: 'stream', target: file, identity: `${st.dev}:${st.ino}` };
    refuse(file, null, kindOf(st));
  }
  const target = followLinks(file);
  const name = path.basename(target);
  if (!name || name === '.' || name === '..' || /[\\/]$/.test(target)) refuse(file, target, 'it names a folder, not a file');
  const folder = path.dirname(target);
  const dir = fs.statSync(folder, { throwIfNoEntry: false });
  if (!dir || !dir.isDirectory()) refuse(file, target, `its folder '${folder}' does not exist or is not a folder`);
  // Rename would replace a read-only file given a writable folder; a file we may not write is not ours.
  try { fs.accessSync(folder, fs.constants.W_OK | fs.constants.X_OK); } catch { refuse(file, target, `cannot write into its folder '${folder}'`); }
  if (st) { try { fs.accessSync(target, fs.constants.W_OK); } catch { refuse(file, target, 'the file there may not be written'); } }
  return { file, kind: 'replace', target, identity: st ? `${st.dev}:${st.ino}` : null };
}

/** Refuses an output that is one of the input files, however either is spelled (device + inode). */
export function checkNotInput(out, inputs) {
  if (!out.identity) return;
  for (const input of inputs) {
    let st;
    try { st = fs.statSync(input); } catch { continue; }
    if (`${st.dev}:${st.ino}` === out.identity) throw new Error(`will not write '${out.file}': it is the input '${input}'`);
  }
}

function writeAll(fd, buf) {
  for (let off = 0; off < buf.length;) off += fs.writeSync(fd, buf, off, buf.length - off);
}

// ---- Temporary files removed on signals (the solver's remove_temporary_files_on_signals) -------
// JavaScript handles a signal only between callbacks, so the temporary file is written with
// asynchronous calls (fs.write, fs.fsync: looked up when called), between which the handler runs.
// The listeners stay once added: one removed while libuv holds a signal not yet delivered to it
// would swallow that signal. With no temporary file the handler ends the process as the signal
// would have. (Node resets every signal to its default at start, so none was being ignored.)

const temporaries = new Set();
const SIGNALS = process.platform === 'win32' ? ['SIGINT'] : ['SIGINT', 'SIGTERM', 'SIGHUP'];
let listening = false;

function removeTemporariesThenResignal(signal) {
  for (const file of temporaries) { try { fs.unlinkSync(file); } catch { /* already gone */ } }
  temporaries.clear();
  for (const s of SIGNALS) process.removeListener(s, removeTemporariesThenResignal);
  // Without listeners libuv puts the default action back: the signal then ends the process.
  if (process.listenerCount(signal) === 0) process.kill(process.pid, signal);
}

function removeOnSignals(file) {
  temporaries.add(file);
  if (listening) return;
  listening = true;
  for (const s of SIGNALS) process.on(s, removeTemporariesThenResignal);
}

const fsCall = (name, ...args) => new Promise((resolve, reject) => {
  fs[name](...args, (e, value) => (e ? reject(e) : resolve(value)));
});

async function writeAllAsync(fd, buf) {
  for (let off = 0; off < buf.length;) off += await fsCall('write', fd, buf, off, buf.length - off, null);
}

/** Owner and group of the replaced file where we may (root; or the group alone, when we belong to
 *  it); else the new file is ours, as any new file would be. As the solver does. */
function keepOwner(fd, old) {
  if (!process.geteuid || (old.uid === process.geteuid() && old.gid === process.getegid())) return;
  try { fs.fchownSync(fd, old.uid, old.gid); } catch {
    try { fs.fchownSync(fd, -1, old.gid); } catch { /* ours */ }
  }
}

async function writeReplace(out, buf) {
  const folder = path.dirname(out.target);
  const tmp = path.join(folder, `${path.basename(out.target).slice(0, 200)}.tmp-${process.pid}-${crypto.randomBytes(4).toString('hex')}`);
  let fd;
  try { fd = fs.openSync(tmp, 'wx', 0o666); } catch (e) { refuse(out.file, out.target, `cannot create a temporary file in '${folder}': ${reason(e)}`); }
  removeOnSignals(tmp);
  try {
    try {
      await writeAllAsync(fd, buf);
      await fsCall('fsync', fd);
      const old = fs.statSync(out.target, { throwIfNoEntry: false });
      if (old && !old.isFile()) refuse(out.file, out.target, 'it changed while being written: it is no longer a regular file');
      if (old) {  // (a new file keeps what open gave it: 0666 less the umask)
        keepOwner(fd, old);  // first: a change of owner may clear set-id bits
        fs.fchmodSync(fd, old.mode & 0o7777);
      }
    } finally { fs.closeSync(fd); }
    fs.renameSync(tmp, out.target);
  } catch (e) {
    try { fs.unlinkSync(tmp); } catch { /* already gone */ }
    if (e.code) refuse(out.file, out.target, reason(e));
    throw e;
  } finally { temporaries.delete(tmp); }
}

/** Writes data (string as UTF-8, or bytes) to out (from resolveOutput, or a path) by the rules
 *  above. Asynchronous, so that a signal can remove the temporary file mid-write: await it. */
export async function writeOutput(out, data) {
  if (typeof out === 'string') out = resolveOutput(out);
  const buf = typeof data === 'string' ? Buffer.from(data, 'utf8') : Buffer.from(data.buffer, data.byteOffset, data.byteLength);
  if (out.kind === 'stdout') { process.stdout.write(buf); return; }
  if (out.kind === 'stream') {
    let fd;
    try { fd = fs.openSync(out.target, fs.constants.O_WRONLY | (fs.constants.O_NOCTTY || 0)); } catch (e) { refuse(out.file, null, reason(e)); }
    try {
      const st = fs.fstatSync(fd);  // swapped for a file since resolveOutput: never write a file this way
      if (!st.isFIFO() && !st.isCharacterDevice()) refuse(out.file, null, 'it changed while being opened');
      writeAll(fd, buf);
    } catch (e) {
      if (e.code) refuse(out.file, null, reason(e));
      throw e;
    } finally { fs.closeSync(fd); }
    return;
  }
  await writeReplace(out, buf);
}

/** Write a file whole or not at all (writeOutput's rules; kept for callers of the old name). */
export function writeFileAtomic(file, data) { return writeOutput(file, data); }
