// Entry point of examples/web/render (the bash wrapper checks for node first).
import { main } from './render.mjs';

process.exitCode = await main(process.argv.slice(2));
