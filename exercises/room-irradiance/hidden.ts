// One ray of the irradiance in the room: hidden tests. Radiances, angles and indices are
// drawn from the grading seed (src/grading/checks/generated.ts), so neither a table of the
// public inputs nor a constant passes.
import type { CheckSpec } from '../../src/grading/exercise.ts';
import { caseSampler } from '../../src/grading/checks/generated.ts';

const f = Math.fround;
const HIDDEN_TOLERANCE = { rtol: 1e-5, atol: 1e-7 } as const;

export const HIDDEN_CHECKS: readonly CheckSpec[] = [
  {
    kind: 'generated-cases',
    name: 'Any ray',
    points: 2,
    message: 'For some radiances, angles or indices your estimate is off: π (1 − F_r(cos θ, η)) L.',
    ...HIDDEN_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'room irradiance any');
      return Array.from({ length: 16 }, (_, k) => ({
        label: `ray ${k + 1}`,
        args: [f(r.logUniform(0.01, 20)), f(r.uniform(0.02, 1)), f(r.uniform(1.05, 1.6))],
      }));
    },
  },
  {
    kind: 'generated-cases',
    name: 'Grazing rays and η = 1',
    points: 1,
    message:
      'Near grazing incidence almost everything is reflected, and with η = 1 nothing is: the ' +
      'estimate is then π L exactly.',
    ...HIDDEN_TOLERANCE,
    generate: (seed) => {
      const r = caseSampler(seed, 'room irradiance edges');
      const radiance = f(r.logUniform(0.1, 10));
      return [
        { label: 'grazing', args: [radiance, f(r.uniform(0.001, 0.02)), f(r.uniform(1.05, 1.6))] },
        { label: 'η = 1', args: [radiance, f(r.uniform(0.05, 1)), 1] },
        { label: 'partner', args: [radiance, f(r.uniform(0.3, 1)), f(r.uniform(1.05, 1.6))] },
      ];
    },
  },
];
