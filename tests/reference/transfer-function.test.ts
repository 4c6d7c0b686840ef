// The transfer-function widget's model: the CT phantom's values at known points
// (Shepp–Logan gray levels read as attenuation relative to water), the transfer
// function built from the parameters (clamped, sorted, merged with the colour map),
// the presets in Hounsfield units, and the image's convergence with the step size.
import { describe, expect, it } from 'vitest';
import { parseParameters } from '../../src/widgets/parameters.ts';
import { transferLookup } from '../../src/reference/volume.ts';
import {
  buildTransferFunction,
  colourDomain,
  controlPointsFrom,
  inputsFrom,
  opacityAt,
  presetValues,
  renderImageCpu,
  rmse,
  terminationBiasBound,
  TRANSFER_PRESETS,
  type ControlPoint,
} from '../../src/widgets/transfer-function/model.ts';
import {
  eulerMatrix,
  histogram,
  phantomHounsfield,
  phantomVolume,
  SHEPP_LOGAN_3D,
  worldToPhantom,
} from '../../src/widgets/transfer-function/phantom.ts';
import { TRANSFER_FUNCTION } from '../../src/widgets/transfer-function/schema.ts';
import { logLogSlope } from '../../src/widgets/base/sweep.ts';

const parse = (raw: Record<string, string>) =>
  parseParameters(TRANSFER_FUNCTION.parameters, (name) => raw[name]);

describe('the 3D Shepp–Logan phantom in Hounsfield units', () => {
  it('has air, scalp, skull, brain, ventricles and lesions at their published gray levels', () => {
    expect(phantomHounsfield(0, 0, 0)).toBeCloseTo(20, 9); // brain: 2 − 0.98 = 1.02
    expect(phantomHounsfield(0, 0.9, 0)).toBeCloseTo(1000, 9); // skull: 2
    expect(phantomHounsfield(0.71, 0, 0)).toBe(40); // our scalp
    expect(phantomHounsfield(0.95, 0, 0)).toBe(-1000); // air
    expect(phantomHounsfield(0, 0.35, -0.15)).toBeCloseTo(30, 9); // lesion e: 1.02 + 0.01
    // The centre of a ventricle lies in its rotated frame: p = Aᵀc.
    const ventricle = SHEPP_LOGAN_3D[2]!;
    const m = eulerMatrix(ventricle.angles);
    const [cx, cy, cz] = ventricle.centre;
    const p: [number, number, number] = [
      m[0] * cx + m[3] * cy + m[6] * cz,
      m[1] * cx + m[4] * cy + m[7] * cz,
      m[2] * cx + m[5] * cy + m[8] * cz,
    ];
    expect(phantomHounsfield(...p)).toBeCloseTo(0, 9); // 1.02 − 0.02 = water/CSF
  });

  it('maps world axes with y up: the head’s long axis (phantom z) is world y', () => {
    expect(worldToPhantom([0, 0.12, 0])).toEqual([0, -0, 1]);
    expect(worldToPhantom([0.06, 0, -0.12])).toEqual([0.5, 1, 0]);
  });

  it('is deterministic, stored with the CT intercept (stored = HU + 1024 ≥ 0), and its histogram counts every voxel', () => {
    const volume = phantomVolume();
    const n = volume.size;
    expect(volume.hounsfield.length).toBe(n ** 3);
    expect(volume.hounsfield[0]).toBe(-1000);
    expect(volume.hounsfield[n / 2 + n * (n / 2 + n * (n / 2))]).toBeCloseTo(20, 3);
    expect(volume.stored.every((v) => v >= 0)).toBe(true);
    expect(volume.stored[0]).toBe(24);
    const counts = histogram(volume.hounsfield);
    expect(counts.counts.reduce((a, b) => a + b, 0)).toBe(n ** 3);
    // Air fills most of the cube; the brain is the second peak.
    const peak = counts.counts.indexOf(Math.max(...counts.counts));
    expect(counts.edges[peak]).toBeLessThan(-990);
  });
});

describe('the transfer function from the parameters', () => {
  it('clamps values out of range and reports them (HU to [−1024, 3071], opacity to [0, 1])', () => {
    const parsed = parse({ 'hu-3': '5000', 'opacity-2': '-0.5', 'opacity-4': 'lots' });
    expect(parsed.values['hu-3']).toBe(3071);
    expect(parsed.values['opacity-2']).toBe(0);
    expect(parsed.values['opacity-4']).toBe(0);
    expect(parsed.warnings).toHaveLength(3);
  });

  it('sorts points given out of order and says so, keeping each point’s parameter index', () => {
    const parsed = parse({ 'hu-2': '800', 'opacity-2': '0.7' });
    const { points, reordered } = controlPointsFrom(parsed.values);
    expect(reordered).toBe(true);
    expect(points.map((p) => p.hu)).toEqual([-1024, 30, 80, 400, 800, 900]);
    expect(points[4]).toEqual({ hu: 800, opacity: 0.7, index: 2 });
    expect(controlPointsFrom(parse({}).values).reordered).toBe(false);
  });

  it('merges the opacity points and the colour map into one exact piecewise-linear table', () => {
    for (const preset of TRANSFER_PRESETS) {
      const { points } = controlPointsFrom(parse(toStrings(presetValues(preset))).values);
      const tf = buildTransferFunction(points, preset.colormap);
      expect(tf.count).toBeLessThanOrEqual(16);
      expect([...tf.values].sort((a, b) => a - b)).toEqual(tf.values);
      for (let v = -1024; v <= 3071; v += 7.5)
        expect(transferLookup(tf, v)[3]).toBeCloseTo(opacityAt(points, v), 12);
    }
  });

  it('spreads the colour map over the opacity ramp', () => {
    const points: ControlPoint[] = [
      [-1024, 0],
      [0, 0],
      [250, 0],
      [700, 0.7],
      [1500, 0.7],
      [3071, 0.7],
    ].map(([hu, opacity], k) => ({ hu: hu!, opacity: opacity!, index: k + 1 }));
    expect(colourDomain(points)).toEqual([250, 700]);
    const flat = points.map((p) => ({ ...p, opacity: 0 }));
    expect(colourDomain(flat)).toEqual([-1024, 3071]);
  });

  it('bounds the early-termination bias by ε times the brightest emission', () => {
    const on = inputsFrom(parse({ epsilon: '0.05' }).values);
    expect(terminationBiasBound(on)).toBeCloseTo(0.05, 12); // the tissue map ends in white
    const off = inputsFrom(parse({ termination: 'off' }).values);
    expect(terminationBiasBound(off)).toBe(0);
  });
});

describe('the rendered image (float64 twin, 16×16 pixels)', () => {
  it('converges with the step: RMSE falls about as Δs² between 2 and ½ voxel for the default preset', () => {
    const input = inputsFrom(parse({ termination: 'off' }).values);
    const reference = renderImageCpu(16, input, 1 / 16, 0);
    const steps = [2, 1, 0.5];
    const errors = steps.map((s) => rmse(renderImageCpu(16, input, s, 0).rgb, reference.rgb));
    expect(errors[0]).toBeGreaterThan(errors[1]!);
    expect(errors[1]).toBeGreaterThan(errors[2]!);
    const slope = logLogSlope(
      steps.map((s) => 1 / s),
      errors,
    );
    expect(slope).toBeLessThan(-1.5);
  });
});

function toStrings(values: Record<string, string | number>): Record<string, string> {
  return Object.fromEntries(Object.entries(values).map(([k, v]) => [k, String(v)]));
}
