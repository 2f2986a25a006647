#!/usr/bin/env node
// Write an rbla result as a .3dm that Rhino opens without any plugin.
import { parseArgs, numberOpt, inputLimit, main, usageError, resolveOutput, checkNotInput, readJsonInput, writeOutput, MAX_INPUT_BYTES } from './lib/cli.mjs';
import { resultTo3dm } from './lib/rhino-io.mjs';

const USAGE = `usage: result-to-3dm.mjs MODEL.json RESULT.json -o OUT.3dm [--amplitude S] [--run-name NAME] [--max-input-bytes N]
  Layers: "rbla run <UTC timestamp>" with sublayers blocks, displaced, interfaces::<state>, labels.
  Displaced blocks: p -> g + R(S theta)(p - g) + S u (default S: mechanism.displacement_scale).
  Inputs: files or pipes of at most --max-input-bytes each (default ${MAX_INPUT_BYTES}; 512M, 1G).`;

main(async () => {
  let args;
  try { args = parseArgs(process.argv.slice(2), { options: { '-o': 'out', '--output': 'out', '--amplitude': 'amplitude', '--run-name': 'runName', '--max-input-bytes': 'maxInputBytes' } }); } catch (e) { throw usageError(e.message); }
  if (args.help) { console.log(USAGE); return 0; }
  if (args._.length !== 2 || !args.out) throw usageError('need MODEL.json RESULT.json and -o OUT.3dm');
  const out = resolveOutput(args.out);  // refused before any work: never an input, a folder, ...
  checkNotInput(out, args._);
  const maxBytes = inputLimit(args);
  const model = readJsonInput(args._[0], maxBytes);
  const result = readJsonInput(args._[1], maxBytes);
  const { doc, parentName, amplitude, counts } = await resultTo3dm(model, result, { amplitude: numberOpt(args.amplitude, '--amplitude'), runName: args.runName });
  await writeOutput(out, doc.toByteArray());
  process.stderr.write(`wrote ${args.out}: layer "${parentName}", amplitude ${amplitude}, interfaces ${JSON.stringify(counts)}\n`);
  return 0;
}, USAGE);
