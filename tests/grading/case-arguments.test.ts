// The "Arguments" cell of a report's samples table: the case's label, and the
// arguments only where the label does not already state them all.
import { describe, expect, it } from 'vitest';
import { caseArguments } from '../../src/grading/grade.ts';

describe('caseArguments', () => {
  it('does not repeat arguments the label states', () => {
    expect(caseArguments('g = 0.7, μ = -1', 'g = 0.7, mu = -1', [0.7, -1])).toBe('g = 0.7, μ = -1');
    expect(caseArguments('σt = 1/m, d = 2 m', 'sigmaT = 1, d = 2', [1, 2])).toBe(
      'σt = 1/m, d = 2 m',
    );
  });

  it('keeps the arguments when the label names only some, or other values', () => {
    expect(caseArguments('σ0 = 3, 4 steps', 's0 = 3, a = 0.9, d = 1, n = 4', [3, 0.9, 1, 4])).toBe(
      'σ0 = 3, 4 steps: s0 = 3, a = 0.9, d = 1, n = 4',
    );
    expect(caseArguments('thin fog', 'sigmaT = 0.02, d = 30', [0.02, 30])).toBe(
      'thin fog: sigmaT = 0.02, d = 30',
    );
    // Same number of assignments, but a value the label rounds: show the exact arguments.
    expect(caseArguments('g = 0.7, μ = 0.33', 'g = 0.7, mu = 0.3333333', [0.7, 1 / 3])).toBe(
      'g = 0.7, μ = 0.33: g = 0.7, mu = 0.3333333',
    );
  });
});
