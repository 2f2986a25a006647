// Shared helpers of the web test suite (exchange + viewer).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { spawnSync } from 'node:child_process';
import Ajv from 'ajv';

export const HERE = path.dirname(fileURLToPath(import.meta.url));
export const REPO = path.resolve(HERE, '..', '..');
export const EXCHANGE = path.join(REPO, 'plugin', 'exchange');
export const VIEWER = path.join(REPO, 'plugin', 'viewer');
export const SAMPLES = path.join(REPO, 'samples');
export const ARTIFACTS = path.join(HERE, 'artifacts');

/** The rbla binary: $RBLA_EXE, else the usual build folders. */
export function rblaExe() {
  const cands = [process.env.RBLA_EXE, ...['build-web', 'build'].map((b) => path.join(REPO, b, 'solver', 'rbla'))].filter(Boolean);
  for (const c of cands) if (fs.existsSync(c)) return c;
  return null;
}

export function tmpDir(prefix = 'rbla-web-') {
  return fs.mkdtempSync(path.join(os.tmpdir(), prefix));
}

export function run(cmd, args, opts = {}) {
  const r = spawnSync(cmd, args, { encoding: 'utf8', timeout: 60000, ...opts });
  return { code: r.status, signal: r.signal, stdout: r.stdout || '', stderr: r.stderr || '', error: r.error };
}

export function node(script, args) {
  return run(process.execPath, [path.join(EXCHANGE, script), ...args]);
}

export function readJson(p) { return JSON.parse(fs.readFileSync(p, 'utf8')); }

let ajv = null;
/** Draft-07 validators for the model and result schemas. */
export function validators() {
  if (!ajv) {
    ajv = new Ajv({ allErrors: true, strict: false });
    ajv.addFormat('json-pointer', /^(\/([^~/]|~[01])*)*$/);
    ajv.addSchema(readJson(path.join(REPO, 'schema', 'model.schema.json')), 'model');
    ajv.addSchema(readJson(path.join(REPO, 'schema', 'result.schema.json')), 'result');
  }
  const wrap = (name) => (data) => {
    const v = ajv.getSchema(name);
    const ok = v(data);
    return { ok, errors: ok ? [] : ajv.errorsText(v.errors, { separator: '\n' }) };
  };
  return { model: wrap('model'), result: wrap('result') };
}

/** Solve a model with rbla; returns the parsed result. */
export function solve(modelPath, resultPath) {
  const exe = rblaExe();
  const r = run(exe, ['solve', modelPath, '-o', resultPath]);
  if (r.code !== 0) throw new Error(`rbla solve ${modelPath} exited ${r.code}: ${r.stderr}`);
  return readJson(resultPath);
}

/** A character device like /dev/<name> (Linux major 1): as root a new node in dir (so a script that
 *  replaced it would replace only that copy), else the real one (only root could replace it); null
 *  when there is none. */
export function charDevice(dir, name, major, minor) {
  if (process.getuid && process.getuid() === 0) {
    const p = path.join(dir, name);
    const r = run('mknod', ['-m', '666', p, 'c', String(major), String(minor)]);
    return r.code === 0 ? p : null;
  }
  return fs.existsSync(`/dev/${name}`) ? `/dev/${name}` : null;
}
