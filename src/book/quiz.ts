// In-page checking of the quizzes rendered by build/quiz.ts. The chosen answer is
// kept in localStorage so that a student's progress survives a reload.

function storageKey(form: HTMLFormElement): string {
  return `scatterbook:quiz:${location.pathname}#${form.id}`;
}

function check(form: HTMLFormElement, announce: boolean): void {
  const chosen = form.querySelector<HTMLInputElement>('input[type="radio"]:checked');
  const feedback = form.querySelector<HTMLElement>('.quiz-feedback');
  if (!chosen || !feedback) {
    if (feedback && announce) feedback.textContent = 'Choose an answer first.';
    return;
  }
  const correct = chosen.hasAttribute('data-correct');
  form.classList.toggle('is-correct', correct);
  form.classList.toggle('is-wrong', !correct);
  for (const item of form.querySelectorAll('li'))
    item.classList.toggle('is-chosen', item.contains(chosen));
  feedback.textContent = correct
    ? 'Correct. The explanation below says why.'
    : 'Not quite. Try another answer, or open the explanation.';
  const explanation = form.querySelector<HTMLDetailsElement>('.quiz-explanation');
  if (explanation && correct) explanation.open = true;
  try {
    localStorage.setItem(storageKey(form), chosen.value);
  } catch {
    // Storage may be unavailable; checking still works.
  }
}

export function setupQuizzes(): void {
  for (const form of document.querySelectorAll<HTMLFormElement>('form.quiz')) {
    form.addEventListener('submit', (event) => {
      event.preventDefault();
      check(form, true);
    });
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
      check(form, false);
    }
  }
}
