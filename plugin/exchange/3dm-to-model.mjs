#!/usr/bin/env node
// Convert a Rhino .3dm to an rbla model JSON by the CAD attribute convention
// (docs/cad-attributes.md; the Rhino plugin reads the same keys the same way).
import path from 'node:path';
import { parseArgs, numberOpt, inputLimit, main, usageError, resolveOutput, checkNotInput, readInput, writeOutput, MAX_INPUT_BYTES } from './lib/cli.mjs';
import { readFile3dm, file3dmToModel } from './lib/rhino-io.mjs';

const USAGE = `usage: 3dm-to-model.mjs IN.3dm -o MODEL.json [--unit-weight W] [--friction MU] [--title TEXT] [--max-input-bytes N]
  Blocks: closed Breps, extrusions, closed meshes; interface objects (rbla.interface) and load
  points (rbla.load); object and Document User Text rbla.* as in docs/cad-attributes.md.
  --unit-weight, --friction and --title override rbla.default_unit_weight, rbla.default_friction
  and rbla.title. Every error is listed and nothing is written when there is one (exit 1).
  IN.3dm: a file or a pipe of at most --max-input-bytes (default ${MAX_INPUT_BYTES}; 512M, 1G).`;

main(async () => {
  let args;
  try {
    args = parseArgs(process.argv.slice(2), { options: { '-o': 'out', '--output': 'out', '--unit-weight': 'unitWeight', '--friction': 'friction', '--title': 'title', '--max-input-bytes': 'maxInputBytes' } });
  } catch (e) { throw usageError(e.message); }
  if (args.help) { console.log(USAGE); return 0; }
  if (args._.length !== 1 || !args.out) throw usageError('need one input .3dm and -o MODEL.json');
  const out = resolveOutput(args.out);  // refused before any work: never an input, a folder, ...
  checkNotInput(out, [args._[0]]);
  const unitWeight = numberOpt(args.unitWeight, '--unit-weight');
  const friction = numberOpt(args.friction, '--friction');
  const maxBytes = inputLimit(args);
  const bytes = new Uint8Array(readInput(args._[0], maxBytes));
  const doc = await readFile3dm(bytes);
  const { model, warnings, errors } = await file3dmToModel(doc, {
    unitWeight, friction, title: args.title, name: path.basename(args._[0]).replace(/\.3dm$/i, ''),
  });
  for (const w of warnings) process.stderr.write(`warning [${w.code}]: ${w.text}\n`);
  if (errors.length) {
    for (const e of errors) process.stderr.write(`error [${e.code}]: ${e.text}\n`);
    process.stderr.write(`${args._[0]}: ${errors.length} error(s); no model written\n`);
    return 1;
  }
  await writeOutput(out, JSON.stringify(model, null, 1) + '\n');
  process.stderr.write(`wrote ${args.out}: ${model.blocks.length} blocks, ${(model.interfaces || []).length} interfaces given, units ${model.units.length}\n`);
  return 0;
}, USAGE);
