#!/usr/bin/env node
// Convert a Rhino .3dm (closed planar-faced Breps, extrusions, closed meshes) to an rbla model JSON.
import fs from 'node:fs';
import { parseArgs, numberOpt, main, usageError } from './lib/cli.mjs';
import { readFile3dm, file3dmToModel } from './lib/rhino-io.mjs';

const USAGE = `usage: 3dm-to-model.mjs IN.3dm -o MODEL.json [--unit-weight W] [--friction MU] [--title TEXT]
  Object name -> block id; object User Text rbla.role (free|fixed|moving_support),
  rbla.unit_weight, rbla.friction, rbla.label. Document units -> units.length.`;

main(async () => {
  let args;
  try {
    args = parseArgs(process.argv.slice(2), { options: { '-o': 'out', '--output': 'out', '--unit-weight': 'unitWeight', '--friction': 'friction', '--title': 'title' } });
  } catch (e) { throw usageError(e.message); }
  if (args.help) { console.log(USAGE); return 0; }
  if (args._.length !== 1 || !args.out) throw usageError('need one input .3dm and -o MODEL.json');
  const bytes = new Uint8Array(fs.readFileSync(args._[0]));
  const doc = await readFile3dm(bytes);
  const { model, warnings } = await file3dmToModel(doc, {
    unitWeight: numberOpt(args.unitWeight, '--unit-weight'),
    friction: numberOpt(args.friction, '--friction'),
    title: args.title,
  });
  for (const w of warnings) process.stderr.write(`warning: ${w}\n`);
  fs.writeFileSync(args.out, JSON.stringify(model, null, 1) + '\n');
  process.stderr.write(`wrote ${args.out}: ${model.blocks.length} blocks, units ${model.units.length}\n`);
  return 0;
}, USAGE);
