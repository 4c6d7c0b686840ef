// Every (kernel, conditions) variant the book's pages and the command line link, so
// that the build can link each one into a static WGSL file (staticKernels.ts).
// Derived, not listed by hand:
// - every kernel in shaders/kernels/ whose code does not depend on link conditions, once,
//   with none (that is how every widget links them);
// - every kernel whose code does depend on them (the scene kernel: @if in integrator.wesl),
//   under the plan (src/scene/plan.ts) of every scene the book can show: each scene
//   widget's scene at every choice value crossed with each number's minimum, default and
//   maximum (a plan depends on numbers only through zero tests such as σs > 0 or σa > 0,
//   which the range ends and the default decide; presets and deck slides lie inside the
//   ranges); the example scenes of public/scenes/ (the command line renders them); and the general
//   conditions (the kernel that renders any scene, which single-scatter times against).
// A plan that none of these produces still renders: the page links it at run time
// (src/gpu/prelinked.ts) and says so in the console.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import {
  linkLibraryKernel,
  variantKey,
  type LinkConditions,
  type ShaderLibrary,
} from '../../gpu/link.ts';
import { CONDITION_NAMES, GENERAL_CONDITIONS, plan } from '../../scene/plan.ts';
import type { SceneDescription } from '../../scene/types.ts';
import { parseScene } from '../../scene/validate.ts';
import type { ParameterValues, WidgetEntry } from '../../widgets/parameters.ts';
import {
  buildScene as buildSingleScatterScene,
  inputsFrom as singleScatterInputs,
} from '../../widgets/single-scatter/model.ts';
import { SINGLE_SCATTER } from '../../widgets/single-scatter/schema.ts';
import {
  buildScene as buildPathTracerScene,
  inputsFrom as pathTracerInputs,
} from '../../widgets/volume-path-tracer/model.ts';
import { VOLUME_PATH_TRACER } from '../../widgets/volume-path-tracer/schema.ts';

export interface KernelVariant {
  /** Path under shaders/, e.g. `kernels/scene-render.wesl`. */
  kernel: string;
  conditions: LinkConditions;
  /** variantKey(kernel, conditions): the page looks the variant up by it. */
  key: string;
}

/** A widget that renders scenes through the planner, and the scenes it builds from its values. */
export interface SceneWidget {
  /** The widget's schema (not its widget.ts: a definition loads the element, DOM code). */
  entry: WidgetEntry;
  scenes(values: ParameterValues): SceneDescription[];
}

/**
 * The widgets that plan scenes (tests/book/kernelVariants.test.ts fails when a widget
 * folder imports the planner and is missing here). Image size, samples and seed do not
 * change a plan, so the scenes are built tiny.
 */
export const SCENE_WIDGETS: readonly SceneWidget[] = [
  {
    entry: SINGLE_SCATTER,
    scenes: (values) => [
      parseScene(
        buildSingleScatterScene(singleScatterInputs(values), {
          width: 8,
          height: 8,
          spp: 1,
          seed: 1,
        }),
      ),
    ],
  },
  {
    entry: VOLUME_PATH_TRACER,
    scenes: (values) =>
      ([1, 'unlimited'] as const).map((order) =>
        buildPathTracerScene(pathTracerInputs(values), order, { width: 8, height: 8 }, 1, 1),
      ),
  },
];

/**
 * The parameter values to plan a widget's scenes at: every choice crossed with each
 * number's minimum, default and maximum.
 */
export function parameterSamples(entry: WidgetEntry): ParameterValues[] {
  const { parameters } = entry;
  const axes = parameters.map((p) =>
    p.kind === 'choice' ? p.choices.map((c) => c.value) : [...new Set([p.min, p.default, p.max])],
  );
  const samples: ParameterValues[] = [];
  const index = axes.map(() => 0);
  for (;;) {
    samples.push(Object.fromEntries(parameters.map((p, i) => [p.name, axes[i]![index[i]!]!])));
    let axis = 0;
    while (axis < axes.length && ++index[axis]! === axes[axis]!.length) index[axis++] = 0;
    if (axis === axes.length) return samples;
  }
}

/** The scenes of public/scenes/ (JSON), validated: the command line's examples. */
export function exampleScenes(root: string): SceneDescription[] {
  const folder = join(root, 'public', 'scenes');
  return readdirSync(folder)
    .filter((file) => file.endsWith('.json'))
    .sort()
    .map((file) => parseScene(JSON.parse(readFileSync(join(folder, file), 'utf8'))));
}

const plansByRoot = new Map<string, LinkConditions[]>();

/**
 * The distinct plan conditions of every scene the book and the command line show
 * (a few thousand scenes, a few seconds: computed once per process).
 */
export function scenePlanConditions(root: string): LinkConditions[] {
  let plans = plansByRoot.get(root);
  if (!plans) {
    plans = planConditionsOf(root);
    plansByRoot.set(root, plans);
  }
  return plans;
}

function planConditionsOf(root: string): LinkConditions[] {
  const scenes = [
    ...SCENE_WIDGETS.flatMap((w) => parameterSamples(w.entry).flatMap((v) => w.scenes(v))),
    ...exampleScenes(root),
  ];
  const byKey = new Map<string, LinkConditions>();
  for (const conditions of [GENERAL_CONDITIONS, ...scenes.map((s) => plan(s).conditions)])
    byKey.set(variantKey('', conditions), conditions);
  return [...byKey.values()];
}

/** Every condition named by an @if in the library (a kernel may depend on these only). */
export function conditionsInLibrary(library: ShaderLibrary): string[] {
  const names = new Set<string>();
  for (const source of Object.values(library))
    for (const match of source.matchAll(/@(?:el)?if\s*\(([^)]*(?:\([^)]*\)[^)]*)*)\)/g))
      for (const name of match[1]!.match(/[A-Za-z_]\w*/g) ?? [])
        if (name !== 'true' && name !== 'false') names.add(name);
  return [...names].sort();
}

/**
 * Whether a kernel's linked code depends on the plan's conditions: linked with all of
 * them on and with none, it differs.
 */
async function dependsOnConditions(library: ShaderLibrary, kernel: string): Promise<boolean> {
  const all = Object.fromEntries(CONDITION_NAMES.map((name) => [name, true]));
  return (
    (await linkLibraryKernel(library, kernel, all)) !== (await linkLibraryKernel(library, kernel))
  );
}

/** Every variant to build, in a stable order (kernel path, then conditions). */
export async function kernelVariants(
  root: string,
  library: ShaderLibrary,
): Promise<KernelVariant[]> {
  // A condition the planner does not decide could not be enumerated from plans.
  const known = new Set<string>(CONDITION_NAMES);
  const unknown = conditionsInLibrary(library).filter((name) => !known.has(name));
  if (unknown.length > 0)
    throw new Error(
      `shaders use link conditions that src/scene/plan.ts does not decide: ${unknown.join(', ')}; ` +
        'src/book/build/kernelVariants.ts cannot enumerate their variants',
    );
  const kernels = Object.keys(library)
    .filter((path) => /^kernels\/[^/]+\.wesl$/.test(path))
    .sort();
  const variants: KernelVariant[] = [];
  let plans: LinkConditions[] | null = null;
  for (const kernel of kernels) {
    const conditionSets = (await dependsOnConditions(library, kernel))
      ? (plans ??= scenePlanConditions(root))
      : [{}];
    for (const conditions of conditionSets)
      variants.push({ kernel, conditions, key: variantKey(kernel, conditions) });
  }
  return variants.sort((a, b) => (a.key < b.key ? -1 : a.key > b.key ? 1 : 0));
}
