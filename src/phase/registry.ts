// The phase functions a scene medium can have (README "Scenes", `phase`), each defined
// once, here. Everything else derives from this list:
// - the scene JSON: the `type` names and their parameters with ranges (validate.ts reads
//   them with the same messages as every other field; types.ts's PhaseDescription);
// - the packed record the renderer reads (packPhase: the entry's index is the numeric
//   tag, parameter k goes to value k);
// - the plan: the `@if` condition that links the entry's code into a specialized kernel
//   (plan.ts CONDITION_NAMES and GENERAL_CONDITIONS take PHASE_CONDITIONS);
// - the CPU twin's dispatch (src/reference/integrator.ts mediumPhaseEval/Sample calls
//   `twin`), and the WGSL dispatch, which stays hand-written WGSL in
//   shaders/integrator.wesl (mediumPhaseEval/mediumPhaseSample) because the kernels are
//   linked from plain .wesl files. tests/reference/phase-registry.test.ts fails unless
//   every entry has its SCENE_PHASE_* constant equal to its index there and a case under
//   its condition that returns exactly `wgsl.eval`/`wgsl.sample`, calling library
//   functions that have twins; tests/shaders/phase-dispatch.test.ts runs that dispatch
//   on the GPU against the twin for every entry's examples.
//
// The first entry is the default (a medium without `phase`) and the fallback of the
// WGSL dispatch: it needs no condition, and a kind whose condition a kernel was not
// linked with scatters as it (the planner never lets that happen).
//
// Tabulated phase functions (issue 21, e.g. Mie from a table) plug in as one more entry
// that uses PhaseRecord.table: PhaseParameter gains a kind ('real', as now, or
// 'table'); a table parameter's JSON value names a file under public/ (checked like grid
// files in validate.ts, read by load.ts into the resolved scene); pack.ts appends the
// tables to one phase-table storage buffer, which a new integrator binding exposes under
// the entry's condition, and packPhase writes the table's offset; the entry's WGSL
// eval/sample read the table from that offset, and its twin reads the same array (which
// SceneData then carries next to the density grid).
import { sampleUniformSphere, type Vec3 } from '../reference/directions.ts';
import {
  hgEvalDirections,
  hgSample,
  phaseIsotropic,
  rayleighEval,
  rayleighSample,
} from '../reference/phase.ts';

/** Real parameters of one phase function in the packed record (ScenePhase.values). */
export const PHASE_MAX_VALUES = 3;

/**
 * A medium's phase function as the renderer reads it (integrator.wesl ScenePhase): the
 * tag (index of the entry in PHASE_FUNCTIONS), up to PHASE_MAX_VALUES real parameters
 * (f32 in the record; unused ones 0) and the offset of its table in the phase-table
 * buffer of tabulated entries (0 for analytic ones).
 */
export interface PhaseRecord {
  kind: number;
  values: readonly [number, number, number];
  table: number;
}

/** One real parameter: its JSON key and allowed range (bounds included). */
export interface PhaseParameter<Name extends string = string> {
  name: Name;
  min: number;
  max: number;
  unit?: string;
  /** For README-style documentation and error context. */
  description: string;
}

/** Plan condition names of phase functions (`@if(...)` in integrator.wesl). */
type PhaseConditionName = `phase${string}`;

export interface PhaseFunctionDefinition<
  Id extends string = string,
  Name extends string = string,
  Condition extends PhaseConditionName | null = PhaseConditionName | null,
> {
  /** The scene JSON's `phase.type`. */
  id: Id;
  /** Its name in the plan's text, e.g. "Henyey–Greenstein". */
  label: string;
  /** In the order they are packed into PhaseRecord.values. */
  parameters: readonly PhaseParameter<Name>[];
  /** The WESL condition that links its code (null: always linked, the fallback). */
  condition: Condition;
  /**
   * The WGSL side in shaders/integrator.wesl: the tag constant and the exact expression
   * each case of mediumPhaseEval (scope: medium, wo, wi) and mediumPhaseSample (scope:
   * medium, wo, u) returns; medium.phase is the ScenePhase of the record.
   */
  wgsl: { tag: string; eval: string; sample: string };
  /** The float64 twin of those two expressions (the same library functions' twins). */
  twin: {
    eval(phase: PhaseRecord, wo: Vec3, wi: Vec3): number;
    sample(phase: PhaseRecord, wo: Vec3, u: readonly [number, number]): Vec3;
  };
  /** Parameter sets the tests sample and compare across GPU and twin. */
  examples: readonly Readonly<Record<Name, number>>[];
}

/** Keeps the literal types of an entry (its id, parameter names and condition). */
function definePhase<
  const Id extends string,
  const Name extends string,
  const Condition extends PhaseConditionName | null,
>(
  definition: PhaseFunctionDefinition<Id, Name, Condition>,
): PhaseFunctionDefinition<Id, Name, Condition> {
  if (definition.parameters.length > PHASE_MAX_VALUES)
    throw new Error(`${definition.id}: at most ${PHASE_MAX_VALUES} parameters fit the record`);
  return definition;
}

/**
 * |g| of Henyey–Greenstein a scene may ask for (shaders/phase.wesl HG_MAX_ABS_G clamps
 * to the f32 of this; the scene refuses more rather than clamping silently).
 */
export const HG_G_LIMIT = 0.99999;

export const PHASE_FUNCTIONS = [
  definePhase({
    id: 'isotropic',
    label: 'isotropic',
    parameters: [],
    condition: null,
    wgsl: {
      tag: 'SCENE_PHASE_ISOTROPIC',
      eval: 'phaseIsotropic()',
      sample: 'sampleUniformSphere(u)',
    },
    twin: {
      eval: () => phaseIsotropic(),
      sample: (_phase, _wo, u) => sampleUniformSphere(u),
    },
    examples: [{}],
  }),
  definePhase({
    id: 'henyey-greenstein',
    label: 'Henyey–Greenstein',
    parameters: [
      {
        name: 'g',
        min: -HG_G_LIMIT,
        max: HG_G_LIMIT,
        description: 'asymmetry parameter, the mean cosine of the scattering angle',
      },
    ],
    condition: 'phaseHg',
    wgsl: {
      tag: 'SCENE_PHASE_HG',
      eval: 'hgEvalDirections(medium.phase.values.x, wo, wi)',
      sample: 'hgSample(medium.phase.values.x, wo, u).wi',
    },
    twin: {
      eval: (phase, wo, wi) => hgEvalDirections(phase.values[0], wo, wi),
      sample: (phase, wo, u) => hgSample(phase.values[0], wo, u).wi,
    },
    examples: [{ g: 0.3 }, { g: -0.6 }, { g: 0.9 }],
  }),
  definePhase({
    id: 'rayleigh',
    label: 'Rayleigh',
    parameters: [],
    condition: 'phaseRayleigh',
    wgsl: {
      tag: 'SCENE_PHASE_RAYLEIGH',
      eval: 'rayleighEval(-dot(wo, wi))',
      sample: 'rayleighSample(wo, u).wi',
    },
    twin: {
      eval: (_phase, wo, wi) => rayleighEval(-(wo[0] * wi[0] + wo[1] * wi[1] + wo[2] * wi[2])),
      sample: (_phase, wo, u) => rayleighSample(wo, u).wi,
    },
    examples: [{}],
  }),
] as const;

type Entry = (typeof PHASE_FUNCTIONS)[number];
type Simplify<T> = { [K in keyof T]: T[K] } & {};
type DescriptionOf<E> =
  E extends PhaseFunctionDefinition<infer Id, infer Name, PhaseConditionName | null>
    ? Simplify<{ type: Id } & { [K in Name]: number }>
    : never;

export type PhaseId = Entry['id'];
/** A medium's `phase` in the scene JSON, one variant per entry. */
export type PhaseDescription = DescriptionOf<Entry>;
export type PhaseCondition = NonNullable<Entry['condition']>;

export const PHASE_IDS: readonly PhaseId[] = PHASE_FUNCTIONS.map((entry) => entry.id);

/** The condition names of the entries that have one, in registry order. */
export const PHASE_CONDITIONS: readonly PhaseCondition[] = PHASE_FUNCTIONS.flatMap((entry) =>
  entry.condition === null ? [] : [entry.condition],
);

/** The default phase function (a medium without `phase`) and the dispatch's fallback. */
export const DEFAULT_PHASE: PhaseDescription = { type: PHASE_FUNCTIONS[0].id };

export function phaseEntry(id: PhaseId): PhaseFunctionDefinition {
  const entry = PHASE_FUNCTIONS.find((e) => e.id === id);
  if (!entry) throw new Error(`unknown phase function ${id}`);
  return entry;
}

/** The numeric tag of a phase function: its index in PHASE_FUNCTIONS. */
export function phaseTag(id: PhaseId): number {
  return PHASE_FUNCTIONS.findIndex((e) => e.id === id);
}

/** The packed record of a validated description: tag, parameters in schema order. */
export function packPhase(description: PhaseDescription): PhaseRecord {
  const entry = phaseEntry(description.type);
  const named = description as Readonly<Record<string, number | string>>;
  const values: [number, number, number] = [0, 0, 0];
  entry.parameters.forEach((parameter, k) => {
    values[k] = Number(named[parameter.name]);
  });
  return { kind: phaseTag(description.type), values, table: 0 };
}

/**
 * The entry a record dispatches to in a kernel linked with `conditions`: its own when
 * its condition is on (or it has none), else the fallback, as the WGSL dispatch does.
 */
export function dispatchedPhase(
  kind: number,
  conditions: Readonly<Record<string, boolean>>,
): PhaseFunctionDefinition {
  const entry: PhaseFunctionDefinition | undefined = PHASE_FUNCTIONS[kind];
  if (entry && (entry.condition === null || conditions[entry.condition] === true)) return entry;
  return PHASE_FUNCTIONS[0];
}
