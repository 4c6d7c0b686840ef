// What the browser benches share (bench/interaction.ts, pages.ts, firstPictureProbe.ts,
// dragProfile.ts): the production build served by `vite preview` on a free port, and the
// slider an interaction moves.
import type { Page } from 'playwright-core';
import { preview, type PreviewServer } from 'vite';
import type { Slider } from './interactionJudge.ts';

/** Serves the build in `dist` (a `vite build` output) on a free port; base URL without a slash. */
export async function servePreview(
  root: string,
  dist: string,
): Promise<{ server: PreviewServer; base: string }> {
  const server = await preview({
    root,
    configFile: false,
    preview: { port: 0, strictPort: false },
    build: { outDir: dist },
    logLevel: 'error',
  });
  const address = server.httpServer.address();
  const port = typeof address === 'object' && address ? address.port : 4173;
  return { server, base: `http://localhost:${port}` };
}

/**
 * The first enabled, visible range input among the controls of the widget `tag`, marked
 * with data-probe="1" so that the page's scripts find it again, and its range and value.
 */
export function markFirstSlider(page: Page, tag: string): Promise<Slider & { value: number }> {
  return page.evaluate((t) => {
    const el = document.querySelector(t) as HTMLElement;
    const control = [...el.querySelectorAll<HTMLInputElement>('.sb-controls input[type=range]')]
      .filter((c) => !c.disabled && c.checkVisibility())
      .at(0);
    if (!control) throw new Error('no slider');
    control.dataset['probe'] = '1';
    return {
      min: Number(control.min),
      max: Number(control.max),
      step: Number(control.step) || 1,
      value: Number(control.value),
    };
  }, tag);
}
