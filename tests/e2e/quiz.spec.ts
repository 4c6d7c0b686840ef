// Quizzes as a student meets them: a wrong answer explains itself, the right one is
// confirmed with the explanation, progress survives a reload, a shared link shows
// the same order, the keyboard works, the page passes axe in both themes, and a
// reader without JavaScript finds the answer in the answer key. The right option is
// known here from the Markdown source, never from the page.
import { readdirSync, readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import AxeBuilder from '@axe-core/playwright';
import { expect, test, type Locator, type Page } from '@playwright/test';
import { optionsInPageOrder, parseQuiz, quizKeyOf } from '../../src/book/build/quiz.ts';
import { shuffledIds } from '../../src/book/quizCode.ts';
import { trackErrors } from './support.ts';

const CHAPTER = '02-extinction-and-transmittance';
const PATH = `/chapters/${CHAPTER}.html`;

/** The quizzes of a chapter from its source, in page order (`quiz-1`, `quiz-2`, …). */
function sourceQuizzes(slug: string) {
  const file = fileURLToPath(new URL(`../../chapters/${slug}.md`, import.meta.url));
  const blocks = readFileSync(file, 'utf8').split('```quiz\n').slice(1);
  return blocks.map((block) => {
    const quiz = parseQuiz(block.split('\n```')[0] ?? '', slug);
    const options = optionsInPageOrder(quiz);
    return {
      key: quizKeyOf(quiz),
      ids: options.map((o) => o.id),
      right: options.find((o) => o.correct)!,
      wrong: options.filter((o) => !o.correct),
    };
  });
}

/** A sentence of plain words from Markdown, as the page shows it. */
function plainWords(markdown: string): string {
  return (markdown.match(/[A-Za-z][A-Za-z ,]{24,}/g) ?? []).sort((a, b) => b.length - a.length)[0]!;
}

async function order(quiz: Locator): Promise<string[]> {
  return quiz
    .locator('input[type="radio"]')
    .evaluateAll((inputs) => inputs.map((input) => (input as HTMLInputElement).value));
}

async function answer(page: Page, quiz: Locator, id: string): Promise<void> {
  await quiz.locator(`input[value="${id}"]`).check();
  await quiz.getByRole('button', { name: 'Check answer' }).click();
}

const [milk, slab] = sourceQuizzes(CHAPTER);

/** How many quizzes the chapters hold (the answer key lists each once). */
function sourceQuizCount(): number {
  const dir = fileURLToPath(new URL('../../chapters', import.meta.url));
  return readdirSync(dir)
    .filter((name) => /^\d{2}-.*\.md$/.test(name))
    .reduce(
      (n, name) => n + readFileSync(`${dir}/${name}`, 'utf8').split('```quiz\n').length - 1,
      0,
    );
}

test('a wrong answer shows that option\'s explanation, the right one the explanation, the answer is kept, and "Show the answer" explains', async ({
  page,
}) => {
  const errors = trackErrors(page);
  await page.goto(PATH);
  const quiz = page.locator('#quiz-2');
  await quiz.scrollIntoViewIfNeeded();
  const feedback = quiz.locator('.quiz-feedback');
  await expect(feedback).toHaveAttribute('aria-live', 'polite');
  await expect(feedback).toHaveAttribute('role', 'status');

  for (const wrong of slab!.wrong) {
    await answer(page, quiz, wrong.id);
    await expect(quiz).toHaveClass(/is-wrong/);
    await expect(feedback).toContainText('Not quite');
    await expect(feedback).toContainText(plainWords(wrong.why));
    await expect(quiz.getByRole('button', { name: 'Show the answer' })).toBeVisible();
  }
  await answer(page, quiz, slab!.right.id);
  await expect(quiz).toHaveClass(/is-correct/);
  await expect(feedback).toContainText('Correct');
  await expect(feedback).toContainText('By the multiplicative property');
  await expect(quiz.getByRole('button', { name: 'Show the answer' })).toBeHidden();

  // Checking wrote this quiz's order into the address bar; a reload keeps both.
  const before = await order(quiz);
  await expect.poll(() => page.url()).toMatch(/#.*quiz-2\.order=[0-9a-z]+/);
  await page.reload();
  await expect(page.locator('#quiz-2')).toHaveClass(/is-correct/);
  expect(await order(page.locator('#quiz-2'))).toEqual(before);

  // Quiz 1, untouched so far: "Show the answer" after a wrong try marks the right option
  // and explains it.
  const first = page.locator('#quiz-1');
  await answer(page, first, milk!.wrong[0]!.id);
  await first.getByRole('button', { name: 'Show the answer' }).click();
  await expect(first.locator('li.is-answer input')).toHaveValue(milk!.right.id);
  await expect(first.locator('.quiz-feedback')).toContainText('nine orders of magnitude');
  expect(errors).toEqual([]);
});

test('options are shuffled per load, a deep link reproduces the order, and the keyboard alone can answer', async ({
  page,
  browser,
}) => {
  const orders = new Set<string>();
  for (let load = 0; load < 4; load++) {
    await page.goto(`${PATH}?load=${load}`);
    const quiz = page.locator('#quiz-1');
    const seed = (await quiz.getAttribute('data-seed')) ?? '';
    // The order is the one the seed defines (quizCode.ts), whatever the build wrote.
    expect(await order(quiz)).toEqual(shuffledIds(milk!.ids, seed, milk!.key));
    orders.add((await order(quiz)).join());
  }
  // Four loads of a four-option quiz all in one order: probability (1/24)³.
  expect(orders.size).toBeGreaterThan(1);

  const quiz = page.locator('#quiz-1');
  const sent = await order(quiz);
  const link = (await quiz
    .getByRole('link', { name: 'Link to this question' })
    .getAttribute('href'))!;
  expect(link).toMatch(/#quiz-1\.order=[0-9a-z]+/);
  // Another reader, with nothing stored, opens the shared link.
  const context = await browser.newContext({ serviceWorkers: 'block' });
  const other = await context.newPage();
  await other.goto(link);
  const received = other.locator('#quiz-1');
  expect(await order(received)).toEqual(sent);
  await expect(received).toBeInViewport();
  await context.close();

  // The keyboard alone chooses and checks an answer (quiz 2 of the last load, unanswered).
  const slabQuiz = page.locator('#quiz-2');
  const ids = await order(slabQuiz);
  await slabQuiz.locator('input[type="radio"]').first().focus();
  await page.keyboard.press('Space');
  await page.keyboard.press('ArrowDown');
  await expect(slabQuiz.locator(`input[value="${ids[1]}"]`)).toBeChecked();
  await page.keyboard.press('Tab');
  await expect(slabQuiz.getByRole('button', { name: 'Check answer' })).toBeFocused();
  await page.keyboard.press('Enter');
  await expect(slabQuiz.locator('.quiz-feedback')).toContainText(
    ids[1] === slab!.right.id ? 'Correct' : 'Not quite',
  );
});

/**
 * axe-core's violations inside `include` (the quizzes, or the answer key's frame and
 * first entries), one line each. KaTeX's HTML rendering is left out (the aria-hidden
 * visual copy of the MathML beside it; see axeViolations in support.ts). `colourOnly`:
 * only the rules a theme can change, for the second theme (the rest of WCAG does not
 * depend on colours and ran in the first).
 */
async function scopedAxe(page: Page, include: string[], colourOnly = false): Promise<string[]> {
  await page.evaluate(() => document.fonts.ready.then(() => undefined));
  let builder = new AxeBuilder({ page });
  for (const selector of include) builder = builder.include(selector);
  builder = builder.exclude('.katex-html');
  const results = await (
    colourOnly
      ? builder.withRules(['color-contrast', 'link-in-text-block'])
      : builder.withTags(['wcag2a', 'wcag2aa'])
  ).analyze();
  return results.violations.map(
    (v) => `${v.id}: ${v.nodes.map((n) => n.target.join(' ')).join(', ')}`,
  );
}

/** Switches the page's theme with its own button, as a reader does. */
async function switchTheme(page: Page, theme: 'light' | 'dark'): Promise<void> {
  await page.locator('.theme-toggle').click();
  await expect(page.locator('html')).toHaveAttribute('data-theme', theme);
}

// One load of the chapter for the page before any answer and for axe in both themes,
// before and after answering: the light theme gets the full WCAG A/AA rule set, the dark
// theme the colour rules (the other rules do not depend on the theme).
test('before an answer the page holds no marker of the right option and no explanation; quizzes pass axe in both themes, before and after answering', async ({
  page,
}) => {
  // axe over KaTeX-heavy markup takes tens of seconds on a loaded two-core machine.
  test.setTimeout(240_000);
  await page.emulateMedia({ colorScheme: 'light' });
  await page.goto(PATH);
  await expect(page.locator('form.quiz')).toHaveCount(2);
  await expect(page.locator('[data-correct]')).toHaveCount(0);
  const html = await page.content();
  for (const option of [...slab!.wrong, ...milk!.wrong])
    expect(html).not.toContain(plainWords(option.why));
  expect(html).not.toContain('By the multiplicative property');
  // The radio group is named by its legend.
  const group = page.locator('#quiz-2 fieldset');
  await expect(group.locator('legend')).toContainText('twice as thick');

  const quizzes = ['form.quiz'];
  expect(await scopedAxe(page, quizzes), 'light theme, before answering').toEqual([]);
  await switchTheme(page, 'dark');
  expect(await scopedAxe(page, quizzes, true), 'dark theme, before answering').toEqual([]);
  await answer(page, page.locator('#quiz-2'), slab!.wrong[0]!.id);
  await answer(page, page.locator('#quiz-1'), milk!.right.id);
  await expect(page.locator('#quiz-2')).toHaveClass(/is-wrong/);
  await expect(page.locator('#quiz-1')).toHaveClass(/is-correct/);
  expect(await scopedAxe(page, quizzes, true), 'dark theme, after answering').toEqual([]);
  await switchTheme(page, 'light');
  expect(await scopedAxe(page, quizzes), 'light theme, after answering').toEqual([]);
});

test('the answer key passes axe in both themes, with an answer open', async ({ page }) => {
  // axe over KaTeX-heavy markup takes tens of seconds on a loaded two-core machine.
  test.setTimeout(180_000);
  await page.emulateMedia({ colorScheme: 'light' });
  await page.goto('/appendix/answers.html');
  await expect(page.locator('section.answer')).toHaveCount(sourceQuizCount());
  await page.locator('section.answer summary').first().click();
  // The page is long (every quiz's KaTeX); the first chapter's entries and the page
  // frame carry every kind of element it has.
  const scope = ['header', 'nav', '[id="answers-chapter-1"]', '[id^="01-"]', '[id^="02-"]'];
  expect(await scopedAxe(page, scope), 'light theme').toEqual([]);
  await switchTheme(page, 'dark');
  expect(await scopedAxe(page, scope, true), 'dark theme').toEqual([]);
});

test.describe('without JavaScript', () => {
  test.use({ javaScriptEnabled: false });
  test('a quiz links to its folded answer in the answer key', async ({ page }) => {
    await page.goto(PATH);
    const quiz = page.locator('#quiz-2');
    await expect(quiz.getByRole('button', { name: 'Check answer' })).toBeHidden();
    const link = quiz.getByRole('link', { name: /see the answer/ });
    await expect(link).toBeVisible();
    await link.click();
    await expect(page).toHaveURL(/appendix\/answers\.html#02-extinction-and-transmittance-quiz-2$/);
    const entry = page.locator('[id="02-extinction-and-transmittance-quiz-2"]');
    await expect(entry.locator('.answer-right')).toBeHidden();
    await entry.getByText('Show the answer').click();
    await expect(entry.locator('.answer-right')).toContainText('0.25');
    await expect(entry).toContainText(plainWords(slab!.wrong[0]!.why));
  });
});
