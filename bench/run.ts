// `npm run bench`: prints the benchmark tables and writes them as JSON to
// bench/results/latest.json. Quick mode (--quick) uses fewer samples.
// Numbers are medians of repeated runs in one process; compare ratios, not
// absolute times, on a shared machine.
import { nodeDevice, releaseNodeDevice } from '../src/gpu/nodeDevice.ts';
import { benchEstimators } from './estimators.ts';
import { benchTransmittance } from './transmittance.ts';
import { printTable, saveTables } from './table.ts';

const quick = process.argv.includes('--quick');
const device = await nodeDevice();
const tables = [
  await benchTransmittance(device, { n: quick ? 1 << 16 : 1 << 20, repeats: 5 }),
  await benchEstimators(device, {
    gpuWalks: quick ? 1 << 14 : 1 << 18,
    cpuWalks: quick ? 1 << 11 : 1 << 14,
    repeats: 5,
  }),
];
for (const table of tables) printTable(table);
const path = new URL('./results/latest.json', import.meta.url).pathname;
saveTables(path, tables, {
  date: new Date().toISOString(),
  device: 'Dawn (webgpu npm package); SwiftShader on machines without a GPU',
  command: `npm run bench${quick ? ' -- --quick' : ''}`,
});
console.log(`\nWrote ${path}`);
await releaseNodeDevice();
