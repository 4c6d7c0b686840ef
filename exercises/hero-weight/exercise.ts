// Hero-wavelength weight (chapter 12, colour in a medium): the public part of the exercise.
// The student writes the factor of the one-sample balance heuristic over the three channels
// (Veach 1997 §9.2.4; Wilkie et al. 2014): w_h/((1/3) p_h) with w_h = p_h/Σp, i.e. 3/Σp. The
// reference is the library's heroBalanceWeight (shaders/chromatic.wesl). Point checks only:
// the function is deterministic, and the cases separate each known mistake (1/Σp, 1/p_h, the
// power heuristic) from it by a factor of at least 1.2.
import type { ExerciseDefinition } from '../../src/grading/exercise.ts';

/** Tolerance of every case, as the statement states it. */
export const TOLERANCE = { rtol: 1e-5, atol: 0 } as const;

/** The message of a failed case check: what the factor is and the three common slips. */
export const WEIGHT_MESSAGE =
  'The factor is w_h / ((1/3)·p_h) with the balance heuristic w_h = p_h/(p0 + p1 + p2), which ' +
  'simplifies to 3/(p0 + p1 + p2), the same whichever channel is the hero. Off by exactly 3: ' +
  'the hero is chosen with probability 1/3, so its density is p_h/3, not p_h. 1/p_hero ignores ' +
  'the other channels (plain hero sampling without MIS). 3·p_h/(p0² + p1² + p2²) is the power ' +
  'heuristic; this exercise asks for the balance heuristic.';

export const EXERCISE: ExerciseDefinition = {
  id: 'hero-weight',
  chapter: '12-beyond-the-lecture',
  title: 'The hero-wavelength MIS weight',
  starter: `// Hero-wavelength sampling of a chromatic medium: a path's distances were drawn with the
// extinction of one channel, the hero (index \`hero\`, chosen uniformly among 0, 1, 2), and
// p0, p1, p2 are the densities with which each channel's own sampling would have produced
// the same path (pdfs of the path, ≥ 0). Return the factor F such that f_c · F estimates
// every channel c: the one-sample multiple-importance-sampling weight of the hero's
// technique (balance heuristic) divided by the probability density of having drawn this path.
// Return 0 when no channel could have produced the path (p0 = p1 = p2 = 0).
fn heroWeight(p0: f32, p1: f32, p2: f32, hero: u32) -> f32 {
  // Your code here.
  return 0.0;
}
`,
  signature: 'fn heroWeight(p0: f32, p1: f32, p2: f32, hero: u32) -> f32',
  hints: [
    'One-sample MIS: choose technique h with probability c_h, draw x from p_h, and estimate f(x) by w_h(x) f(x) / (c_h p_h(x)).',
    'Here c_h = 1/3 for every channel and the balance heuristic is w_h = p_h / (p0 + p1 + p2).',
    'Multiply it out: p_h cancels. Guard the sum before dividing.',
  ],
  gradingNotes:
    'Each case passes when |F − F_ref| ≤ 1e-5·|F_ref|. Public: equal pdfs and three sets of ' +
    'different pdfs with each channel as the hero. Hidden checks draw pdfs from the grading seed ' +
    'over many decades, with a channel that cannot produce the path (p = 0) and with none.',
  subject: {
    name: 'heroWeight',
    params: [
      { name: 'p0', type: 'f32' },
      { name: 'p1', type: 'f32' },
      { name: 'p2', type: 'f32' },
      { name: 'hero', type: 'u32' },
    ],
    result: 'f32',
  },
  reference: `import package::chromatic::heroBalanceWeight;
fn heroWeight(p0: f32, p1: f32, p2: f32, hero: u32) -> f32 {
  return heroBalanceWeight(vec3f(p0, p1, p2), hero);
}`,
  checks: [
    {
      kind: 'cases',
      name: 'Equal pdfs (a grey medium)',
      points: 1,
      message:
        'With p0 = p1 = p2 = p every channel would have drawn the path alike, and the factor is 1/p: ' +
        'the estimate is the plain f/p. Off by 3 means the 1/3 of choosing the hero is counted twice or not at all.',
      ...TOLERANCE,
      cases: [0.25, 1, 4].map((p) => ({ label: `p0 = p1 = p2 = ${p}`, args: [p, p, p, 1] })),
    },
    {
      kind: 'cases',
      name: 'Different pdfs, each channel the hero',
      points: 3,
      message: WEIGHT_MESSAGE,
      ...TOLERANCE,
      cases: [
        [0.5, 2, 6],
        [3, 0.2, 0.05],
        [1, 4, 1],
      ].flatMap((p) =>
        [0, 1, 2].map((hero) => ({
          label: `p = (${p.join(', ')}), hero ${hero}`,
          args: [...p, hero],
        })),
      ),
    },
  ],
};
