// Numerical integration for the tests: an independent check of closed forms and of
// the integrals in variance formulas (physics.md §1, §4, §5).

/** Composite Simpson's rule over [a, b] with n (even) intervals. */
export function simpson(f: (x: number) => number, a: number, b: number, n = 2000): number {
  const h = (b - a) / n;
  let sum = f(a) + f(b);
  for (let i = 1; i < n; i++) sum += (i % 2 ? 4 : 2) * f(a + i * h);
  return (sum * h) / 3;
}
