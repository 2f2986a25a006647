// .3dm exchange outputs, written by the solver's rules (plugin/exchange/lib/cli.mjs): an output that
// is an input is refused (however spelled), a link is followed (the link stays a link), a folder is
// refused with no temporary file left, a FIFO or character device is written into (never replaced),
// a replaced file keeps its permission bits (and owner and group where allowed), a signal mid-write
// leaves the old file and no temporary file, '-' is standard output.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { spawn } from 'node:child_process';
import { EXCHANGE, SAMPLES, node, run, tmpDir, solve, rblaExe, charDevice } from './helpers.mjs';

let dir, model, f3dm, result;
const noTemporary = () => assert.deepEqual(fs.readdirSync(dir).filter((n) => n.includes('.tmp')), []);
const bytes = (p) => fs.readFileSync(p);

before(() => {
  dir = tmpDir('rbla-exchange-out-');
  model = path.join(dir, 'model.json');
  fs.copyFileSync(path.join(SAMPLES, 'arch.json'), model);
  f3dm = path.join(dir, 'model.3dm');
  const r = node('model-to-3dm.mjs', [model, '-o', f3dm]);
  assert.equal(r.code, 0, r.stderr);
  if (rblaExe()) { result = path.join(dir, 'result.json'); solve(model, result); }
});

after(() => { fs.rmSync(dir, { recursive: true, force: true }); });

const device = (name, major, minor) => charDevice(dir, name, major, minor);

test('3dm-to-model refuses to write over its input, however spelled', () => {
  const before = bytes(f3dm);
  fs.symlinkSync('model.3dm', path.join(dir, 'link.3dm'));
  for (const out of [f3dm, path.join(dir, '.', 'model.3dm'), path.join(dir, 'link.3dm')]) {
    const r = node('3dm-to-model.mjs', [f3dm, '-o', out]);
    assert.notEqual(r.code, 0, `-o ${out} accepted`);
    assert.match(r.stderr, /input/);
    assert.doesNotMatch(r.stderr, /\n\s+at /, 'no stack trace');
  }
  assert.deepEqual(bytes(f3dm), before, 'the input is unchanged');
  assert.ok(fs.lstatSync(path.join(dir, 'link.3dm')).isSymbolicLink());
});

test('result-to-3dm refuses to write over either input', { skip: rblaExe() ? false : 'no rbla binary (set RBLA_EXE)' }, () => {
  for (const input of [result, model]) {
    const before = bytes(input);
    const r = node('result-to-3dm.mjs', [model, result, '-o', input]);
    assert.notEqual(r.code, 0, `-o ${input} accepted`);
    assert.match(r.stderr, /input/);
    assert.deepEqual(bytes(input), before, `${input} is unchanged`);
  }
  const out = path.join(dir, 'result.3dm');
  const r = node('result-to-3dm.mjs', [model, result, '-o', out]);
  assert.equal(r.code, 0, r.stderr);
});

test('model-to-3dm refuses to write over its input', () => {
  const before = bytes(model);
  const r = node('model-to-3dm.mjs', [model, '-o', model]);
  assert.notEqual(r.code, 0);
  assert.deepEqual(bytes(model), before);
});

test('a link is followed: its target is written, the link stays a link', () => {
  const target = path.join(dir, 'target.json');
  fs.writeFileSync(target, 'old\n');
  fs.symlinkSync('target.json', path.join(dir, 'out-link.json'));
  fs.symlinkSync('created.json', path.join(dir, 'dangling.json'));
  for (const link of ['out-link.json', 'dangling.json']) {
    const r = node('3dm-to-model.mjs', [f3dm, '-o', path.join(dir, link)]);
    assert.equal(r.code, 0, r.stderr);
    assert.ok(fs.lstatSync(path.join(dir, link)).isSymbolicLink(), `${link} is still a link`);
  }
  for (const name of ['target.json', 'created.json']) {
    assert.equal(JSON.parse(fs.readFileSync(path.join(dir, name), 'utf8')).blocks.length, 18);
  }
  noTemporary();
});

test('a folder is refused and no temporary file is left', () => {
  const folder = path.join(dir, 'folder');
  fs.mkdirSync(folder);
  for (const out of [folder, `${folder}/`]) {
    const r = node('3dm-to-model.mjs', [f3dm, '-o', out]);
    assert.notEqual(r.code, 0);
    assert.match(r.stderr, /directory|folder/);
  }
  assert.deepEqual(fs.readdirSync(folder), []);
  noTemporary();
});

test('a replaced file keeps its permission bits', () => {
  const out = path.join(dir, 'perm.json');
  fs.writeFileSync(out, 'old\n');
  fs.chmodSync(out, 0o640);
  const r = node('3dm-to-model.mjs', [f3dm, '-o', out]);
  assert.equal(r.code, 0, r.stderr);
  assert.equal(fs.statSync(out).mode & 0o7777, 0o640);
  assert.equal(JSON.parse(fs.readFileSync(out, 'utf8')).blocks.length, 18);
});

test('a replaced file keeps its owner and group where allowed', (t) => {
  const out = path.join(dir, 'owned.json');
  fs.writeFileSync(out, 'old\n');
  let owner;
  if (process.getuid?.() === 0) owner = [4321, 4322];  // root may give the new file anyone's
  else {
    const other = (process.getgroups?.() || []).find((g) => g !== process.getegid());
    if (other === undefined) { t.skip('not root and in no second group: nothing to keep'); return; }
    owner = [process.getuid(), other];
  }
  fs.chownSync(out, ...owner);
  const r = node('3dm-to-model.mjs', [f3dm, '-o', out]);
  assert.equal(r.code, 0, r.stderr);
  const st = fs.statSync(out);
  assert.deepEqual([st.uid, st.gid], owner);
  assert.equal(JSON.parse(fs.readFileSync(out, 'utf8')).blocks.length, 18);
});

// A writer that signals itself once its data is flushed, as a kill mid-write would; fsync then
// holds its answer (as a slow disk would), so the signal comes before the rename.
const SIGNALLED_WRITER = `
import fs from 'node:fs';
import { pathToFileURL } from 'node:url';
const [cli, out, sig] = process.argv.slice(1);
const { writeOutput } = await import(pathToFileURL(cli).href);
const fsync = fs.fsync, fsyncSync = fs.fsyncSync;
fs.fsync = (fd, callback) => fsync(fd, (e) => { process.kill(process.pid, sig); setTimeout(() => callback(e), 30000); });
fs.fsyncSync = (fd) => { fsyncSync(fd); process.kill(process.pid, sig); };
await writeOutput(out, 'new\\n');
process.stdout.write('survived');
`;

test('a signal mid-write removes the temporary file and still ends the process', { skip: process.platform === 'win32' }, () => {
  const sub = path.join(dir, 'signalled');
  fs.mkdirSync(sub);
  const out = path.join(sub, 'out.json');
  for (const sig of ['SIGTERM', 'SIGHUP', 'SIGINT']) {
    fs.writeFileSync(out, 'old\n');
    const r = run(process.execPath, ['--input-type=module', '-e', SIGNALLED_WRITER, path.join(EXCHANGE, 'lib', 'cli.mjs'), out, sig]);
    assert.equal(r.signal, sig, `${sig}: ended by it, as without a handler (${r.stdout} ${r.stderr})`);
    assert.deepEqual(fs.readdirSync(sub), ['out.json'], `${sig}: no temporary file`);
    assert.equal(fs.readFileSync(out, 'utf8'), 'old\n', `${sig}: the old file untouched`);
  }
});

test('character devices are written into, never replaced', (t) => {
  const nul = device('null', 1, 3), full = device('full', 1, 7);
  if (!nul || !full) { t.skip('no character device to write to'); return; }
  let r = node('3dm-to-model.mjs', [f3dm, '-o', nul]);
  assert.equal(r.code, 0, r.stderr);
  assert.ok(fs.lstatSync(nul).isCharacterDevice());
  r = node('3dm-to-model.mjs', [f3dm, '-o', full]);
  assert.notEqual(r.code, 0, 'a full device is a write error');
  assert.match(r.stderr, /no space/i);
  assert.ok(fs.lstatSync(full).isCharacterDevice());
  noTemporary();
});

test('a FIFO is written into, never replaced', { skip: process.platform === 'win32' }, async () => {
  const fifo = path.join(dir, 'pipe');
  assert.equal(run('mkfifo', [fifo]).code, 0);
  const child = spawn(process.execPath, [path.join(EXCHANGE, '3dm-to-model.mjs'), f3dm, '-o', fifo], { stdio: ['ignore', 'ignore', 'pipe'] });
  const exited = new Promise((resolve) => child.on('exit', (code) => resolve(code)));
  // The reader opens the FIFO, so a writer that replaced it instead would leave it waiting: a
  // timeout then unblocks it by opening the FIFO for writing itself.
  const timer = setTimeout(() => { try { fs.closeSync(fs.openSync(fifo, fs.constants.O_WRONLY | fs.constants.O_NONBLOCK)); } catch { /* gone */ } }, 20000);
  const text = await new Promise((resolve, reject) => {
    const chunks = [];
    fs.createReadStream(fifo).on('data', (c) => chunks.push(c)).on('end', () => resolve(Buffer.concat(chunks).toString('utf8'))).on('error', reject);
  });
  clearTimeout(timer);
  assert.equal(await exited, 0);
  assert.equal(JSON.parse(text).blocks.length, 18);
  assert.ok(fs.lstatSync(fifo).isFIFO());
});

test("'-' is standard output", () => {
  const r = node('3dm-to-model.mjs', [f3dm, '-o', '-']);
  assert.equal(r.code, 0, r.stderr);
  assert.equal(JSON.parse(r.stdout).blocks.length, 18);
});
