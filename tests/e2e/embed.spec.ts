// Embeds (issue 18, item 3): every widget of the catalog on its own page,
// embed/<widget>.html, opened with a non-default state in the deep-link hash format;
// and the Copy menu's <iframe> snippet placed in a host page of another origin.
import { createServer, type Server } from 'node:http';
import type { AddressInfo } from 'node:net';
import AxeBuilder from '@axe-core/playwright';
import { expect, test, type Locator, type Page } from '@playwright/test';
import { PNG } from 'pngjs';
import { WIDGET_CATALOG } from '../../src/widgets/catalog.ts';
import { canvasStats, trackErrors, waitForPicture, waitForSettled } from './support.ts';

/**
 * For each widget, one parameter set away from its chapter's value, chosen to change
 * the picture visibly. Every catalog widget must appear here (checked below), so a
 * new widget cannot go untested; a widget without parameters (the exercise) has none.
 */
const NON_DEFAULT: Readonly<Record<string, readonly [string, string] | null>> = {
  'beer-law': ['sigma-a', '3'],
  'hg-lobe': ['g', '-0.7'],
  'rayleigh-sky': ['sun-elevation', '4'],
  'vre-ray': ['sigma', '4'],
  'raymarch-steps': ['density', '4.5'],
  'delta-tracking': ['majorant', 'low'],
  'dipole-profile': ['material', 'ketchup'],
  'translucent-render': ['exposure', '5'],
  'translucent-room': ['walls', 'black'],
  'inverse-render': ['novel', '200'],
  'transfer-function': ['azimuth', '-120'],
  'single-scatter': ['sigma-s', '3'],
  'volume-path-tracer': ['optical-thickness', '1'],
  'photon-map': ['radius', '0.2'],
  'mie-lobe': ['log-radius', '-1.5'],
  'chromatic-media': ['exposure', '5'],
  exercise: null,
};

/**
 * Further keys of the same hash that shrink the work of a figure whose full refinement
 * (waited for below, before its picture is compared) takes tens of seconds on a CPU
 * WebGPU; the parameter the test changes (NON_DEFAULT) is left alone. They are read
 * from the hash like the first key, so the page is also checked to take several.
 */
const CHEAPER: Readonly<Record<string, Readonly<Record<string, string>>>> = {
  // A gather visits the photons inside its radius: at r = 0.2 (25× the default's disc)
  // the default 65 536 photons took over a minute; 4 096 gather about as many per pixel
  // as the chapter's figure does.
  'photon-map': { photons: '4096' },
  // 32×32 pictures instead of 64×64, and a path-traced target of 2⁶ spp instead of 2¹⁰.
  'translucent-render': { size: '32', spp: '6' },
  // 16×16 pictures of 4 samples per pixel instead of 64×64 of 256.
  'translucent-room': { size: '16', spp: '2' },
  // One sample per pixel per frame instead of four.
  'volume-path-tracer': { spp: '1' },
  // Half the ray-marching steps.
  'transfer-function': { step: '2' },
  // 8 view-ray samples instead of 32.
  'rayleigh-sky': { steps: '8' },
  // Two samples per pixel in one pass instead of accumulating passes of four up to 64.
  'chromatic-media': { spp: '2', target: '2' },
};

const FRAME = { width: 800, height: 600 };

/** Mean absolute difference of luminance (0–255) between two screenshots, over 8×8 blocks. */
function blockDifference(a: Buffer, b: Buffer): number {
  const first = PNG.sync.read(a);
  const second = PNG.sync.read(b);
  const width = Math.min(first.width, second.width);
  const height = Math.min(first.height, second.height);
  const block = 8;
  const blocksX = Math.floor(width / block);
  const blocksY = Math.floor(height / block);
  const mean = (image: PNG, bx: number, by: number): number => {
    let sum = 0;
    for (let y = by * block; y < (by + 1) * block; y++)
      for (let x = bx * block; x < (bx + 1) * block; x++) {
        const i = 4 * (y * image.width + x);
        sum +=
          0.2126 * (image.data[i] ?? 0) +
          0.7152 * (image.data[i + 1] ?? 0) +
          0.0722 * (image.data[i + 2] ?? 0);
      }
    return sum / (block * block);
  };
  let total = 0;
  for (let by = 0; by < blocksY; by++)
    for (let bx = 0; bx < blocksX; bx++)
      total += Math.abs(mean(first, bx, by) - mean(second, bx, by));
  return total / Math.max(blocksX * blocksY, 1);
}

/** The control that shows a parameter: its select, or the number box of a slider. */
function control(widget: Locator, name: string): Locator {
  return widget.locator(`select[name="${name}"], input[type="number"][name="${name}"]`).first();
}

async function openEmbed(page: Page, widget: string, hash = ''): Promise<Locator> {
  // A new document each time: a change of the hash alone would not reload the page.
  await page.goto('about:blank');
  await page.goto(`/embed/${widget}.html${hash ? `#${hash}` : ''}`);
  return page.locator(`sb-${widget}`);
}

test('the test covers every widget in the catalog', () => {
  expect(Object.keys(NON_DEFAULT).sort()).toEqual(Object.keys(WIDGET_CATALOG).sort());
});

for (const widget of Object.keys(WIDGET_CATALOG)) {
  test(`embed/${widget}.html: the widget alone, its state from the hash, sized to an 800×600 frame`, async ({
    page,
  }) => {
    test.setTimeout(240_000);
    await page.setViewportSize(FRAME);
    const errors = trackErrors(page);
    const change = NON_DEFAULT[widget] ?? null;
    const id = `${widget}-1`;

    // One page per widget: opened with a non-default state in the deep-link format.
    const cheaper = Object.entries(CHEAPER[widget] ?? {});
    const keys = change ? [change, ...cheaper] : [];
    const element = await openEmbed(
      page,
      widget,
      change ? `${keys.map(([name, value]) => `${id}.${name}=${value}`).join('&')}&v=1` : '',
    );
    await expect(element).toHaveCount(1);
    await expect(page.locator('.site-header, .site-footer, .toc')).toHaveCount(0);
    let picture: Buffer | null = null;
    let canvasPicture: Buffer | null = null;
    if (change) {
      // Full refinement (the picture compared below): single-scatter's takes over 45 s
      // on a loaded two-core machine, so it gets longer than waitForRender allows.
      await waitForPicture(element);
      await waitForSettled(element, 120_000);
      for (const [key, wanted] of keys)
        await expect(control(element, key), `${key} from the hash`).toHaveValue(wanted);
      const changed = await canvasStats(element.locator('canvas.sb-canvas').first());
      expect(changed.luminanceDeviation, 'the canvas shows a picture').toBeGreaterThan(3);
      picture = (await canvasStats(element.locator('.sb-stage'))).png;
      canvasPicture = changed.png;
    } else {
      await expect(element.locator('.sb-widget')).toBeVisible();
    }

    // Sized to the frame: it fills the width, and nothing overflows sideways.
    const box = await element.boundingBox();
    expect(box?.width ?? 0).toBeGreaterThan(FRAME.width - 40);
    const overflow = await page.evaluate(
      () => document.documentElement.scrollWidth - document.documentElement.clientWidth,
    );
    expect(overflow).toBeLessThanOrEqual(0);

    // The link back to the chapter resolves, carries the state, and leaves the frame.
    const link = page.locator('a.embed-chapter-link');
    await expect(link).toHaveText(/^Open in the book: \d+\. /);
    await expect(link).toHaveAttribute('target', '_blank');
    expect(await link.getAttribute('href')).toMatch(/^\.\.\/chapters\/[^/]+\.html/);
    await link.focus();
    const href = (await link.getAttribute('href')) ?? '';
    for (const [key, value] of keys) expect(href).toContain(`${id}.${key}=${value}`);
    if (change) expect(href).toContain(`#${id}.${change[0]}=${change[1]}`);
    const chapter = new URL(href, page.url());
    chapter.hash = '';
    const response = await page.request.get(chapter.href);
    expect(response.status()).toBe(200);
    expect(await response.text()).toContain(`<sb-${widget}`);

    if (change && picture) {
      const [name, value] = change;
      const stage = element.locator('.sb-stage');
      // Back to the chapter's value through the control: the picture must differ.
      const entry = WIDGET_CATALOG[widget];
      const initial =
        (await element.getAttribute(name)) ??
        String(entry?.parameters.find((p) => p.name === name)?.default);
      expect(initial).not.toBe(value);
      const rendered = Number(await element.getAttribute('data-rendered'));
      const input = control(element, name);
      if ((await input.evaluate((node) => node.tagName)) === 'SELECT')
        await input.selectOption(initial);
      else {
        await input.fill(initial);
        await input.dispatchEvent('change');
      }
      // Some figures take tens of seconds a frame on a CPU WebGPU: wait longer than waitForRender.
      await expect
        .poll(async () => Number(await element.getAttribute('data-rendered')), { timeout: 120_000 })
        .toBeGreaterThan(rendered);
      await expect(control(element, name)).toHaveValue(initial);
      // A frame already under way when the value changed may still show the old one. The
      // stage's difference is diluted by what does not change (tables, text, plots'
      // frames), and a converged picture differs less than a noisy preview, so the first
      // picture alone counts as well: σs = 0.6 against 3 in single-scatter moved the
      // stage's block means by 0.96 once converged.
      const firstCanvas = element.locator('canvas.sb-canvas').first();
      await expect
        .poll(
          async () =>
            Math.max(
              blockDifference(picture, (await canvasStats(stage)).png),
              canvasPicture
                ? blockDifference(canvasPicture, (await canvasStats(firstCanvas)).png)
                : 0,
            ),
          { message: `${name}=${value} against ${initial} changes the picture`, timeout: 30_000 },
        )
        .toBeGreaterThan(1);
    }

    // Presentation mode: F enters it (filling the frame), Esc leaves it.
    await element.locator('[data-action="present"]').focus();
    await page.keyboard.press('f');
    const shell = element.locator('.sb-widget');
    await expect(shell).toHaveClass(/is-presenting/);
    const presented = await shell.boundingBox();
    expect(presented).toEqual({ x: 0, y: 0, ...FRAME });
    await page.keyboard.press('Escape');
    await expect(shell).not.toHaveClass(/is-presenting/);

    expect(errors).toEqual([]);
  });
}

test('a link copied in a chapter opens its figure on the embed page (second instance, preset key)', async ({
  page,
}) => {
  // hg-lobe-2 is the chapter's second lobe (g = −0.3, log scale, Rayleigh).
  let element = await openEmbed(page, 'hg-lobe', 'hg-lobe-2.samples=12&v=1');
  await waitForPicture(element);
  await expect(element).toHaveAttribute('id', 'hg-lobe-2');
  await expect(control(element, 'g')).toHaveValue('-0.3');
  await expect(control(element, 'scale')).toHaveValue('log');
  await expect(control(element, 'samples')).toHaveValue('12');
  // The beer-law presets: key 3 recalls the layered slab, and the hash records it.
  element = await openEmbed(page, 'beer-law');
  await waitForPicture(element);
  await element.locator('input[type="range"]').first().focus();
  await page.keyboard.press('3');
  await expect(element.locator('.sb-preset-toast')).toHaveText('3 · layered');
  await expect(control(element, 'profile')).toHaveValue('layered');
  await expect.poll(() => page.url()).toContain('beer-law-1.profile=layered');
  // theme=dark in the hash sets the theme, whatever the system prefers.
  await page.emulateMedia({ colorScheme: 'light' });
  element = await openEmbed(page, 'beer-law', 'theme=dark');
  await expect(page.locator('html')).toHaveAttribute('data-theme', 'dark');
  // The embed page with its Copy menu open passes the axe-core check.
  await waitForPicture(element);
  await element.getByRole('button', { name: 'Copy', exact: true }).click();
  const results = await new AxeBuilder({ page })
    .withTags(['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'])
    .analyze();
  expect(
    results.violations.map((v) => `${v.id}: ${v.nodes.map((n) => n.target.join(' ')).join(', ')}`),
  ).toEqual([]);
});

test('the Copy menu gives an iframe snippet that draws the widget, in its state, inside a host page', async ({
  page,
  context,
  baseURL,
}, info) => {
  test.setTimeout(120_000);
  await context.grantPermissions(['clipboard-read', 'clipboard-write']);
  await page.goto('/chapters/02-extinction-and-transmittance.html');
  const widget = page.locator('sb-beer-law').first();
  await waitForPicture(widget);
  await widget.locator('select[name="profile"]').selectOption('smooth');
  await control(widget, 'sigma-a').fill('1.5');
  await control(widget, 'sigma-a').dispatchEvent('change');

  // The menu by keyboard: a real button that opens, announces, and closes with Esc.
  const toggle = widget.getByRole('button', { name: 'Copy', exact: true });
  await toggle.focus();
  await page.keyboard.press('Enter');
  await expect(toggle).toHaveAttribute('aria-expanded', 'true');
  const embedButton = widget.getByRole('button', { name: 'Copy embed code' });
  await expect(widget.getByRole('button', { name: 'Copy link' })).toBeFocused();
  await page.keyboard.press('Tab');
  await expect(embedButton).toBeFocused();
  await page.keyboard.press('Enter');
  await expect(widget.getByRole('status').filter({ hasText: 'Copied embed code' })).toBeVisible();
  await expect(toggle).toHaveAttribute('aria-expanded', 'false');
  await expect(toggle).toBeFocused();
  await page.keyboard.press('Enter');
  await expect(toggle).toHaveAttribute('aria-expanded', 'true');
  await page.keyboard.press('Escape');
  await expect(toggle).toHaveAttribute('aria-expanded', 'false');
  await expect(widget.locator('.sb-widget')).not.toHaveClass(/is-presenting/);

  const snippet = await widget.evaluate((el) =>
    (el as HTMLElement & { embedCode(): string }).embedCode(),
  );
  expect(snippet).toMatch(/^<iframe src="http:\/\/localhost:\d+\/embed\/beer-law\.html#[^"]+"/);
  expect(snippet).toContain('title="Beer\'s law: transmittance through a slab — Scatterbook"');
  for (const attribute of ['width="100%"', 'loading="lazy"', 'allow="fullscreen"'])
    expect(snippet).toContain(attribute);
  const src = /src="([^"]+)"/.exec(snippet)?.[1]?.replace(/&amp;/g, '&') ?? '';
  expect(src.startsWith(`${baseURL}/embed/`)).toBe(true);
  expect(src).toContain('beer-law-1.profile=smooth');
  expect(src).toContain('beer-law-1.sigma-a=1.5');
  // The full state, defaults included: the embed may start from other attributes.
  expect(src).toContain('beer-law-1.thickness=2');
  const height = Number(/height="(\d+)"/.exec(snippet)?.[1]);
  expect(height).toBeGreaterThanOrEqual(320);

  // A lecturer's page on another origin (a server of the test's own on 127.0.0.1, a
  // real local address: Chromium refuses a public page's frames to local servers).
  const body = `<!doctype html><html lang="en"><head><title>Week 3</title></head><body style="margin:0"><h1>Week 3</h1><div style="width:800px">${snippet}</div></body></html>`;
  const server: Server = createServer((_request, response) => {
    response.writeHead(200, { 'content-type': 'text/html; charset=utf-8' });
    response.end(body);
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const host = `http://127.0.0.1:${(server.address() as AddressInfo).port}/slides.html`;
  expect(new URL(host).origin).not.toBe(new URL(src).origin);
  try {
    await page.goto(host);
    const frame = page.frameLocator('iframe');
    const embedded = frame.locator('sb-beer-law');
    await waitForPicture(embedded);
    await expect(control(embedded, 'profile')).toHaveValue('smooth');
    await expect(control(embedded, 'sigma-a')).toHaveValue('1.5');
    const stats = await canvasStats(embedded.locator('canvas.sb-canvas'));
    expect(stats.luminanceDeviation).toBeGreaterThan(10);
    // At the snippet's height the frame needs no scrollbar.
    const overflow = await frame.locator('html').evaluate((html) => ({
      x: html.scrollWidth - html.clientWidth,
      y: html.scrollHeight - html.clientHeight,
    }));
    expect(overflow.x).toBeLessThanOrEqual(0);
    expect(overflow.y).toBeLessThanOrEqual(0);
    await expect(frame.locator('a.embed-chapter-link')).toHaveAttribute('target', '_blank');
    await page.screenshot({ path: info.outputPath('host-page.png') });
  } finally {
    server.close();
  }
});
