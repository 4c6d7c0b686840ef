// Every WGSL the project produces, compiled by a second engine: wgpu's naga (the
// shader compiler of Firefox) through Deno, next to Dawn's Tint that every other test
// uses. Firefox students run the same kernels and grade in the page, so a program
// only Tint accepts is a broken widget or exercise there (issue 16).
//
// The sources, linked here in Node exactly as the book links them:
// - every kernel in shaders/kernels/ (as the widgets link it, no conditions);
// - the scene kernel under the plan of every example scene in public/scenes/, the
//   general conditions, each condition alone, every pair of conditions, none and all;
// - every static kernel file the build writes for the pages (src/book/build/
//   staticKernels.ts: the plans of the widgets' settings too), where not already above;
// - every library module linked as a root (all of its functions), under no
//   conditions and under the general ones;
// - the evaluation kernel of every library function the command line can evaluate
//   (`npm run cli -- eval`, generateKernel/specFor);
// - every exercise as the grader assembles it: the reference, the starter and each
//   known-wrong submission meant to compile, with the helpers, the instrumented loops
//   and the harness. These are captured from a real grading run on Dawn by a device
//   that records every createShaderModule, so the test sees what grade.ts compiles,
//   not a copy of its assembly.
// One Deno process compiles them all and builds every compute pipeline and a render
// pipeline for every vertex and fragment entry; one Vitest test per source.
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { beforeAll, describe, expect, it } from 'vitest';
import { EXERCISE_IDS } from '../../exercises/index.ts';
import { linkStaticKernels } from '../../src/book/build/staticKernels.ts';
import {
  UnsupportedSignatureError,
  functionsOf,
  generateKernel,
  specFor,
} from '../../src/gpu/functionEvaluator.ts';
import { linkKernel, linkLibraryKernel } from '../../src/gpu/link.ts';
import { gradeReference, gradeSubmission } from '../../src/grading/grade.ts';
import { loadFullExercise, wrongSubmissions } from '../../src/grading/node.ts';
import { linkSceneKernel } from '../../src/scene/gpuRenderer.ts';
import { loadSceneFile, PUBLIC_DIRECTORY } from '../../src/scene/loadNode.ts';
import {
  CONDITION_NAMES,
  GENERAL_CONDITIONS,
  plan,
  type ConditionName,
  type Conditions,
} from '../../src/scene/plan.ts';
import { runOnWgpu, type CompileRequest, type WgpuAnswer } from '../support/denoGpu.ts';
import { nodeDevice } from '../support/nodeGpu.ts';
import { SHADER_LIBRARY } from '../support/shaderLibrary.ts';
import { pipelinesFor } from '../support/wgslEntryPoints.ts';

const library = SHADER_LIBRARY;
const kernelPaths = Object.keys(library)
  .filter((path) => path.startsWith('kernels/'))
  .sort();
const modulePaths = Object.keys(library)
  .filter((path) => !path.includes('/'))
  .sort();
const SCENE_KERNEL = 'kernels/scene-render.wesl';

function conditionsWith(on: readonly ConditionName[]): Conditions {
  return Object.fromEntries(CONDITION_NAMES.map((name) => [name, on.includes(name)])) as Conditions;
}

/** The scene kernel variants: example scenes' plans, general, each alone, none, all. */
async function sceneVariants(): Promise<{ name: string; conditions: Conditions }[]> {
  const folder = join(PUBLIC_DIRECTORY, 'scenes');
  const scenes = readdirSync(folder)
    .filter((file) => file.endsWith('.json'))
    .sort();
  const variants: { name: string; conditions: Conditions }[] = [];
  for (const file of scenes) {
    const resolved = await loadSceneFile(join(folder, file));
    variants.push({ name: `plan of scenes/${file}`, conditions: plan(resolved.scene).conditions });
  }
  variants.push({ name: 'general conditions', conditions: GENERAL_CONDITIONS });
  variants.push({ name: 'no condition', conditions: conditionsWith([]) });
  for (const name of CONDITION_NAMES)
    variants.push({ name: `only ${name}`, conditions: conditionsWith([name]) });
  // Every pair: a condition's code may use another's (e.g. @if(gridMedia && !…)), and the
  // widgets plan scenes from their controls, so pairs the examples miss do occur.
  CONDITION_NAMES.forEach((first, i) =>
    CONDITION_NAMES.slice(i + 1).forEach((second) =>
      variants.push({
        name: `only ${first} and ${second}`,
        conditions: conditionsWith([first, second]),
      }),
    ),
  );
  variants.push({ name: 'every condition', conditions: conditionsWith(CONDITION_NAMES) });
  return variants;
}

/** A device that records the WGSL of every shader module created through it. */
function recordingDevice(device: GPUDevice, sink: string[]): GPUDevice {
  return new Proxy(device, {
    get(target, key) {
      if (key === 'createShaderModule')
        return (descriptor: GPUShaderModuleDescriptor) => {
          sink.push(descriptor.code);
          return target.createShaderModule(descriptor);
        };
      const value: unknown = Reflect.get(target, key, target);
      return typeof value === 'function'
        ? (value as (...a: unknown[]) => unknown).bind(target)
        : value;
    },
  });
}

/** Sources that could not be gathered (each fails the coverage test). */
const setupProblems: string[] = [];

/** What the grader compiles for each exercise: reference, starter, compiling wrong ones. */
async function graderSources(): Promise<{ name: string; code: string }[]> {
  const device = await nodeDevice();
  const sources: { name: string; code: string }[] = [];
  for (const id of EXERCISE_IDS) {
    const exercise = await loadFullExercise(id);
    // The reference links its imports with WESL (gradeReference); a submission's imports
    // are not linked (the helpers are in front of it), so it goes through gradeSubmission.
    const referenceCode: string[] = [];
    await gradeReference(recordingDevice(device, referenceCode), library, exercise, {
      which: 'public',
    });
    if (referenceCode.length === 0) setupProblems.push(`${id}: the reference was not compiled`);
    referenceCode.forEach((code, k) =>
      sources.push({ name: `exercise ${id}, reference solution: program ${k + 1}`, code }),
    );
    let wrong: { label: string; source: string }[] = [];
    try {
      wrong = wrongSubmissions(id)
        .filter((w) => w.status !== 'compile-error' && w.status !== 'wrong-signature')
        .map((w) => ({ label: `wrong/${w.file}`, source: w.source }));
    } catch (error) {
      // Reported by its own test below; the other sources are still compiled.
      setupProblems.push(`${id}: ${(error as Error).message}`);
    }
    const submissions = [{ label: 'starter', source: exercise.starter }, ...wrong];
    for (const { label, source } of submissions) {
      const recorded: string[] = [];
      // Public checks only: enough to compile every program; the checks' results are
      // the grading tests' business.
      await gradeSubmission(recordingDevice(device, recorded), library, exercise, source, {
        which: 'public',
      });
      // A known-wrong submission may be refused before compiling (e.g. extra bindings).
      if (recorded.length === 0 && label === 'starter')
        setupProblems.push(`${id}: the starter was not compiled`);
      recorded.forEach((code, k) =>
        sources.push({ name: `exercise ${id}, ${label}: program ${k + 1}`, code }),
      );
    }
  }
  // The reference appears once per grading run (it is cached per device, but each
  // recording device is new); keep one copy of each distinct program.
  const seen = new Set<string>();
  return sources.filter(({ code }) => !seen.has(code) && (seen.add(code), true));
}

/** The WGSL of every static kernel file the book's build writes. */
const staticKernelCodes: string[] = [];

async function allSources(): Promise<CompileRequest[]> {
  const sources: { name: string; code: string }[] = [];
  for (const path of kernelPaths) {
    if (path === SCENE_KERNEL) continue;
    sources.push({ name: `kernel ${path}`, code: await linkLibraryKernel(library, path) });
  }
  for (const variant of await sceneVariants())
    sources.push({
      name: `kernel ${SCENE_KERNEL}, ${variant.name}`,
      code: await linkSceneKernel(library, variant.conditions),
    });
  const root = fileURLToPath(new URL('../..', import.meta.url));
  const linked = new Set(sources.map((source) => source.code));
  for (const variant of await linkStaticKernels(root, 'assets', library)) {
    staticKernelCodes.push(variant.code);
    if (linked.has(variant.code)) continue;
    linked.add(variant.code);
    sources.push({ name: `static kernel ${variant.key}`, code: variant.code });
  }
  for (const path of modulePaths) {
    const source = library[path] as string;
    sources.push({ name: `module ${path}`, code: await linkKernel(library, source) });
    if (/@if\(/.test(source))
      sources.push({
        name: `module ${path}, general conditions`,
        code: await linkKernel(library, source, { ...GENERAL_CONDITIONS }),
      });
  }
  for (const path of modulePaths) {
    const module = path.replace(/\.wesl$/, '');
    for (const signature of functionsOf(library, module)) {
      try {
        const spec = specFor(signature);
        sources.push({
          name: `cli eval ${module}.${signature.fn}`,
          code: await linkKernel(library, generateKernel(spec, 1)),
        });
      } catch (error) {
        if (!(error instanceof UnsupportedSignatureError)) throw error;
      }
    }
  }
  sources.push(...(await graderSources()));
  return sources.map((source) => ({ ...source, ...pipelinesFor(source.code) }));
}

// Linked at collection time (top-level await), so that each source is a test of its own.
const requests = await allSources();
let answer: WgpuAnswer | null = null;

beforeAll(async () => {
  answer = await runOnWgpu({ compile: requests });
}, 240_000);

describe('every WGSL source compiles under naga (wgpu, as in Firefox)', () => {
  it('covers the kernels, the scene variants, the modules and the exercises', () => {
    const names = requests.map((r) => r.name);
    for (const path of kernelPaths)
      expect(
        names.some((n) => n.startsWith(`kernel ${path}`)),
        path,
      ).toBe(true);
    for (const path of modulePaths) expect(names, path).toContain(`module ${path}`);
    const codes = new Set(requests.map((r) => r.code));
    expect(staticKernelCodes.length).toBeGreaterThan(kernelPaths.length);
    expect(staticKernelCodes.filter((code) => !codes.has(code))).toEqual([]);
    for (const id of EXERCISE_IDS)
      expect(
        names.some((n) => n.startsWith(`exercise ${id}, reference`)),
        id,
      ).toBe(true);
    expect(setupProblems).toEqual([]);
    expect(answer?.compile.length).toBe(requests.length);
    expect(answer?.lost ?? null).toBeNull();
  });

  requests.forEach((request, index) => {
    const pipelines = (request.compute?.length ?? 0) + (request.render?.length ?? 0);
    it(`${request.name}${pipelines > 0 ? ` (+${pipelines} pipelines)` : ''}`, () => {
      const result = answer?.compile[index];
      expect(result?.name, 'naga answered for this source').toBe(request.name);
      const problems = [
        ...(result?.messages ?? [])
          .filter((m) => m.type === 'error')
          .map((m) => `${m.line}:${m.column} ${m.message}`),
        ...(result?.pipelines ?? [])
          .filter((p) => p.error !== null)
          .map((p) => `${p.kind} pipeline ${p.entry}: ${p.error}`),
      ];
      expect(problems, `naga on ${request.name}`).toEqual([]);
    });
  });
});
