// Quizzes: the syntax and its errors (file and line), every chapter's quizzes with
// an explanation for each wrong option, the seeded shuffle, and the built pages,
// which must not give the answer away before the student answers.
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { buildBook } from '../../src/book/build/generate.ts';
import { parseChapter } from '../../src/book/build/chapters.ts';
import { createMarkdown, renderChapterBody } from '../../src/book/build/markdown.ts';
import { optionsInPageOrder, parseQuiz, quizKeyOf, type Quiz } from '../../src/book/build/quiz.ts';
import {
  blobKey,
  openBlob,
  optionId,
  randomSeed,
  SEED_PATTERN,
  shuffledIds,
  type OptionFeedback,
} from '../../src/book/quizCode.ts';

const ROOT = fileURLToPath(new URL('../..', import.meta.url));
const CHAPTERS = join(ROOT, 'chapters');

/** Every ```quiz block of the chapters, parsed, with the file and line it starts at. */
function chapterQuizzes(): { file: string; quiz: Quiz }[] {
  const found: { file: string; quiz: Quiz }[] = [];
  for (const name of readdirSync(CHAPTERS)
    .filter((n) => /^\d{2}-.*\.md$/.test(n))
    .sort()) {
    const lines = readFileSync(join(CHAPTERS, name), 'utf8').split('\n');
    lines.forEach((line, index) => {
      if (line.trim() !== '```quiz') return;
      const end = lines.findIndex((l, j) => j > index && l.trim() === '```');
      const body = lines.slice(index + 1, end).join('\n');
      found.push({ file: name, quiz: parseQuiz(body, name, index + 2) });
    });
  }
  return found;
}

function render(body: string, file = 'test.md') {
  return renderChapterBody(createMarkdown(), body, 7, '/chapters/07-test.html', file);
}

const SIMPLE = [
  '? Q?',
  '+ right',
  '- wrong',
  '  > because',
  '- other',
  '  > why not',
  '> explained',
];

describe('quiz syntax', () => {
  it('parses the question, the options with their reasons, and the explanation', () => {
    const quiz = parseQuiz([...SIMPLE, '> more'].join('\n'), 'f.md', 10);
    expect(quiz.question).toBe('Q?');
    expect(quiz.options.map((o) => [o.text, o.correct, o.why, o.line])).toEqual([
      ['right', true, '', 11],
      ['wrong', false, 'because', 12],
      ['other', false, 'why not', 14],
    ]);
    expect(quiz.explanation).toBe('explained\n\nmore');
  });

  it('keeps several "  > why" lines of one option as paragraphs', () => {
    const quiz = parseQuiz('? Q\n+ a\n- b\n  > one\n  > two\n> e', 'f.md');
    expect(quiz.options[1]?.why).toBe('one\n\ntwo');
  });

  it('requires a reason for every wrong option, naming the file and line of the option', () => {
    expect(() => parseQuiz('? Q\n+ a\n- b\n  > ok\n- c\n> e', 'ch.md', 20)).toThrow(
      /^ch\.md:24: wrong option "c" needs an indented " {2}> why"/,
    );
  });

  it('rejects malformed quizzes with the file and line', () => {
    expect(() => parseQuiz('? Q\n- a\n  > x\n- b\n  > y\n> e', 'f.md')).toThrow(/exactly one/);
    expect(() => parseQuiz('? Q\n+ a\n+ b\n> e', 'f.md')).toThrow(/exactly one/);
    expect(() => parseQuiz('? Q\n+ a\n- b\n  > x', 'f.md')).toThrow(/explanation/);
    expect(() => parseQuiz('? Q\n+ a\n* b\n> e', 'f.md', 5)).toThrow(/^f\.md:7: .*must start/);
    expect(() => parseQuiz('? Q\n+ a\n  > x\n- b\n  > y\n> e', 'f.md')).toThrow(
      /^f\.md:3: the right option/,
    );
    expect(() => parseQuiz('? Q\n+ a\n- b\n  > y\n> e\n- c\n  > z', 'f.md')).toThrow(
      /^f\.md:6: options must come before/,
    );
    expect(() => parseQuiz('? Q\n+ a\n- a\n  > y\n> e', 'f.md')).toThrow(/same/);
  });

  it('a chapter whose quiz lacks a reason fails the build with the line in the chapter file', () => {
    const source = [
      '---',
      'title: T',
      'summary: S',
      '---',
      '',
      'Text.',
      '',
      '```quiz',
      '? Q?',
      '+ right',
      '- wrong',
      '> explained',
      '```',
      '',
    ].join('\n');
    const chapter = parseChapter('chapters/07-test.md', source);
    expect(() =>
      renderChapterBody(
        createMarkdown(),
        chapter.body,
        7,
        '/chapters/07-test.html',
        chapter.file,
        undefined,
        chapter.bodyOffset,
      ),
    ).toThrow(/^chapters\/07-test\.md:11: wrong option "wrong"/);
  });
});

describe("the chapters' quizzes", () => {
  const quizzes = chapterQuizzes();

  it('all parse, and every wrong option says why it is wrong', () => {
    expect(quizzes.length).toBeGreaterThanOrEqual(21);
    for (const { file, quiz } of quizzes) {
      expect(quiz.options.length, `${file}:${quiz.line}`).toBeGreaterThanOrEqual(3);
      for (const option of quiz.options.filter((o) => !o.correct))
        expect(option.why.length, `${file}:${option.line}`).toBeGreaterThan(40);
    }
  });

  it('explanations do not point at options by their position, which the shuffle changes', () => {
    for (const { file, quiz } of quizzes) {
      const text = [quiz.explanation, ...quiz.options.map((o) => o.why)].join('\n');
      expect(text, `${file}:${quiz.line}`).not.toMatch(
        /\b(first|second|third|fourth|last) (answer|option)\b/i,
      );
    }
  });

  it('the shuffle is a permutation, the same for the same seed, and puts the right option everywhere', () => {
    const seeds = Array.from({ length: 600 }, (_, i) => `s${i.toString(36)}`);
    for (const { file, quiz } of quizzes) {
      const key = quizKeyOf(quiz);
      const ids = quiz.options.map((o) => optionId(key, o.text));
      const right = optionId(key, quiz.options.find((o) => o.correct)?.text ?? '');
      const counts = new Array<number>(ids.length).fill(0);
      const orders = new Set<string>();
      for (const seed of seeds) {
        const order = shuffledIds(ids, seed, key);
        expect([...order].sort()).toEqual([...ids].sort());
        expect(shuffledIds([...ids].reverse(), seed, key)).toEqual(order);
        orders.add(order.join());
        counts[order.indexOf(right)] = (counts[order.indexOf(right)] ?? 0) + 1;
      }
      // Uniform would be 600/n per position (150 for four options); ±50 % is a
      // loose bound that a stuck or biased shuffle still fails.
      for (const count of counts)
        expect(count, `${file}:${quiz.line} ${counts.join(',')}`).toBeGreaterThan(
          (0.5 * seeds.length) / ids.length,
        );
      expect(orders.size, `${file}:${quiz.line}`).toBe(
        [1, 1, 2, 6, 24, 120][ids.length] ?? orders.size,
      );
    }
  });

  it('random seeds are short base-36 strings that a link may carry', () => {
    for (let i = 0; i < 50; i++) expect(randomSeed()).toMatch(SEED_PATTERN);
    expect(randomSeed(() => 0)).toBe('000000');
  });

  it('the order on the page depends on the options, not on the order the author wrote them in', () => {
    const forward = render(['```quiz', ...SIMPLE, '```', ''].join('\n')).html;
    const swapped = ['? Q?', '- other', '  > why not', '- wrong', '  > because', '+ right'];
    const backward = render(['```quiz', ...swapped, '> explained', '```', ''].join('\n')).html;
    expect(backward).toBe(forward);
  });
});

describe('the built pages', () => {
  const book = buildBook(ROOT);
  const quizzes = chapterQuizzes();

  it('carry no answer marker: no data-correct, no unsealed feedback', () => {
    for (const page of book.pages) {
      expect(page.html, page.file).not.toMatch(/data-correct|data-quiz-seal|data-quiz-right/);
      expect(page.html, page.file).not.toMatch(/is-correct|is-answer/);
    }
  });

  it('hold no explanation text of any quiz; the answer key holds all of it', () => {
    const answers = book.pages.find((page) => page.file === 'appendix/answers.html')?.html ?? '';
    for (const { file, quiz } of quizzes) {
      const page = book.pages.find((p) => p.file === `chapters/${file.replace(/\.md$/, '.html')}`);
      expect(page, file).toBeDefined();
      const texts = [quiz.explanation, ...quiz.options.map((o) => o.why)].filter(Boolean);
      for (const text of texts) {
        // A run of plain words from the Markdown, long enough to be unique.
        const words = (text.match(/[A-Za-z][A-Za-z ,]{24,}/g) ?? []).sort(
          (a, b) => b.length - a.length,
        )[0];
        expect(words, `${file}:${quiz.line}`).toBeDefined();
        expect(page?.html, `${file}:${quiz.line}: "${words}"`).not.toContain(words);
        expect(answers, `${file}:${quiz.line}: "${words}"`).toContain(words);
      }
    }
  });

  it('encode each option so that exactly the right one decodes as right, with equal-length blobs', async () => {
    let checked = 0;
    for (const { file, quiz } of quizzes) {
      const page = book.pages.find((p) => p.file === `chapters/${file.replace(/\.md$/, '.html')}`);
      const key = quizKeyOf(quiz);
      const form = new RegExp(`<form class="quiz" [^>]*data-quiz="${key}"[^>]*>`).exec(
        page?.html ?? '',
      )?.[0];
      expect(form, `${file}:${quiz.line}`).toBeDefined();
      const explanation = /data-explanation="([^"]+)"/.exec(form ?? '')?.[1] ?? '';
      const blobs = new Map<string, string>();
      for (const match of (page?.html ?? '').matchAll(
        /<input type="radio" name="[^"]+" value="([^"]+)" data-feedback="([^"]+)">/g,
      ))
        blobs.set(match[1] ?? '', match[2] ?? '');
      const options = optionsInPageOrder(quiz);
      expect(new Set(options.map((o) => blobs.get(o.id)?.length)).size, file).toBe(1);
      for (const option of options) {
        const blob = blobs.get(option.id);
        expect(blob, `${file}:${option.line}`).toBeDefined();
        const feedback = JSON.parse(
          await openBlob(blob ?? '', blobKey(key, option.id, 'option')),
        ) as OptionFeedback;
        expect(feedback.c === 1, `${file}:${option.line}`).toBe(option.correct);
        if (!option.correct) expect(feedback.h, `${file}:${option.line}`).toMatch(/^<p>/);
        if (option.correct) {
          const html = await openBlob(explanation, blobKey(key, option.id, 'explanation'));
          expect(html, `${file}:${quiz.line}`).toMatch(/^<p>/);
        }
        checked += 1;
      }
    }
    expect(checked).toBeGreaterThanOrEqual(84);
  });

  it('list the options in an order that does not reveal the right one', () => {
    const positions = quizzes.map(({ quiz }) =>
      optionsInPageOrder(quiz).findIndex((option) => option.correct),
    );
    // The page order is the order of the options' hashes: across the book the right
    // option sits in several places, not in one the author chose.
    expect(new Set(positions).size).toBeGreaterThanOrEqual(3);
  });

  it('link every quiz to its entry in the answer key, for readers without JavaScript', () => {
    const answers = book.pages.find((page) => page.file === 'appendix/answers.html')?.html ?? '';
    let links = 0;
    for (const page of book.pages.filter((p) => p.file.startsWith('chapters/'))) {
      for (const match of page.html.matchAll(/<noscript>.*?href="([^"]+)"/g)) {
        const anchor = (match[1] ?? '').split('#')[1] ?? '';
        expect(answers, `${page.file} → #${anchor}`).toContain(`id="${anchor}"`);
        links += 1;
      }
    }
    expect(links).toBe(quizzes.length);
  });
});
