// WGSL PCG stream vs its TypeScript twin: the u32 sequence must be identical
// bit for bit, so a test can replay a pixel's random numbers on the CPU.
import { describeShaderFunction } from '../support/shaderHarness.ts';
import {
  pcgAdvance,
  pcgHash,
  pcgOutput,
  rngNextFloat,
  rngSeed,
  u32ToUnitFloat,
} from '../../src/reference/rng.ts';
import { ONE_MINUS_EPSILON_F32 } from '../support/f32.ts';

const WORDS = [
  0, 1, 2, 3, 42, 0x7fffffff, 0x80000000, 0xdeadbeef, 0xfffffffe, 0xffffffff, 123456789, 2891336453,
];
const exact = { ulps: 0, reason: 'integer arithmetic and an exact power-of-two scaling' };

for (const [fn, twin] of [
  ['pcgAdvance', pcgAdvance],
  ['pcgOutput', pcgOutput],
  ['pcgHash', pcgHash],
] as const) {
  describeShaderFunction({
    module: 'rng',
    fn,
    args: ['u32'],
    result: 'u32',
    twin,
    tolerance: exact,
    cases: WORDS.map((word) => ({ name: `0x${word.toString(16)}`, args: [word] })),
  });
}

describeShaderFunction({
  module: 'rng',
  fn: 'rngSeed',
  args: ['u32', 'u32'],
  result: 'u32',
  twin: rngSeed,
  tolerance: exact,
  cases: [
    [0, 0],
    [1, 0],
    [0, 1],
    [640 * 480 - 1, 7],
    [0xffffffff, 0xffffffff],
  ].map(([pixel, frame]) => ({
    name: `pixel ${pixel}, frame ${frame}`,
    args: [pixel ?? 0, frame ?? 0],
  })),
});

describeShaderFunction({
  module: 'rng',
  fn: 'u32ToUnitFloat',
  args: ['u32'],
  result: 'f32',
  twin: u32ToUnitFloat,
  tolerance: exact,
  cases: [
    { name: '0 maps to 0', args: [0], expected: 0 },
    {
      name: '0xFFFFFFFF maps to 1 − 2^-24, never 1 (hard case 16)',
      args: [0xffffffff],
      expected: ONE_MINUS_EPSILON_F32,
    },
    { name: 'low 8 bits are dropped', args: [0xff], expected: 0 },
    { name: '2^31 maps to 0.5', args: [0x80000000], expected: 0.5 },
  ],
});

// rngNextFloat takes a pointer; the wrapper draws four numbers from one seed and
// returns them, and the twin replays the same stream.
describeShaderFunction({
  module: 'rng',
  fn: 'rngNextFloat',
  args: ['u32'],
  result: 'vec4f',
  wrapper: {
    imports: ['rngNextFloat'],
    wgsl: `fn caseUnderTest(seed: u32) -> vec4f {
  var state = seed;
  let a = rngNextFloat(&state);
  let b = rngNextFloat(&state);
  let c = rngNextFloat(&state);
  let d = rngNextFloat(&state);
  return vec4f(a, b, c, d);
}`,
  },
  twin: (seed: number) => {
    const state = { value: seed };
    return [rngNextFloat(state), rngNextFloat(state), rngNextFloat(state), rngNextFloat(state)];
  },
  tolerance: exact,
  cases: WORDS.map((word) => ({ name: `stream from seed 0x${word.toString(16)}`, args: [word] })),
});
