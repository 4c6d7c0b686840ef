// The phase-function registry (src/phase/registry.ts) against everything that must agree
// with it, for every entry, so that a new entry is checked without a new test:
// - shaders/integrator.wesl: a SCENE_PHASE_* constant equal to the entry's index, and in
//   mediumPhaseEval/mediumPhaseSample a case under the entry's condition that returns
//   exactly its `wgsl` expressions (the first entry is the fallback, with no condition),
//   after exactly PHASE_TABLE_LOAD for a tabulated entry and nothing for the others;
//   each function called is imported from a library module that declares it and whose
//   twin (src/reference/<module>.ts) exports it;
// - the planner's condition list and general kernel;
// - validation: each example is accepted and round-trips, each parameter is range-checked
//   with a message naming the field;
// - the float64 twin: normalisation ∫p dω = 1 by quadrature, and samples distributed as
//   the evaluation (chi-square in μ and in the azimuth), tabulated entries on the table
//   packPhases builds;
// - the old scene format: the public scenes and inline `phase` objects written before the
//   registry pack to the tags and values the old packer wrote (isotropic 0, HG 1 with g in
//   the next word, Rayleigh 2) and the twin dispatches them to the same functions.
// The GPU side of the dispatch is run in tests/shaders/phase-dispatch.test.ts.
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import {
  DEFAULT_PHASE,
  PHASE_CONDITIONS,
  PHASE_FUNCTIONS,
  PHASE_IDS,
  PHASE_TABLE_LOAD,
  PHASE_TABLE_WORDS,
  packPhase,
  packPhases,
  phaseEntry,
  phaseTag,
  type PhaseDescription,
  type PhaseRecord,
} from '../../src/phase/registry.ts';
import { sampleUniformSphere, type Vec3 } from '../../src/reference/directions.ts';
import {
  mediumPhaseEval,
  mediumPhaseSample,
  sceneMedium,
  type SceneData,
} from '../../src/reference/integrator.ts';
import {
  hgEvalDirections,
  hgSample,
  phaseIsotropic,
  rayleighEval,
  rayleighSample,
} from '../../src/reference/phase.ts';
import { rngNextFloat, rngSeed } from '../../src/reference/rng.ts';
import { loadSceneFile, PUBLIC_DIRECTORY } from '../../src/scene/loadNode.ts';
import { resolveScene } from '../../src/scene/load.ts';
import { packScene, sceneData } from '../../src/scene/pack.ts';
import { CONDITION_NAMES, GENERAL_CONDITIONS, plan } from '../../src/scene/plan.ts';
import { parseScene, validateScene } from '../../src/scene/validate.ts';
import { chiSquareSurvival } from '../../src/statistics/distributions.ts';
import {
  chiSquare,
  DirectionHistogramBuilder,
  dot,
  expectedMuCounts,
  MU_BINS,
  PHI_BINS,
  phaseBreakpoints,
  phaseOfMu,
  probability,
} from '../support/phaseStatistics.ts';

const SHADERS = fileURLToPath(new URL('../../shaders/', import.meta.url));
const INTEGRATOR = readFileSync(join(SHADERS, 'integrator.wesl'), 'utf8');

/** The body of `fn name(...)` in WGSL source, up to its closing brace at column 0. */
function functionBody(source: string, name: string): string {
  const start = source.indexOf(`fn ${name}(`);
  expect(start, `fn ${name} in integrator.wesl`).toBeGreaterThanOrEqual(0);
  const end = source.indexOf('\n}\n', start);
  return source.slice(start, end + 2);
}

interface DispatchCase {
  condition: string;
  tag: string;
  /** The statements before the return, whitespace collapsed ('' when none). */
  preamble: string;
  returned: string;
}

/**
 * `@if(cond) { if (medium.phase.kind == TAG) { [statements] return EXPR; } }` cases, and
 * the fallback.
 */
function dispatchOf(body: string): { cases: DispatchCase[]; fallback: string | undefined } {
  const pattern =
    /@if\((\w+)\)\s*\{\s*if \(medium\.phase\.kind == (\w+)\) \{\s*((?:(?!return\b)[^{};]*;\s*)*)return ([^;]+);\s*\}\s*\}/g;
  const cases = [...body.matchAll(pattern)].map((m) => ({
    condition: m[1]!,
    tag: m[2]!,
    preamble: m[3]!.replace(/\s+/g, ' ').trim(),
    returned: m[4]!.trim(),
  }));
  const fallback = /return ([^;]+);\s*\}\s*$/.exec(body)?.[1]?.trim();
  return { cases, fallback };
}

/** The functions integrator.wesl imports, with the module of each. */
function integratorImports(): Map<string, string> {
  const imports = new Map<string, string>();
  for (const m of INTEGRATOR.matchAll(/import package::(\w+)::(\{[^}]*\}|\w+);/g)) {
    for (const name of m[2]!
      .replace(/[{}\s]/g, '')
      .split(',')
      .filter(Boolean))
      imports.set(name, m[1]!);
  }
  return imports;
}

const calledFunction = (expression: string): string => /^(\w+)\(/.exec(expression)?.[1] ?? '';

describe('the registry and the WGSL dispatch of integrator.wesl agree', () => {
  const constants = new Map(
    [...INTEGRATOR.matchAll(/const (SCENE_PHASE_\w+): u32 = (\d+)u;/g)].map((m) => [
      m[1]!,
      Number(m[2]),
    ]),
  );

  it('each entry has its tag constant equal to its index, and there are no others', () => {
    PHASE_FUNCTIONS.forEach((entry, index) => {
      expect(constants.get(entry.wgsl.tag), `${entry.id}: ${entry.wgsl.tag}`).toBe(index);
      expect(phaseTag(entry.id)).toBe(index);
    });
    expect([...constants.keys()].sort()).toEqual(PHASE_FUNCTIONS.map((e) => e.wgsl.tag).sort());
  });

  it('only the first entry (the default and fallback) has no condition', () => {
    expect(PHASE_FUNCTIONS[0].condition).toBeNull();
    expect(DEFAULT_PHASE).toEqual({ type: PHASE_FUNCTIONS[0].id });
    for (const entry of PHASE_FUNCTIONS.slice(1)) expect(entry.condition, entry.id).not.toBeNull();
    expect(new Set(PHASE_IDS).size).toBe(PHASE_IDS.length);
    expect(new Set(PHASE_CONDITIONS).size).toBe(PHASE_CONDITIONS.length);
  });

  for (const [fn, field] of [
    ['mediumPhaseEval', 'eval'],
    ['mediumPhaseSample', 'sample'],
  ] as const) {
    it(`${fn}: one case per conditioned entry, in registry order, returning its wgsl.${field}`, () => {
      const { cases, fallback } = dispatchOf(functionBody(INTEGRATOR, fn));
      expect(cases).toEqual(
        PHASE_FUNCTIONS.slice(1).map((entry) => ({
          condition: entry.condition,
          tag: entry.wgsl.tag,
          preamble: entry.tabulate ? PHASE_TABLE_LOAD : '',
          returned: entry.wgsl[field],
        })),
      );
      expect(fallback).toBe(PHASE_FUNCTIONS[0].wgsl[field]);
    });
  }

  it('every @if(phase…) condition in integrator.wesl is a registry condition', () => {
    const used = new Set([...INTEGRATOR.matchAll(/@if\((phase\w+)\)/g)].map((m) => m[1]));
    expect([...used].sort()).toEqual([...PHASE_CONDITIONS].sort());
  });

  it('each called function is imported from a module that declares it, and its twin exists', async () => {
    const imports = integratorImports();
    for (const entry of PHASE_FUNCTIONS) {
      for (const expression of [entry.wgsl.eval, entry.wgsl.sample]) {
        const name = calledFunction(expression);
        const module = imports.get(name);
        expect(module, `${entry.id}: integrator.wesl imports ${name}`).toBeDefined();
        const source = readFileSync(join(SHADERS, `${module}.wesl`), 'utf8');
        expect(source, `shaders/${module}.wesl declares ${name}`).toMatch(
          new RegExp(`\\bfn ${name}\\(`),
        );
        const twin = (await import(`../../src/reference/${module}.ts`)) as Record<string, unknown>;
        expect(typeof twin[name], `src/reference/${module}.ts exports ${name}`).toBe('function');
      }
    }
  });

  it('README "Scenes" names every phase function', () => {
    const readme = readFileSync(fileURLToPath(new URL('../../README.md', import.meta.url)), 'utf8');
    const scenes = readme.slice(
      readme.indexOf('## Scenes'),
      readme.indexOf('\n## ', readme.indexOf('## Scenes') + 1),
    );
    for (const id of PHASE_IDS) expect(scenes, id).toContain(`\`${id}\``);
  });

  it('the planner lists every phase condition, and the general kernel links each', () => {
    for (const condition of PHASE_CONDITIONS) {
      expect(CONDITION_NAMES).toContain(condition);
      expect(GENERAL_CONDITIONS[condition]).toBe(true);
    }
  });
});

/** A minimal valid scene with one scattering medium of the given `phase`. */
function sceneWith(phase: unknown): Record<string, unknown> {
  return {
    image: { width: 4, height: 4 },
    samplesPerPixel: 4,
    scatteringOrder: 1,
    camera: {
      type: 'perspective',
      position: [0, 0, 5],
      target: [0, 0, 0],
      up: [0, 1, 0],
      fovY: 40,
    },
    media: [
      {
        type: 'homogeneous',
        bounds: { type: 'box', min: [-1, -1, -1], max: [1, 1, 1] },
        sigmaA: [0.1, 0.1, 0.1],
        sigmaS: [1, 1, 1],
        ...(phase === undefined ? {} : { phase }),
      },
    ],
    lights: [{ type: 'directional', direction: [0, -1, 0], irradiance: [1, 1, 1] }],
  };
}

const errorsOf = (scene: unknown): string[] => {
  const result = validateScene(scene);
  return result.ok ? [] : result.errors;
};

describe('validation and packing follow each entry’s schema', () => {
  for (const entry of PHASE_FUNCTIONS) {
    for (const example of entry.examples) {
      const phase = { type: entry.id, ...example } as PhaseDescription;
      it(`${JSON.stringify(phase)} is accepted, planned and packed in schema order`, () => {
        const result = validateScene(sceneWith(phase));
        expect(result.ok ? [] : result.errors).toEqual([]);
        if (!result.ok) return;
        expect(result.scene.media[0]?.phase).toEqual(phase);
        const conditions = plan(result.scene).conditions;
        for (const other of PHASE_FUNCTIONS)
          if (other.condition !== null)
            expect(conditions[other.condition], other.condition).toBe(other === entry);
        const { records, tables } = packPhases([phase, phase]);
        const record = records[0]!;
        expect(record.kind).toBe(phaseTag(entry.id));
        expect(record.table).toBe(0);
        expect(records[1], 'equal descriptions share a table').toEqual(record);
        expect(tables.length).toBe(entry.tabulate ? PHASE_TABLE_WORDS : 0);
        entry.parameters.forEach((p, k) => expect(record.values[k]).toBe(phase[p.name as never]));
        expect(record.values.slice(entry.parameters.length).every((v) => v === 0)).toBe(true);
      });
    }
    for (const parameter of entry.parameters) {
      it(`${entry.id}.${parameter.name} is required and range-checked`, () => {
        const example = entry.examples[0] as Record<string, number>;
        const path = `media[0].phase.${parameter.name}`;
        const rest = Object.fromEntries(
          Object.entries(example).filter(([name]) => name !== parameter.name),
        );
        expect(errorsOf(sceneWith({ type: entry.id, ...rest })).join('\n')).toContain(
          `${path}: missing`,
        );
        for (const bad of [parameter.max + 1e-3, parameter.min - 1e-3, 'x'])
          expect(
            errorsOf(sceneWith({ type: entry.id, ...example, [parameter.name]: bad })).join('\n'),
          ).toContain(`${path} = ${JSON.stringify(bad)}: must be`);
      });
    }
    it(`${entry.id} refuses unknown fields`, () => {
      expect(errorsOf(sceneWith({ ...entry.examples[0], type: entry.id, colour: 1 }))).toEqual([
        `media[0].phase.colour: unknown field (allowed: ${['type', ...entry.parameters.map((p) => p.name)].join(', ')})`,
      ]);
    });
  }

  it('an unknown type lists the registry’s ids', () => {
    expect(errorsOf(sceneWith({ type: 'fournier-forand' }))).toEqual([
      `media[0].phase.type = "fournier-forand": must be one of ${PHASE_IDS.map((id) => JSON.stringify(id)).join(', ')}`,
    ]);
  });
});

// ---------------------------------------------------------------------------
// The twin of every entry: normalisation and sampling against its own evaluation.
// ---------------------------------------------------------------------------
const WO: Vec3 = (() => {
  const v = [0.3, -0.5, 0.81];
  const n = Math.hypot(...v);
  return [v[0]! / n, v[1]! / n, v[2]! / n];
})();

const SAMPLES = 40_000;
const EXAMPLES = PHASE_FUNCTIONS.reduce((n, e) => n + e.examples.length, 0);
/** Two chi-square tests per example, family-wise α = 0.01. */
const ALPHA = 0.01 / (2 * EXAMPLES);

describe('every entry’s twin is normalised and samples its own density', () => {
  PHASE_FUNCTIONS.forEach((entry) => {
    entry.examples.forEach((example) => {
      const { records, tables } = packPhases([{ type: entry.id, ...example } as PhaseDescription]);
      const record: PhaseRecord = records[0]!;
      const p = phaseOfMu(entry, record, WO, tables);
      const breakpoints = phaseBreakpoints(entry, record, tables);
      const label = `${entry.id} ${JSON.stringify(example)}`;

      it(`${label}: ∫ p dω = 1 and p does not depend on the azimuth`, () => {
        expect(probability(p, -1, 1, breakpoints)).toBeCloseTo(1, 6);
        const rotated = phaseOfMu(entry, record, WO, tables, 0.81);
        for (const mu of [-0.8, 0, 0.6]) expect(rotated(mu)).toBeCloseTo(p(mu), 10);
      });

      it(`${label}: ${SAMPLES} samples follow p in μ (${MU_BINS} bins) and are uniform in azimuth (${PHI_BINS} bins)`, () => {
        const builder = new DirectionHistogramBuilder(WO);
        for (let i = 0; i < SAMPLES; i++) {
          const state = { value: rngSeed(i, 7) };
          builder.add(
            entry.twin.sample(record, WO, [rngNextFloat(state), rngNextFloat(state)], tables),
          );
        }
        const { mu, phi, lengthError } = builder.histogram;
        // A table's complements 1 − μ_k and 1 + μ_k are f32 words rounded separately (each
        // keeps its digits at its own end), so they sum to 2 only to f32's 6e-8 and the
        // sampled sin θ and μ make a unit vector to ≈ 3e-8.
        const lengthTolerance = entry.tabulate ? 1e-7 : 1e-12;
        expect(lengthError, 'every wi is a unit vector').toBeLessThan(lengthTolerance);
        const muStatistic = chiSquare(mu, expectedMuCounts(p, SAMPLES, breakpoints));
        expect(
          chiSquareSurvival(muStatistic, MU_BINS - 1),
          `χ² in μ = ${muStatistic}`,
        ).toBeGreaterThan(ALPHA);
        const phiStatistic = chiSquare(phi, new Array<number>(PHI_BINS).fill(SAMPLES / PHI_BINS));
        expect(
          chiSquareSurvival(phiStatistic, PHI_BINS - 1),
          `χ² in φ = ${phiStatistic}`,
        ).toBeGreaterThan(ALPHA);
      });
    });
  });

  it('the chi-square test rejects a sampler that does not follow the density', () => {
    // HG g = 0.3 evaluated, isotropic sampled: the test above must fail on such a pair.
    const hg = phaseEntry('henyey-greenstein');
    const p = phaseOfMu(hg, packPhase({ type: 'henyey-greenstein', g: 0.3 }), WO);
    const builder = new DirectionHistogramBuilder(WO);
    for (let i = 0; i < SAMPLES; i++) {
      const state = { value: rngSeed(i, 7) };
      builder.add(sampleUniformSphere([rngNextFloat(state), rngNextFloat(state)]));
    }
    const statistic = chiSquare(builder.histogram.mu, expectedMuCounts(p, SAMPLES));
    expect(chiSquareSurvival(statistic, MU_BINS - 1)).toBeLessThan(ALPHA);
  });
});

// ---------------------------------------------------------------------------
// The scene format from before the registry.
// ---------------------------------------------------------------------------
/** The tags and the dispatch the renderer had before the registry (commit 5259338). */
const OLD_TAGS = { isotropic: 0, 'henyey-greenstein': 1, rayleigh: 2 } as const;

function oldEval(phase: { type: string; g?: number }, wo: Vec3, wi: Vec3): number {
  if (phase.type === 'henyey-greenstein') return hgEvalDirections(Math.fround(phase.g!), wo, wi);
  if (phase.type === 'rayleigh') return rayleighEval(-dot(wo, wi));
  return phaseIsotropic();
}

function oldSample(phase: { type: string; g?: number }, wo: Vec3, u: [number, number]): Vec3 {
  if (phase.type === 'henyey-greenstein') return hgSample(Math.fround(phase.g!), wo, u).wi;
  if (phase.type === 'rayleigh') return rayleighSample(wo, u).wi;
  return sampleUniformSphere(u);
}

/** The packed medium's first-record words and its twin dispatch vs the old ones. */
function expectOldBehaviour(
  data: SceneData,
  index: number,
  phase: { type: string; g?: number },
): void {
  const medium = sceneMedium(data, index);
  expect(medium.phase.kind).toBe(OLD_TAGS[phase.type as keyof typeof OLD_TAGS]);
  expect(medium.phase.values).toEqual([
    phase.type === 'henyey-greenstein' ? Math.fround(phase.g!) : 0,
    0,
    0,
  ]);
  expect(medium.phase.table).toBe(0);
  for (let i = 0; i < 16; i++) {
    const state = { value: rngSeed(i, 11) };
    const u: [number, number] = [rngNextFloat(state), rngNextFloat(state)];
    const wi = sampleUniformSphere([rngNextFloat(state), rngNextFloat(state)]);
    expect(mediumPhaseEval(data, medium, WO, wi)).toBe(oldEval(phase, WO, wi));
    expect(mediumPhaseSample(data, medium, WO, u)).toEqual(oldSample(phase, WO, u));
  }
}

describe('scenes written before the registry load and dispatch as before', () => {
  const folder = join(PUBLIC_DIRECTORY, 'scenes');
  type OldScene = { media?: { phase?: { type: string; g?: number } }[] };
  const read = (file: string): OldScene =>
    JSON.parse(readFileSync(join(folder, file), 'utf8')) as OldScene;
  // The examples whose phase functions all existed before the registry (later ones, such
  // as a Mie medium, have no old behaviour to keep).
  const files = readdirSync(folder)
    .filter((file) => file.endsWith('.json'))
    .filter((file) =>
      (read(file).media ?? []).every((m) => (m.phase?.type ?? 'isotropic') in OLD_TAGS),
    );

  it('most example scenes predate the registry', () => expect(files.length).toBeGreaterThan(5));

  it.each(files)('public/scenes/%s', async (file) => {
    const json = read(file);
    const resolved = await loadSceneFile(join(folder, file));
    const data = sceneData(packScene(resolved), plan(resolved.scene).conditions);
    (json.media ?? []).forEach((medium, i) =>
      expectOldBehaviour(data, i, medium.phase ?? { type: 'isotropic' }),
    );
  });

  it.each([
    ['no phase (isotropic by default)', undefined],
    ['Henyey–Greenstein g = 0.85', { type: 'henyey-greenstein', g: 0.85 }],
    ['Henyey–Greenstein g = −0.3', { type: 'henyey-greenstein', g: -0.3 }],
    ['Rayleigh', { type: 'rayleigh' }],
    ['isotropic, explicit', { type: 'isotropic' }],
  ] as const)('%s', async (_name, phase) => {
    const resolved = await resolveScene(parseScene(sceneWith(phase)));
    const data = sceneData(packScene(resolved), GENERAL_CONDITIONS);
    expectOldBehaviour(data, 0, phase ?? { type: 'isotropic' });
  });
});
