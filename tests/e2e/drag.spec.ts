// A picture that follows the slider while it is dragged (issue 23). During a drag every
// input comes before the last one's first picture is done, and the base element used to
// drop each such picture as stale: beer-law showed 1 frame in a 1 s drag of 20 inputs
// while it drew 16, volume-path-tracer 0–1. A first picture now runs to its end and is
// shown (refinement.ts showsWhenStale); the widget still settles on the last input's
// values. Checked on WebGPU and on the CPU fallback, on a cheap widget, a staged one and
// the two path tracers whose stale previews their own views dropped too.
import { expect, test, type Locator, type Page } from '@playwright/test';
import { WIDGET_CATALOG } from '../../src/widgets/catalog.ts';
import { trackErrors } from './support.ts';

// Up to 90 s to settle after loading and 60 s after the drag on a loaded machine.
test.setTimeout(180_000);

/** Inputs of the scripted drag, and the time between them (a quick hand on a slider). */
const INPUTS = 30;
const INTERVAL_MS = 50;

/**
 * Drags the widget's first slider from its minimum to its maximum (INPUTS input events,
 * INTERVAL_MS apart) and returns how many frames the widget showed (data-frames) and how
 * many renders it finished (data-rendered, shown or not) from the first input until one
 * interval after the last, and the slider's last value.
 */
async function framesDuringDrag(
  widget: Locator,
): Promise<{ shown: number; rendered: number; last: string }> {
  return widget.evaluate(
    async (element, { inputs, interval }) => {
      const control = element.querySelector<HTMLInputElement>('input[type=range]');
      if (!control) throw new Error('no slider');
      // Every frame shown: the current inputs' and earlier inputs' first pictures.
      const frames = (): number =>
        Number(element.getAttribute('data-frames') ?? '0') +
        Number(element.getAttribute('data-stale-frames') ?? '0');
      const renders = (): number => Number(element.getAttribute('data-rendered') ?? '0');
      const min = Number(control.min);
      const max = Number(control.max);
      const before = frames();
      const rendersBefore = renders();
      const start = performance.now();
      for (let i = 0; i < inputs; i++) {
        const wait = start + i * interval - performance.now();
        if (wait > 0) await new Promise((resolve) => setTimeout(resolve, wait));
        control.value = String(min + ((max - min) * i) / (inputs - 1));
        control.dispatchEvent(new Event('input', { bubbles: true }));
      }
      await new Promise((resolve) => setTimeout(resolve, interval));
      return { shown: frames() - before, rendered: renders() - rendersBefore, last: control.value };
    },
    { inputs: INPUTS, interval: INTERVAL_MS },
  );
}

async function open(page: Page, name: string, query: string): Promise<Locator> {
  await page.setViewportSize({ width: 1280, height: 900 });
  await page.goto(`/embed/${name}.html${query}`);
  const widget = page.locator(`sb-${name}`).first();
  // Settled, not merely without data-settled="false" (waitForSettled): the attribute
  // comes with the first render.
  await expect(widget).toHaveAttribute('data-settled', 'true', { timeout: 90_000 });
  return widget;
}

// Every widget with a slider (the exercise has none), on both backends.
const DRAGGED = Object.keys(WIDGET_CATALOG).filter((name) => name !== 'exercise');

for (const query of ['', '?backend=cpu'])
  for (const name of DRAGGED)
    test(`${name}${query}: the picture follows a dragged slider and settles on its last value`, async ({
      page,
    }) => {
      const errors = trackErrors(page);
      const widget = await open(page, name, query);
      const { shown, rendered, last } = await framesDuringDrag(widget);
      // 1.5 s of dragging: 11–27 frames shown here on SwiftShader alone. Dropping stale first
      // pictures showed 0–2 on WebGPU (beer-law 1 of 17 renders, volume-path-tracer 0).
      // The share hardly depends on the machine's speed: every first picture is shown
      // unless it is still drawing three first-picture budgets after it started; what is
      // dropped is a later stage or a background frame cut short by an input (up to 45 %
      // of renders here in dipole-profile and chromatic-media, whose previews ask for the
      // next stage at once).
      const counts = `${shown} frames shown of ${rendered} renders`;
      // Not a count: with two browsers on a 2-core CI machine a render took up to 400 ms
      // (2 frames shown of 3 renders in hg-lobe).
      expect(shown, counts).toBeGreaterThanOrEqual(1);
      expect(shown, counts).toBeGreaterThanOrEqual(rendered / 3);
      await expect(widget).toHaveAttribute('data-settled', 'true', { timeout: 60_000 });
      expect(await widget.locator('input[type=range]').first().inputValue()).toBe(last);
      await expect(widget.locator('.sb-notice--error')).toHaveCount(0);
      expect(errors).toEqual([]);
    });
