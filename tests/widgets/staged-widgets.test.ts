// Issue 23's stages for the widgets of int23b: the ladder family that carries a cost
// measured at one parameter value to another, delta-tracking's rungs of samples (a
// stage's estimates are the first of the full picture's, from the same streams),
// raymarch-steps' rungs of image sizes, and the throttled URL writer.
import { describe, expect, it } from 'vitest';
import { LadderFamily } from '../../src/widgets/base/ladderFamily.ts';
import { PREVIEW_WORK_SHARE } from '../../src/widgets/base/refinement.ts';
import { ThrottledWriter, type WriterClock } from '../../src/widgets/base/throttledWriter.ts';
import {
  emptyImageCpu,
  inputsFrom,
  renderRowsCpu,
  withEstimator,
} from '../../src/widgets/delta-tracking/model.ts';
import { DELTA_TRACKING } from '../../src/widgets/delta-tracking/schema.ts';
import { sampleRungs } from '../../src/widgets/delta-tracking/stages.ts';
import { IMAGE_HEIGHT, IMAGE_WIDTH } from '../../src/widgets/raymarch-steps/model.ts';
import { imageRungs } from '../../src/widgets/raymarch-steps/stages.ts';

describe('LadderFamily', () => {
  const rungs = (full: number) => () => sampleRungs(full);

  it('starts a new key on the lowest rung before anything is measured', () => {
    const family = new LadderFamily<number>(100, 0);
    expect(family.get('64', rungs(64)).pick({ stage: 0 }).rung.value).toBe(4);
  });

  it('seeds a new key with the cost per unit of work measured on another', () => {
    const family = new LadderFamily<number>(100, 0);
    const first = family.get('64', rungs(64));
    const choice = first.pick({ stage: 0 }); // 4 samples
    family.record(first, choice, 4 * 1); // 1 ms per sample
    // The first picture's work may take PREVIEW_WORK_SHARE of the 100 ms budget.
    expect(PREVIEW_WORK_SHARE * 100).toBeGreaterThanOrEqual(48);
    expect(PREVIEW_WORK_SHARE * 100).toBeLessThan(64);
    // At spp 48: rungs 3, 12, 48 samples → 3, 12, 48 ms: all fit.
    expect(family.get('48', rungs(48)).pick({ stage: 0 }).rung.value).toBe(48);
    // At spp 256: 16, 64, 256 samples → 16, 64, 256 ms: only 16 fits.
    expect(family.get('256', rungs(256)).pick({ stage: 0 }).rung.value).toBe(16);
  });

  it('returns the same ladder for a key it holds and forgets the oldest past its size', () => {
    const family = new LadderFamily<number>(100, 0);
    const kept = family.get('1', rungs(1));
    expect(family.get('1', rungs(1))).toBe(kept);
    for (let k = 2; k < 40; k++) family.get(String(k), rungs(k));
    expect(family.get('1', rungs(1))).not.toBe(kept);
  });

  it('ignores nonsense measurements', () => {
    const family = new LadderFamily<number>(100, 0);
    const ladder = family.get('64', rungs(64));
    family.record(ladder, ladder.pick({ stage: 0 }), Number.NaN);
    expect(family.get('256', rungs(256)).pick({ stage: 0 }).index).toBe(0);
  });
});

describe('delta-tracking sampleRungs', () => {
  it('climbs 1/16, 1/4 and all of spp, deduplicated, keeping 2 samples for the variance', () => {
    expect(sampleRungs(256).map((r) => r.value)).toEqual([16, 64, 256]);
    expect(sampleRungs(100).map((r) => r.value)).toEqual([7, 25, 100]);
    expect(sampleRungs(4).map((r) => r.value)).toEqual([2, 4]);
    expect(sampleRungs(2).map((r) => r.value)).toEqual([2]);
    expect(sampleRungs(1).map((r) => r.value)).toEqual([1]);
    expect(sampleRungs(256).map((r) => r.label)).toEqual([
      '16 of 256 samples per pixel',
      '64 of 256 samples per pixel',
      '256 samples per pixel',
    ]);
  });

  it('draws a stage from the first estimates of the full picture’s streams (the twin)', () => {
    const defaults = Object.fromEntries(DELTA_TRACKING.parameters.map((p) => [p.name, p.default]));
    // Ratio tracking: continuous estimates, so a mismatch of streams cannot hide.
    const inputs = withEstimator(inputsFrom({ ...defaults, seed: 7 }), 'ratio');
    const [width, height] = [8, 5];
    const render = (spp: number) => {
      const image = emptyImageCpu(width, height, spp);
      renderRowsCpu(image, inputs, 0, height);
      return image;
    };
    const one = render(1);
    const two = render(2);
    const other = renderRowsOtherSeed(inputs, width, height);
    let differs = false;
    for (let p = 0; p < width * height; p++) {
      const x1 = one.mean[p]!;
      const x2 = 2 * two.mean[p]! - x1;
      // The spp = 2 picture's second moment is that of x1 and the x2 it implies.
      expect(two.meanSquare[p]!).toBeCloseTo((x1 * x1 + x2 * x2) / 2, 12);
      if (Math.abs(other.mean[p]! - x1) > 1e-9) differs = true;
    }
    // The check can fail: another seed's first estimates are not these.
    expect(differs).toBe(true);
  });
});

/** The spp = 1 picture of another seed (the streams the check must tell apart). */
function renderRowsOtherSeed(inputs: ReturnType<typeof inputsFrom>, width: number, height: number) {
  const image = emptyImageCpu(width, height, 1);
  renderRowsCpu(image, { ...inputs, seed: inputs.seed + 1 }, 0, height);
  return image;
}

describe('raymarch-steps imageRungs', () => {
  it('draws a quarter, a half and all of the image side, work ∝ rays × steps', () => {
    const rungs = imageRungs(16);
    expect(rungs.map((r) => r.value)).toEqual([
      { width: IMAGE_WIDTH / 4, height: IMAGE_HEIGHT / 4 },
      { width: IMAGE_WIDTH / 2, height: IMAGE_HEIGHT / 2 },
      { width: IMAGE_WIDTH, height: IMAGE_HEIGHT },
    ]);
    expect(rungs[2]!.work).toBe(IMAGE_WIDTH * IMAGE_HEIGHT * 16);
    expect(imageRungs(64)[2]!.work).toBe(4 * rungs[2]!.work);
    expect(rungs[0]!.label).toBe(`${IMAGE_WIDTH / 4}×${IMAGE_HEIGHT / 4} pixels`);
  });
});

describe('ThrottledWriter', () => {
  /** A clock the test moves by hand. */
  function fakeClock(): WriterClock & { advance(ms: number): void } {
    let now = 1000;
    let timers: { at: number; callback: () => void; id: number }[] = [];
    let nextId = 1;
    return {
      now: () => now,
      setTimeout(callback, ms) {
        const id = nextId++;
        timers.push({ at: now + ms, callback, id });
        return id;
      },
      clearTimeout(handle) {
        timers = timers.filter((t) => t.id !== handle);
      },
      advance(ms) {
        now += ms;
        const due = timers.filter((t) => t.at <= now);
        timers = timers.filter((t) => t.at > now);
        for (const t of due) t.callback();
      },
    };
  }

  it('writes a single change at once', () => {
    const clock = fakeClock();
    const writer = new ThrottledWriter(200, clock);
    const written: number[] = [];
    writer.write(() => written.push(1));
    expect(written).toEqual([1]);
    clock.advance(250);
    writer.write(() => written.push(2));
    expect(written).toEqual([1, 2]);
  });

  it('during a drag writes at most once per interval, and the newest state last', () => {
    const clock = fakeClock();
    const writer = new ThrottledWriter(200, clock);
    const written: number[] = [];
    for (let i = 0; i < 20; i++) {
      writer.write(() => written.push(i));
      clock.advance(50);
    }
    clock.advance(200);
    // 1 s of inputs every 50 ms: the first at once, then one per 200 ms.
    expect(written.length).toBeLessThanOrEqual(6);
    expect(written.length).toBeGreaterThanOrEqual(5);
    expect(written[0]).toBe(0);
    expect(written.at(-1)).toBe(19);
  });

  it('flush runs a waiting write now, and nothing when none waits', () => {
    const clock = fakeClock();
    const writer = new ThrottledWriter(200, clock);
    const written: number[] = [];
    writer.write(() => written.push(1));
    writer.write(() => written.push(2));
    expect(written).toEqual([1]);
    writer.flush();
    expect(written).toEqual([1, 2]);
    writer.flush();
    clock.advance(500);
    expect(written).toEqual([1, 2]);
  });
});
