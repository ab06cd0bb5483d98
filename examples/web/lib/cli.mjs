// Entry point of examples/web/render (the bash wrapper checks for node first).
import { main } from './render.mjs';

// puppeteer-core closes its browser on these signals but leaves the process running: exit too.
for (const [signal, code] of [['SIGINT', 130], ['SIGTERM', 143], ['SIGHUP', 129]]) process.on(signal, () => process.exit(code));
process.exitCode = await main(process.argv.slice(2));
