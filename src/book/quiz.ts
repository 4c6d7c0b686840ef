// In-page checking of the quizzes rendered by build/quiz.ts.
//
// Order: every page load shuffles each quiz's options with a fresh seed. The seed
// lives in the URL hash in the widgets' format (urlState.ts), `#quiz-2.order=k7f2qa`:
// "Link to this question" carries it, and checking an answer writes it into the
// address bar, so a link shared from either shows the same order to the reader who
// opens it. A hash without a seed for a quiz (or a plain `#quiz-2`) gets a new one.
//
// Feedback: the page holds each option's feedback encoded (quizCode.ts); it is
// decoded only for the option the student submits. The chosen option is kept in
// localStorage, so a student's progress survives a reload.
import {
  blobKey,
  openBlob,
  randomSeed,
  SEED_PATTERN,
  shuffledIds,
  type OptionFeedback,
} from './quizCode.ts';
import { readWidgetState, widgetLink, writeWidgetState } from '../widgets/base/urlState.ts';

const ORDER_KEY = 'order';

function storageKey(form: HTMLFormElement): string {
  return `scatterbook:quiz:${location.pathname}#${form.id}`;
}

function cryptoRandom(): number {
  const values = new Uint32Array(1);
  crypto.getRandomValues(values);
  return (values[0] ?? 0) / 4294967296;
}

/** The seed a link asks for, or a new one for this load. */
function seedFor(form: HTMLFormElement): { seed: string; fromLink: boolean } {
  const linked = readWidgetState(form.id).get(ORDER_KEY);
  if (linked && SEED_PATTERN.test(linked)) return { seed: linked, fromLink: true };
  return { seed: randomSeed(cryptoRandom), fromLink: false };
}

function items(form: HTMLFormElement): HTMLLIElement[] {
  return [...form.querySelectorAll<HTMLLIElement>('.quiz-options > li[data-option]')];
}

/** Puts the options in the order of `seed` (quizCode.ts: shuffledIds). */
export function applyOrder(form: HTMLFormElement, seed: string): void {
  const list = form.querySelector('.quiz-options');
  const byId = new Map(items(form).map((item) => [item.dataset['option'] ?? '', item]));
  if (!list) return;
  for (const id of shuffledIds([...byId.keys()], seed, form.dataset['quiz'] ?? ''))
    list.append(byId.get(id) as HTMLLIElement);
}

async function feedbackOf(form: HTMLFormElement, input: HTMLInputElement): Promise<OptionFeedback> {
  const blob = input.dataset['feedback'] ?? '';
  const key = blobKey(form.dataset['quiz'] ?? '', input.value, 'option');
  return JSON.parse(await openBlob(blob, key)) as OptionFeedback;
}

async function explanationOf(form: HTMLFormElement, rightInput: HTMLInputElement): Promise<string> {
  const key = blobKey(form.dataset['quiz'] ?? '', rightInput.value, 'explanation');
  return await openBlob(form.dataset['explanation'] ?? '', key);
}

function optionText(input: HTMLInputElement): string {
  return input.closest('label')?.querySelector('.quiz-option-text')?.innerHTML ?? '';
}

function showFeedback(form: HTMLFormElement, verdict: string, html: string): void {
  const region = form.querySelector<HTMLElement>('.quiz-feedback');
  if (!region) return;
  // The HTML is the book's own, written at build time (build/quiz.ts), never user input.
  region.innerHTML = `<p class="quiz-verdict">${verdict}</p>${html ? `<div class="quiz-why">${html}</div>` : ''}`;
}

async function check(form: HTMLFormElement, seed: string, announce: boolean): Promise<void> {
  const chosen = form.querySelector<HTMLInputElement>('input[type="radio"]:checked');
  if (!chosen) {
    if (announce) showFeedback(form, 'Choose an answer first.', '');
    return;
  }
  const feedback = await feedbackOf(form, chosen);
  const correct = feedback.c === 1;
  form.classList.toggle('is-correct', correct);
  form.classList.toggle('is-wrong', !correct);
  form.classList.remove('is-revealed');
  for (const item of items(form)) {
    const isChosen = item.contains(chosen);
    item.classList.toggle('is-chosen', isChosen);
    if (isChosen && !correct) item.classList.add('is-tried');
    item.classList.remove('is-answer');
  }
  if (correct) showFeedback(form, 'Correct.', await explanationOf(form, chosen));
  else
    showFeedback(
      form,
      'Not quite.',
      `${feedback.h ?? ''}<p class="quiz-hint">Try another option, or show the answer.</p>`,
    );
  const reveal = form.querySelector<HTMLButtonElement>('.quiz-reveal');
  if (reveal) reveal.hidden = correct;
  if (announce) {
    // The address bar now reproduces this order too (see the top of this file).
    writeWidgetState(form.id, [[ORDER_KEY, seed]]);
    try {
      localStorage.setItem(storageKey(form), chosen.value);
    } catch {
      // Storage may be unavailable; checking still works.
    }
  }
}

/** After a wrong try, on request: which option is right, and why. */
async function reveal(form: HTMLFormElement): Promise<void> {
  const inputs = [...form.querySelectorAll<HTMLInputElement>('input[type="radio"]')];
  const feedback = await Promise.all(inputs.map((input) => feedbackOf(form, input)));
  const right = inputs[feedback.findIndex((option) => option.c === 1)];
  if (!right) return;
  form.classList.add('is-revealed');
  for (const item of items(form)) item.classList.toggle('is-answer', item.contains(right));
  showFeedback(form, `The answer is: ${optionText(right)}`, await explanationOf(form, right));
}

function escapeHtml(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
}

/** A blob that does not decode (a page from another build, say) is reported in the quiz, not thrown. */
async function safely(form: HTMLFormElement, work: Promise<void>): Promise<void> {
  try {
    await work;
  } catch (error) {
    showFeedback(
      form,
      'This question could not be checked.',
      `<p class="quiz-hint">${escapeHtml(error instanceof Error ? error.message : String(error))}. ` +
        `Reload the page; the answer key lists every answer.</p>`,
    );
  }
}

function setupQuiz(form: HTMLFormElement): boolean {
  const { seed, fromLink } = seedFor(form);
  form.dataset['seed'] = seed;
  applyOrder(form, seed);
  const actions = form.querySelector<HTMLElement>('.quiz-actions');
  if (actions) actions.hidden = false;
  const link = form.querySelector<HTMLAnchorElement>('.quiz-link');
  if (link) link.href = widgetLink(form.id, [[ORDER_KEY, seed]]);
  form.addEventListener('submit', (event) => {
    event.preventDefault();
    void safely(form, check(form, seed, true));
  });
  form
    .querySelector('.quiz-reveal')
    ?.addEventListener('click', () => void safely(form, reveal(form)));
  let saved: string | null = null;
  try {
    saved = localStorage.getItem(storageKey(form));
  } catch {
    saved = null;
  }
  const input =
    saved === null
      ? null
      : form.querySelector<HTMLInputElement>(`input[value="${CSS.escape(saved)}"]`);
  if (input) {
    input.checked = true;
    void safely(form, check(form, seed, false));
  }
  return fromLink;
}

export function setupQuizzes(): void {
  let linked: HTMLFormElement | null = null;
  for (const form of document.querySelectorAll<HTMLFormElement>('form.quiz'))
    if (setupQuiz(form) && !linked) linked = form;
  // `#quiz-2.order=…` names no element, so the browser does not scroll to the quiz.
  linked?.scrollIntoView({ block: 'start' });
}
