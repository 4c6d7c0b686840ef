// `npm run bench`: prints the benchmark tables and writes them as JSON to
// bench/results/latest.json. Quick mode (--quick) uses fewer samples;
// --only=core,transmittance,estimators,subsurface,translucent,chromatic,room,widgets,scenes,peers,startup,photons,grading,pages,interaction,neural
// runs a subset (`pages` and `interaction` measure the production build in dist/, or in
// --dist=DIR: run `npx vite build` first; `interaction` also takes --backend=gpu|cpu|both
// and --only-widgets=a,b and --in-chapter, see bench/interaction.ts (`widgets` takes --only-widgets too);
// `neural` takes --seconds=S and the problem as --views= --batch= --steps= --rate= --table=
// --grid=, see bench/neural.ts; `startup` takes --baseline=DIR, an older checkout to time
// alongside, see bench/startup.ts).
// Numbers are medians of repeated runs in one process; compare ratios, not
// absolute times, on a shared machine.
import { nodeDevice, releaseNodeDevice } from '../src/gpu/nodeDevice.ts';
import { benchChromatic } from './chromatic.ts';
import { benchCore } from './core.ts';
import { benchEstimators } from './estimators.ts';
import { benchGrading } from './grading.ts';
import { benchInteraction, interactionOptionsFromArgs } from './interaction.ts';
import { benchNeural } from './neural.ts';
import { benchPages } from './pages.ts';
import { benchPeers } from './peers.ts';
import { benchPhotons } from './photons.ts';
import { benchScenes } from './scenes.ts';
import { benchStartup } from './startup.ts';
import { benchSubsurface } from './subsurface.ts';
import { benchTranslucent } from './translucent.ts';
import { benchTranslucentRoom } from './translucentRoom.ts';
import { benchTransmittance } from './transmittance.ts';
import { benchWidgets } from './widgets.ts';
import { printTable, saveTables, type BenchTable } from './table.ts';

const quick = process.argv.includes('--quick');
const only = process.argv
  .find((a) => a.startsWith('--only='))
  ?.slice('--only='.length)
  .split(',');
const wanted = (name: string): boolean => !only || only.includes(name);
const dist = process.argv.find((a) => a.startsWith('--dist='))?.slice('--dist='.length);
const baseline = process.argv.find((a) => a.startsWith('--baseline='))?.slice('--baseline='.length);
/** The number given as --name=value, else the fallback. */
const numberArg = (name: string, fallback: number): number => {
  const value = process.argv.find((a) => a.startsWith(`--${name}=`))?.slice(name.length + 3);
  return value === undefined ? fallback : Number(value);
};

const device = await nodeDevice();
const tables: BenchTable[] = [];
if (wanted('core'))
  tables.push(await benchCore(device, { calls: quick ? 200 : 2000, repeats: quick ? 3 : 5 }));
if (wanted('transmittance'))
  tables.push(await benchTransmittance(device, { n: quick ? 1 << 16 : 1 << 20, repeats: 5 }));
if (wanted('estimators'))
  tables.push(
    await benchEstimators(device, {
      gpuWalks: quick ? 1 << 14 : 1 << 18,
      cpuWalks: quick ? 1 << 11 : 1 << 14,
      repeats: 5,
    }),
  );
if (wanted('subsurface'))
  tables.push(
    ...(await benchSubsurface(device, {
      gpuPhotons: quick ? 1 << 16 : 1 << 20,
      cpuPhotons: quick ? 1 << 13 : 1 << 16,
      scenePhotons: quick ? 1 << 14 : 1 << 17,
      repeats: 5,
    })),
  );
if (wanted('translucent'))
  tables.push(
    ...(await benchTranslucent(device, {
      size: quick ? 32 : 64,
      spp: quick ? 64 : 1024,
      sppPerBatch: quick ? 16 : 32,
      repeats: quick ? 3 : 9,
    })),
  );
if (wanted('chromatic'))
  tables.push(await benchChromatic(device, { spp: quick ? 16 : 64, spreads: [1, 16, 100] }));
if (wanted('room'))
  tables.push(
    ...(await benchTranslucentRoom(device, {
      size: quick ? 24 : 32,
      referenceSpp: quick ? 64 : 256,
      dipoleSpp: quick ? 16 : 32,
      batch: quick ? 16 : 32,
      samples: 1024,
      rays: 64,
      passes: 1,
      cases: [
        { material: 'skin1', radius: 5, walls: 0 },
        { material: 'skin1', radius: 5, walls: 2 },
        { material: 'marble', radius: 5, walls: 0 },
        { material: 'wholemilk', radius: 5, walls: 0 },
        { material: 'ketchup', radius: 5, walls: 0 },
        { material: 'skin1', radius: 1, walls: 0 },
      ],
    })),
  );
if (wanted('grading')) tables.push(await benchGrading(device, { repeats: quick ? 3 : 9 }));
if (wanted('widgets'))
  tables.push(
    await benchWidgets({
      repeats: quick ? 3 : 9,
      only: process.argv
        .find((a) => a.startsWith('--only-widgets='))
        ?.slice('--only-widgets='.length)
        .split(',')
        .filter(Boolean),
    }),
  );
if (wanted('pages')) tables.push(...(await benchPages({ dist, repeats: quick ? 1 : 3 })));
if (wanted('interaction'))
  tables.push(...(await benchInteraction(interactionOptionsFromArgs(process.argv, quick ? 3 : 5))));
if (wanted('scenes'))
  tables.push(
    await benchScenes(device, {
      size: quick ? 24 : 48,
      spp: quick ? 16 : 64,
      samplesPerPass: quick ? 4 : 8,
      cpuSpp: quick ? 1 : 4,
    }),
  );
// Mitsuba 3 as a peer: only when asked for by name (it installs Mitsuba into .cache/peers).
if (only?.includes('peers'))
  tables.push(
    await benchPeers(device, {
      size: 64,
      spp: quick ? 16 : 64,
      samplesPerPass: quick ? 4 : 16,
      mitsubaImages: quick ? 4 : 8,
      processes: !process.argv.includes('--no-processes'),
    }),
  );
if (wanted('startup'))
  tables.push(
    await benchStartup({
      runs: quick ? 3 : 5,
      scenes: quick ? 2 : 5,
      ...(baseline ? { baseline } : {}),
    }),
  );
if (wanted('photons'))
  tables.push(
    await benchPhotons(device, {
      photonCounts: quick ? [4096, 65536] : [4096, 16384, 65536, 262144],
      radii: quick ? [0.04] : [0.08, 0.04, 0.02],
      spp: quick ? [4, 64] : [4, 16, 64, 256, 1024],
      repeats: quick ? 1 : 3,
    }),
  );
if (wanted('neural')) {
  // The neural field's default problem in the widget (its preset, chapter 8); quick mode
  // trains each model for 15 s instead of 60 s.
  const seconds = numberArg('seconds', quick ? 15 : 60);
  tables.push(
    ...(await benchNeural(device, {
      seconds,
      checkpoints: [5, 10, 15, 20, 30, 45, 60, 90, 120, 180, 240]
        .filter((c) => c < seconds)
        .concat(seconds),
      views: numberArg('views', 4),
      batch: numberArg('batch', 256),
      steps: numberArg('steps', 16),
      learningRate: numberArg('rate', 0.05),
      tableLog2: numberArg('table', 12),
      resolution: numberArg('grid', 32),
      repeats: quick ? 3 : 5,
    })),
  );
}
for (const table of tables) printTable(table);
const path = new URL('./results/latest.json', import.meta.url).pathname;
saveTables(path, tables, {
  date: new Date().toISOString(),
  device:
    'Dawn (webgpu npm package) for the library; Chromium WebGPU for the widgets; SwiftShader on machines without a GPU',
  command: `npm run bench -- ${process.argv.slice(2).join(' ')}`.trim(),
});
console.log(`\nWrote ${path}`);
await releaseNodeDevice();
