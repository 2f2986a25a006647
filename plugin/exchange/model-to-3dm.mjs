#!/usr/bin/env node
// Write an rbla model JSON as a .3dm: blocks as closed Breps (default) or meshes, with User Text.
import { parseArgs, inputLimit, main, usageError, resolveOutput, checkNotInput, readJsonInput, writeOutput, MAX_INPUT_BYTES } from './lib/cli.mjs';
import { modelTo3dm } from './lib/rhino-io.mjs';

const USAGE = `usage: model-to-3dm.mjs MODEL.json -o OUT.3dm [--as brep|mesh] [--max-input-bytes N]
  MODEL.json: a file or a pipe of at most --max-input-bytes (default ${MAX_INPUT_BYTES}; 512M, 1G).`;

main(async () => {
  let args;
  try { args = parseArgs(process.argv.slice(2), { options: { '-o': 'out', '--output': 'out', '--as': 'as', '--max-input-bytes': 'maxInputBytes' } }); } catch (e) { throw usageError(e.message); }
  if (args.help) { console.log(USAGE); return 0; }
  if (args._.length !== 1 || !args.out) throw usageError('need one MODEL.json and -o OUT.3dm');
  const out = resolveOutput(args.out);  // refused before any work: never an input, a folder, ...
  checkNotInput(out, args._);
  const as = args.as || 'brep';
  if (!['brep', 'mesh'].includes(as)) throw usageError('--as must be brep or mesh');
  const maxBytes = inputLimit(args);
  const model = readJsonInput(args._[0], maxBytes);
  const doc = await modelTo3dm(model, { as });
  await writeOutput(out, doc.toByteArray());
  process.stderr.write(`wrote ${args.out}: ${model.blocks.length} blocks as ${as === "brep" ? "Breps" : "meshes"}\n`);
  return 0;
}, USAGE);
