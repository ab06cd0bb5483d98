// Entry point of examples/web/sweep.
import { sweepMain } from './sweep.mjs';

// puppeteer-core closes its browser on these signals but leaves the process running: exit too.
for (const [signal, code] of [['SIGINT', 130], ['SIGTERM', 143], ['SIGHUP', 129]]) process.on(signal, () => process.exit(code));
process.exitCode = await sweepMain(process.argv.slice(2));
