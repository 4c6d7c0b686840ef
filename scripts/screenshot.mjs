// Takes full-page screenshots of book pages in headless Chromium, to look at what
// a student sees:  node scripts/screenshot.mjs URL OUT.png [--dark] [--no-webgpu] [--width=1280] [--selector=CSS] [--viewport] [--top]
import { chromium } from 'playwright-core';
import { CHROMIUM_PATH, NO_WEBGPU_ARGS, WEBGPU_ARGS } from './chromium.mjs';

const [url, out] = process.argv.slice(2).filter((a) => !a.startsWith('--'));
const flags = new Set(process.argv.slice(2).filter((a) => a.startsWith('--')));
const width = Number([...flags].find((f) => f.startsWith('--width='))?.split('=')[1] ?? 1280);
if (!url || !out) {
  console.error(
    'usage: node scripts/screenshot.mjs URL OUT.png [--dark] [--no-webgpu] [--width=N]',
  );
  process.exit(2);
}
const browser = await chromium.launch({
  executablePath: CHROMIUM_PATH,
  args: flags.has('--no-webgpu') ? NO_WEBGPU_ARGS : WEBGPU_ARGS,
});
const page = await browser.newPage({
  viewport: { width, height: 900 },
  colorScheme: flags.has('--dark') ? 'dark' : 'light',
});
page.on('console', (message) => console.log(`[console.${message.type()}] ${message.text()}`));
page.on('pageerror', (error) => console.log(`[pageerror] ${error.message}`));
await page.goto(url);
await page.waitForLoadState('networkidle');
// Every widget is a custom element named sb-*: wait until each visible one has drawn.
const widgetSelector = await page.evaluate(() =>
  [
    ...new Set(
      [...document.querySelectorAll('*')]
        .map((el) => el.localName)
        .filter((n) => n.startsWith('sb-')),
    ),
  ].join(', '),
);
if (widgetSelector) {
  for (const widget of await page.locator(widgetSelector).filter({ visible: true }).all()) {
    await widget.scrollIntoViewIfNeeded();
    await page
      .waitForFunction(
        (el) => Number(el.dataset.rendered ?? 0) > 0 || el.querySelector('.sb-notice--error'),
        await widget.elementHandle(),
        { timeout: 20000 },
      )
      .catch(() => console.log('widget did not render'));
  }
}
if (flags.has('--top')) await page.evaluate(() => window.scrollTo(0, 0));
const selector = [...flags].find((f) => f.startsWith('--selector='))?.slice('--selector='.length);
if (selector) await page.locator(selector).first().screenshot({ path: out });
else await page.screenshot({ path: out, fullPage: !flags.has('--viewport') });
await browser.close();
