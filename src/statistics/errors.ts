// Errors of an estimate against a reference (images, curves), in float64: the
// root-mean-square error every convergence readout and plot of the book reports,
// and the same relative to the reference's mean. One definition, so that the
// widgets, the bench and the tests measure the same thing.

function checkLengths(estimate: ArrayLike<number>, reference: ArrayLike<number>): void {
  if (estimate.length !== reference.length)
    throw new RangeError(
      `an error needs arrays of one length: estimate ${estimate.length}, reference ${reference.length}`,
    );
}

/**
 * Root-mean-square difference √(Σ(eᵢ − rᵢ)²/n) over all n entries (pixels × channels).
 * NaN for empty arrays (no error is measured) and wherever an entry is NaN; a
 * RangeError when the lengths differ.
 */
export function rmse(estimate: ArrayLike<number>, reference: ArrayLike<number>): number {
  checkLengths(estimate, reference);
  const n = reference.length;
  if (n === 0) return NaN;
  let squares = 0;
  for (let i = 0; i < n; i++) squares += (estimate[i]! - reference[i]!) ** 2;
  return Math.sqrt(squares / n);
}

/**
 * rmse divided by the reference's mean, a scale-free error; NaN when the reference's
 * mean is not positive (a relative error of a dark or empty reference means nothing).
 */
export function relativeRmse(estimate: ArrayLike<number>, reference: ArrayLike<number>): number {
  const error = rmse(estimate, reference);
  let sum = 0;
  for (let i = 0; i < reference.length; i++) sum += reference[i]!;
  const referenceMean = sum / reference.length;
  return referenceMean > 0 ? error / referenceMean : NaN;
}

/** Largest absolute difference of any entry; NaN for empty arrays. */
export function maxAbsoluteError(
  estimate: ArrayLike<number>,
  reference: ArrayLike<number>,
): number {
  checkLengths(estimate, reference);
  if (reference.length === 0) return NaN;
  let worst = 0;
  for (let i = 0; i < reference.length; i++)
    worst = Math.max(worst, Math.abs(estimate[i]! - reference[i]!));
  return worst;
}
