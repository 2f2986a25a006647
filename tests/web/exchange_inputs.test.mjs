// .3dm exchange inputs, read by the solver's rules (plugin/exchange/lib/cli.mjs readInput): a
// directory, a device (/dev/zero would never end) or a file above --max-input-bytes (default 256
// MiB, the solver's) is refused before it is read, with one line naming it and exit 1; a FIFO is
// read up to the limit; a file that is not JSON is refused naming it.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { spawn } from 'node:child_process';
import { SAMPLES, node, run, tmpDir, charDevice } from './helpers.mjs';

let dir, model, out;

before(() => {
  dir = tmpDir('rbla-exchange-in-');
  model = path.join(dir, 'model.json');
  fs.copyFileSync(path.join(SAMPLES, 'arch.json'), model);
  out = path.join(dir, 'out');
});

after(() => { fs.rmSync(dir, { recursive: true, force: true }); });

// Each script with the argument list that makes `input` the file read (result-to-3dm reads two).
const READERS = [
  ['3dm-to-model.mjs', (input) => [input, '-o', out]],
  ['model-to-3dm.mjs', (input) => [input, '-o', out]],
  ['result-to-3dm.mjs', (input) => [input, model, '-o', out]],
  ['result-to-3dm.mjs', (input) => [model, input, '-o', out]],
];

function assertRefused(r, input, why) {
  assert.equal(r.code, 1, r.stderr);
  assert.ok(r.stderr.includes(`cannot read '${input}': `), r.stderr);
  assert.match(r.stderr, why);
  assert.equal(r.stderr.trim().split('\n').length, 1, r.stderr);
  assert.doesNotMatch(r.stderr, /\n\s+at /, 'no stack trace');
  assert.ok(!fs.existsSync(out), 'nothing written');
}

/** Runs a script that reads fifo while another process writes file into it `times` times. The
 *  writer is ended once the script is: a script that never opened the FIFO would leave it waiting. */
async function readFromFifo(fifo, file, times, script, args) {
  const writer = spawn('sh', ['-c', 'i=0; while [ $i -lt "$2" ]; do cat "$1"; i=$((i+1)); done > "$0"', fifo, file, String(times)], { stdio: 'ignore' });
  const exited = new Promise((resolve) => writer.on('exit', resolve));
  const r = node(script, args);
  writer.kill();
  await exited;
  return r;
}

test('a directory, a character device or a file above the limit is refused before it is read', () => {
  const folder = path.join(dir, 'folder');
  fs.mkdirSync(folder);
  const huge = path.join(dir, 'huge.json');
  fs.closeSync(fs.openSync(huge, 'w'));
  fs.truncateSync(huge, 256 * 2 ** 20 + 1);  // sparse: no disk used, and never read
  const cases = [[folder, /it is a directory/], [huge, /268435457 bytes, more than the input limit of 268435456/]];
  const zero = charDevice(dir, 'zero', 1, 5);
  if (zero) cases.push([zero, /it is a character device/]);
  for (const [script, args] of READERS) {
    for (const [input, why] of cases) assertRefused(node(script, args(input)), input, why);
  }
});

test('--max-input-bytes sets the limit, in bytes or with K, M or G; a bad value is a usage error', () => {
  assertRefused(node('model-to-3dm.mjs', [model, '-o', out, '--max-input-bytes', '1K']), model, /more than the input limit of 1024 /);
  for (const bad of ['0', '-5', 'lots', '1.5M']) {
    const r = node('model-to-3dm.mjs', [model, '-o', out, '--max-input-bytes', bad]);
    assert.equal(r.code, 2, `--max-input-bytes ${bad}: ${r.stderr}`);
    assert.match(r.stderr, /--max-input-bytes must be a positive number of bytes/);
  }
  const r = node('model-to-3dm.mjs', [model, '-o', out, '--max-input-bytes', '1M']);
  assert.equal(r.code, 0, r.stderr);
  fs.rmSync(out);
});

test('a FIFO is read, and refused as soon as it gives more than the limit', { skip: process.platform === 'win32' }, async () => {
  const fifo = path.join(dir, 'pipe');
  assert.equal(run('mkfifo', [fifo]).code, 0);
  let r = await readFromFifo(fifo, model, 1, 'model-to-3dm.mjs', [fifo, '-o', out]);
  assert.equal(r.code, 0, r.stderr);
  fs.rmSync(out);
  const limit = fs.statSync(model).size + 10;
  r = await readFromFifo(fifo, model, 3, 'model-to-3dm.mjs', [fifo, '-o', out, '--max-input-bytes', String(limit)]);
  assertRefused(r, fifo, new RegExp(`more than ${limit} bytes`));
});

test('a file that is not JSON is refused naming it', () => {
  const bad = path.join(dir, 'bad.json');
  fs.writeFileSync(bad, '{"blocks": [');
  for (const [script, args] of READERS.slice(1)) assertRefused(node(script, args(bad)), bad, /not JSON/);
});
