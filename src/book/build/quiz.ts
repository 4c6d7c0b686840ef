// Quizzes: a fenced block with info string `quiz` becomes a radio group that is
// checked in place by src/book/quiz.ts, and an entry of the answer key
// (appendix/answers.html), which is where a reader without JavaScript finds the
// answer. Syntax, one item per line:
//
//   ? question                  (Markdown inline; more `?` lines continue it)
//   + the right option          (exactly one)
//   - a wrong option            (at least one)
//     > why it is wrong         (indented; required under every `-`: the
//     > more of it                misconception the option reflects)
//   > explanation               (the right answer's explanation, Markdown)
//
// Every `>` line, indented or not, is a paragraph of its own.
//
// The order in the source does not matter: options are identified by a hash of
// their text (quizCode.ts), written in the order of those hashes and shuffled per
// page load by the script. The page never says in plain text which option is right:
// each option's feedback is encoded (why: quizCode.ts) by sealQuizzes(), which runs
// on the finished page, after equation references and links have been resolved.
import { deflateRawSync } from 'node:zlib';
import type MarkdownIt from 'markdown-it';
import type { RenderEnv } from './markdown.ts';
import { blobKey, hashString, optionId, sealBytes, type OptionFeedback } from '../quizCode.ts';

export interface QuizOption {
  text: string;
  correct: boolean;
  /** Why a wrong option is wrong (Markdown); empty for the right one. */
  why: string;
  /** Line of the option in the source file (1-based). */
  line: number;
}

export interface Quiz {
  question: string;
  options: QuizOption[];
  explanation: string;
  /** Line of the first line of the quiz in the source file (1-based). */
  line: number;
}

/**
 * Parses the body of a ```quiz block. `firstLine` is the line of the block's first
 * body line in `where`, so that every error names the file and line to fix.
 */
export function parseQuiz(source: string, where: string, firstLine = 1): Quiz {
  let question = '';
  const options: QuizOption[] = [];
  const explanation: string[] = [];
  const at = (line: number): string => `${where}:${line}`;
  source.split('\n').forEach((raw, index) => {
    const lineNumber = firstLine + index;
    const line = raw.trimEnd();
    if (line.trim() === '') return;
    const indented = /^\s/.test(line);
    const marker = line.trimStart()[0];
    const rest = line.trimStart().slice(1).trim();
    if (indented) {
      if (marker !== '>')
        throw new Error(`${at(lineNumber)}: an indented quiz line must be "  > why": "${line}"`);
      const option = options[options.length - 1];
      if (!option || explanation.length > 0)
        throw new Error(`${at(lineNumber)}: "  > why" must follow the option it explains`);
      if (option.correct)
        throw new Error(
          `${at(lineNumber)}: the right option is explained by the quiz's unindented "> " lines, not by "  > why"`,
        );
      option.why = option.why ? `${option.why}\n\n${rest}` : rest;
      return;
    }
    if (marker === '?') question = question ? `${question} ${rest}` : rest;
    else if (marker === '+' || marker === '-') {
      if (explanation.length > 0)
        throw new Error(`${at(lineNumber)}: options must come before the "> explanation"`);
      options.push({ text: rest, correct: marker === '+', why: '', line: lineNumber });
    } else if (marker === '>') explanation.push(line.slice(1).replace(/^ /, ''));
    else throw new Error(`${at(lineNumber)}: quiz line must start with ?, +, - or >: "${line}"`);
  });
  if (!question) throw new Error(`${at(firstLine)}: quiz has no "? question" line`);
  if (options.length < 2) throw new Error(`${at(firstLine)}: quiz needs at least two options`);
  const correct = options.filter((option) => option.correct).length;
  if (correct !== 1)
    throw new Error(`${at(firstLine)}: quiz needs exactly one "+" option, has ${correct}`);
  for (const option of options) {
    if (!option.correct && !option.why)
      throw new Error(
        `${at(option.line)}: wrong option "${option.text}" needs an indented "  > why" line ` +
          `saying why it is wrong`,
      );
  }
  const texts = new Set(options.map((option) => option.text));
  if (texts.size !== options.length) throw new Error(`${at(firstLine)}: two options are the same`);
  if (explanation.length === 0) throw new Error(`${at(firstLine)}: quiz needs a "> explanation"`);
  // Each `>` line is a paragraph (as the chapters write them: one idea per line).
  return { question, options, explanation: explanation.join('\n\n'), line: firstLine };
}

/** A quiz of a chapter, rendered for the answer key. */
export interface AnswerKeyEntry {
  /** The quiz's anchor on its chapter page, e.g. `quiz-2`. */
  id: string;
  questionHtml: string;
  rightHtml: string;
  explanationHtml: string;
  wrong: { textHtml: string; whyHtml: string }[];
}

/** The key that ties option ids and blobs to one quiz: a hash of its question. */
export function quizKeyOf(quiz: Pick<Quiz, 'question'>): string {
  return hashString(quiz.question).toString(36);
}

/** The options with their ids, in the order the page lists them: sorted by id. */
export function optionsInPageOrder(quiz: Quiz): (QuizOption & { id: string })[] {
  const key = quizKeyOf(quiz);
  return quiz.options
    .map((option) => ({ ...option, id: optionId(key, option.text) }))
    .sort((a, b) => (a.id < b.id ? -1 : a.id > b.id ? 1 : 0));
}

function escapeAttribute(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/"/g, '&quot;').replace(/</g, '&lt;');
}

/**
 * The quiz as HTML, with each option's feedback still in plain text in a
 * `<template data-quiz-seal>` that sealQuizzes() encodes once the page is finished.
 */
export function renderQuiz(md: MarkdownIt, quiz: Quiz, env: RenderEnv): string {
  env.quizCount += 1;
  const id = `quiz-${env.quizCount}`;
  const key = quizKeyOf(quiz);
  const ids = new Set<string>();
  const options = optionsInPageOrder(quiz);
  for (const option of options) {
    if (ids.has(option.id)) throw new Error(`${env.file}:${option.line}: two options hash alike`);
    ids.add(option.id);
  }
  const right = options.find((option) => option.correct);
  const questionHtml = md.renderInline(quiz.question, env);
  const explanationHtml = md.render(quiz.explanation, env);
  env.quizzes.push({
    id,
    questionHtml,
    rightHtml: right ? md.renderInline(right.text, env) : '',
    explanationHtml,
    wrong: options
      .filter((option) => !option.correct)
      .map((option) => ({
        textHtml: md.renderInline(option.text, env),
        whyHtml: md.render(option.why, env),
      })),
  });
  const items = options
    .map(
      (option) =>
        `<li data-option="${option.id}"><label><input type="radio" name="${id}" value="${option.id}">` +
        ` <span class="quiz-option-text">${md.renderInline(option.text, env)}</span></label>` +
        `<template data-quiz-seal="${option.id}"${option.correct ? ' data-quiz-right' : ''}>` +
        `${option.correct ? '' : md.render(option.why, env)}</template></li>`,
    )
    .join('');
  const answers = `/appendix/answers.html#${answerAnchor(env.page, id)}`;
  return (
    `<form class="quiz" id="${id}" data-quiz="${key}" aria-labelledby="${id}-question">` +
    `<fieldset class="quiz-fieldset">` +
    `<legend class="quiz-question" id="${id}-question"><span class="quiz-kicker">Question</span> ` +
    `${questionHtml}</legend>` +
    `<ul class="quiz-options">${items}</ul></fieldset>` +
    `<template data-quiz-seal="explanation">${explanationHtml}</template>` +
    `<div class="quiz-actions" hidden><button type="submit" class="button">Check answer</button>` +
    `<button type="button" class="sb-button quiz-reveal" hidden>Show the answer</button>` +
    `<a class="quiz-link" href="#${id}">Link to this question</a></div>` +
    `<div class="quiz-feedback" role="status" aria-live="polite"></div>` +
    `<noscript><p class="quiz-noscript">Without JavaScript this page cannot check an answer. ` +
    `Choose one, then <a href="${answers}">see the answer and why each other option is wrong</a> ` +
    `in the answer key.</p></noscript>` +
    `</form>`
  );
}

/** The anchor of a quiz in the answer key: the chapter's slug and the quiz's id. */
export function answerAnchor(page: string, quizId: string): string {
  const slug = page.replace(/^.*\//, '').replace(/\.html$/, '');
  return `${slug}-${quizId}`;
}

function deflate(text: string): Uint8Array {
  return deflateRawSync(new TextEncoder().encode(text), { level: 9 });
}

const FORM = /<form class="quiz" id="([^"]+)" data-quiz="([^"]+)"([^>]*)>([\s\S]*?)<\/form>/g;
const SEAL = /<template data-quiz-seal="([^"]+)"( data-quiz-right)?>([\s\S]*?)<\/template>/g;

/**
 * Encodes the feedback of every quiz on a finished page (see quizCode.ts for why
 * and how far): each option's `<template>` becomes a `data-feedback` blob on its
 * input, all of one length, and the explanation a `data-explanation` blob on the
 * form keyed by the right option. `file` names the page in errors.
 */
export function sealQuizzes(html: string, file: string): string {
  return html.replace(FORM, (_all, id: string, key: string, attrs: string, body: string) => {
    const feedback = new Map<string, OptionFeedback>();
    let explanation = '';
    let rightId = '';
    const rest = body.replace(
      SEAL,
      (_t, sealId: string, right: string | undefined, inner: string) => {
        if (sealId === 'explanation') explanation = inner;
        else {
          feedback.set(sealId, right ? { c: 1 } : { c: 0, h: inner });
          if (right) rightId = sealId;
        }
        return '';
      },
    );
    if (!rightId || !explanation)
      throw new Error(`${file}: quiz ${id} has no right option or explanation`);
    const packed = new Map(
      [...feedback].map(([option, value]) => [option, deflate(JSON.stringify(value))]),
    );
    const longest = Math.max(...[...packed.values()].map((bytes) => bytes.length));
    const sealed = rest.replace(
      /<input type="radio" name="([^"]+)" value="([^"]+)">/g,
      (input, _name: string, value: string) => {
        const bytes = packed.get(value);
        if (bytes === undefined)
          throw new Error(`${file}: quiz ${id} option ${value} has no feedback`);
        const blob = sealBytes(bytes, blobKey(key, value, 'option'), longest);
        return input.replace('>', ` data-feedback="${blob}">`);
      },
    );
    const explanationBlob = sealBytes(deflate(explanation), blobKey(key, rightId, 'explanation'));
    return (
      `<form class="quiz" id="${id}" data-quiz="${key}"${attrs} ` +
      `data-explanation="${escapeAttribute(explanationBlob)}">${sealed}</form>`
    );
  });
}

/** The answer key page's body: every chapter's quizzes with all their feedback in plain text. */
export function renderAnswerKey(
  chapters: { title: string; number: number; page: string; quizzes: AnswerKeyEntry[] }[],
): string {
  const sections = chapters
    .filter((chapter) => chapter.quizzes.length > 0)
    .map((chapter) => {
      const entries = chapter.quizzes
        .map((quiz, index) => {
          const wrong = quiz.wrong
            .map(
              (option) =>
                `<li><p class="answer-option">${option.textHtml}</p>` +
                `<div class="answer-why">${option.whyHtml}</div></li>`,
            )
            .join('');
          return (
            `<section class="answer" id="${answerAnchor(chapter.page, quiz.id)}">` +
            `<h3>Question ${chapter.number}.${index + 1}</h3>` +
            `<p class="answer-question">${quiz.questionHtml} ` +
            `<a href="${chapter.page}#${quiz.id}">Back to the question</a></p>` +
            `<details class="answer-details"><summary>Show the answer</summary>` +
            `<p class="answer-right"><strong>Answer:</strong> ${quiz.rightHtml}</p>` +
            `${quiz.explanationHtml}` +
            `<p><strong>The other options, and why they are wrong:</strong></p>` +
            `<ul class="answer-wrong">${wrong}</ul></details></section>`
          );
        })
        .join('\n');
      const heading = `Chapter ${chapter.number}: ${chapter.title}`;
      return `<h2 id="answers-chapter-${chapter.number}">${heading}</h2>\n${entries}`;
    })
    .join('\n');
  return (
    `<p>The answers to the questions in the chapters, for readers whose browser does not run ` +
    `the page's script, and for review. Each answer stays folded until you open it; every ` +
    `wrong option comes with the misconception behind it.</p>\n${sections}`
  );
}
