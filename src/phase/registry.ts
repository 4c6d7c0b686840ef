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
// Tabulated phase functions (issue 21): an entry with `tabulate` (Lorenz–Mie, `mie`) is
// still described by real parameters; at pack time packPhases builds its table from them
// with the float64 twin (src/reference/mie.ts, cached per parameter values), appends it to
// one phase-table buffer (f32, PHASE_TABLE_WORDS per table, shaders/mie.wesl PhaseTable)
// and writes the table's index to PhaseRecord.table. The kernel binds that buffer as
// integrator.wesl scenePhaseTables (binding 5, declared and read only under the entry's
// condition), and the entry's WGSL case first makes the invocation's private copy
// `scenePhaseTable` hold the record's table (scenePhaseTableLoad: copied only when it
// holds another), which its eval/sample expressions pass by pointer; the twin reads the
// same f32 words (SceneData.phaseTables, phaseTableAt).
// Tables rather than files under public/ because the table is a pure function of three
// numbers that the twin computes in ≈ 10–40 ms; a scene then stays self-contained.
import { sampleUniformSphere, type Vec3 } from '../reference/directions.ts';
import {
  mieTabulatePhase,
  PHASE_TABLE_NODES,
  phaseTabulatedEvalDirections,
  phaseTabulatedSample,
  type PhaseTable,
} from '../reference/mie.ts';
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
 * (f32 in the record; unused ones 0) and the index of its table in the phase-table
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
   * medium, wo, u) returns; medium.phase is the ScenePhase of the record. A tabulated
   * entry's case first loads its table (PHASE_TABLE_LOAD) into `scenePhaseTable`.
   */
  wgsl: { tag: string; eval: string; sample: string };
  /**
   * The float64 twin of those two expressions (the same library functions' twins);
   * `tables` is the packed phase-table buffer (packPhases), which only tabulated
   * entries read.
   */
  twin: {
    eval(phase: PhaseRecord, wo: Vec3, wi: Vec3, tables: Float32Array): number;
    sample(phase: PhaseRecord, wo: Vec3, u: readonly [number, number], tables: Float32Array): Vec3;
  };
  /**
   * Tabulated entries only: the float64 table of the parameter values (in `parameters`
   * order), which packPhases rounds to f32 into the phase-table buffer.
   */
  tabulate?: (values: readonly number[]) => PhaseTable;
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

/**
 * Largest Mie size parameter x = 2πr/λ a scene may ask for. Building the table (the series
 * has ≈ x + 4x^{1/3} terms, summed at up to 16 angles per node) took ≈ 30 ms at x = 200
 * here, ≈ 150 ms at 500 and 400 ms at 1000; the factor by which mieTabulatePhase rescales
 * the 513 node values to ∫p dω = 1 (its `normalization`, a measure of how well the nodes
 * resolve the lobe) is 1.001 at x = 200, 1.005 at 1000. A fog or cloud droplet of radius
 * 5 µm in green light (λ = 0.55 µm) has x ≈ 57.
 */
export const MIE_SIZE_PARAMETER_MAX = 200;

/**
 * The WGSL statement a tabulated entry's case runs before it returns: the invocation's
 * private copy `scenePhaseTable` made to hold the record's table, which the mie.wesl
 * functions take by pointer (WGSL passes no pointer into a storage buffer to a function).
 */
export const PHASE_TABLE_LOAD = 'scenePhaseTableLoad(medium.phase.table);';

/** f32 words of one table in the phase-table buffer (shaders/mie.wesl PhaseTable). */
export const PHASE_TABLE_WORDS = 4 * PHASE_TABLE_NODES;

/** Memoised f64 views of tables in a phase-table buffer, per buffer and table index. */
const tableViews = new WeakMap<Float32Array, Map<number, PhaseTable>>();

/**
 * Table `index` of a packed phase-table buffer as the twin's PhaseTable: the f32 words the
 * GPU reads (columns 1 − μ, 1 + μ, p, C of PHASE_TABLE_NODES each), widened to f64.
 */
export function phaseTableAt(tables: Float32Array, index: number): PhaseTable {
  let views = tableViews.get(tables);
  if (!views) tableViews.set(tables, (views = new Map()));
  let table = views.get(index);
  if (!table) {
    const base = index * PHASE_TABLE_WORDS;
    if (!(base + PHASE_TABLE_WORDS <= tables.length))
      throw new RangeError(`phase table ${index} is not in a buffer of ${tables.length} words`);
    const column = (c: number): Float64Array =>
      Float64Array.from(
        tables.subarray(base + c * PHASE_TABLE_NODES, base + (c + 1) * PHASE_TABLE_NODES),
      );
    table = { oneMinusMu: column(0), onePlusMu: column(1), pdf: column(2), cdf: column(3) };
    views.set(index, table);
  }
  return table;
}

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
  definePhase({
    id: 'mie',
    label: 'Lorenz–Mie (tabulated)',
    parameters: [
      {
        name: 'sizeParameter',
        min: 0.01,
        max: MIE_SIZE_PARAMETER_MAX,
        description: 'size parameter x = 2πr/λ of the spheres (λ in the surrounding medium)',
      },
      {
        name: 'indexReal',
        min: 1.01,
        max: 3,
        description: 'real part n of the relative refractive index m = n + iκ',
      },
      {
        name: 'indexImaginary',
        min: 0,
        max: 10,
        description: 'imaginary part κ ≥ 0 of the relative refractive index (absorption)',
      },
    ],
    condition: 'phaseMie',
    wgsl: {
      tag: 'SCENE_PHASE_MIE',
      eval: 'phaseTabulatedEvalDirections(&scenePhaseTable, wo, wi)',
      sample: 'phaseTabulatedSample(&scenePhaseTable, wo, u).wi',
    },
    twin: {
      eval: (phase, wo, wi, tables) =>
        phaseTabulatedEvalDirections(phaseTableAt(tables, phase.table), wo, wi),
      sample: (phase, wo, u, tables) =>
        phaseTabulatedSample(phaseTableAt(tables, phase.table), wo, u).wi,
    },
    tabulate: ([x, n, kappa]) => mieTabulatePhase(x!, { n: n!, kappa: kappa! }),
    // Bohren & Huffman's sphere (x = 3, m = 1.55, BH §4.4); a water fog droplet
    // (r ≈ 1.75 µm at λ = 0.55 µm: x = 20, m = 1.33); small absorbing soot (m = 1.75 + 0.44i).
    examples: [
      { sizeParameter: 3, indexReal: 1.55, indexImaginary: 0 },
      { sizeParameter: 20, indexReal: 1.33, indexImaginary: 0 },
      { sizeParameter: 0.5, indexReal: 1.75, indexImaginary: 0.44 },
    ],
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

/**
 * The packed record of a validated description: tag, parameters in schema order, and
 * `table`, the index of its table in the phase-table buffer (packPhases; 0 for analytic
 * entries).
 */
export function packPhase(description: PhaseDescription, table = 0): PhaseRecord {
  const entry = phaseEntry(description.type);
  const named = description as Readonly<Record<string, number | string>>;
  const values: [number, number, number] = [0, 0, 0];
  entry.parameters.forEach((parameter, k) => {
    values[k] = Number(named[parameter.name]);
  });
  return { kind: phaseTag(description.type), values, table };
}

/** The phase functions of a scene's media, packed: what the kernel and the twin read. */
export interface PackedPhases {
  /** One per description, in order. */
  records: PhaseRecord[];
  /** The phase-table buffer: PHASE_TABLE_WORDS f32 per distinct tabulated description. */
  tables: Float32Array<ArrayBuffer>;
}

/** Tables (f32 words) built recently, by entry and parameter values. */
const TABLE_CACHE_SIZE = 8;
const tableCache = new Map<string, Float32Array>();

/** The f32 words of the table of a tabulated entry at `values`, built once per values. */
function tableWords(entry: PhaseFunctionDefinition, values: readonly number[]): Float32Array {
  const key = `${entry.id}:${values.join(',')}`;
  const cached = tableCache.get(key);
  if (cached) {
    tableCache.delete(key);
    tableCache.set(key, cached);
    return cached;
  }
  const table = entry.tabulate!(values);
  const words = new Float32Array(PHASE_TABLE_WORDS);
  [table.oneMinusMu, table.onePlusMu, table.pdf, table.cdf].forEach((column, c) =>
    words.set(column, c * PHASE_TABLE_NODES),
  );
  tableCache.set(key, words);
  while (tableCache.size > TABLE_CACHE_SIZE) tableCache.delete(tableCache.keys().next().value!);
  return words;
}

/**
 * Packs the media's phase functions: records in order, and the table of each distinct
 * tabulated description (equal parameters share one) appended to the phase-table buffer.
 */
export function packPhases(descriptions: readonly PhaseDescription[]): PackedPhases {
  const keys: string[] = [];
  const columns: Float32Array[] = [];
  const records = descriptions.map((description) => {
    const entry = phaseEntry(description.type);
    if (!entry.tabulate) return packPhase(description);
    const values = packPhase(description).values.slice(0, entry.parameters.length);
    const key = `${entry.id}:${values.join(',')}`;
    let index = keys.indexOf(key);
    if (index < 0) {
      index = keys.push(key) - 1;
      columns.push(tableWords(entry, values));
    }
    return packPhase(description, index);
  });
  const tables = new Float32Array(columns.length * PHASE_TABLE_WORDS);
  columns.forEach((words, i) => tables.set(words, i * PHASE_TABLE_WORDS));
  return { records, tables };
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
