// Entry point of examples/web/sweep.
import { sweepMain } from './sweep.mjs';

process.exitCode = await sweepMain(process.argv.slice(2));
