// The demo deck page: one slide at a time, moved with the arrow keys, Page
// Up/Down, Space or the buttons; `#slide=N` in the URL selects a slide, so each
// slide is a deep link (widget state rides along in the same hash).

function readSlide(count: number): number {
  const hash = location.hash.replace(/^#/, '');
  const value = Number.parseInt(
    new URLSearchParams(hash.includes('=') ? hash : '').get('slide') ?? '1',
    10,
  );
  return Number.isFinite(value) ? Math.min(Math.max(value, 1), count) : 1;
}

function writeSlide(slide: number): void {
  const hash = location.hash.replace(/^#/, '');
  const params = new URLSearchParams(hash.includes('=') ? hash : '');
  params.set('slide', String(slide));
  // Keep the query (e.g. ?backend=cpu) so that a slide link reopens the same way.
  history.replaceState(
    history.state,
    '',
    `${location.pathname}${location.search}#${params.toString()}`,
  );
}

export function setupDeck(): void {
  const deck = document.querySelector<HTMLElement>('main.deck');
  if (!deck) return;
  const slides = [...deck.querySelectorAll<HTMLElement>('.deck-slide')];
  if (slides.length === 0) return;
  const current = deck.querySelector('.deck-current');
  const previous = deck.querySelector<HTMLButtonElement>('.deck-previous');
  const next = deck.querySelector<HTMLButtonElement>('.deck-next');
  let index = readSlide(slides.length) - 1;

  const show = (target: number, focus: boolean): void => {
    index = Math.min(Math.max(target, 0), slides.length - 1);
    slides.forEach((slide, i) => {
      slide.hidden = i !== index;
    });
    if (current) current.textContent = String(index + 1);
    if (previous) previous.disabled = index === 0;
    if (next) next.disabled = index === slides.length - 1;
    writeSlide(index + 1);
    if (focus)
      slides[index]?.querySelector<HTMLElement>('.deck-title')?.focus({ preventScroll: true });
  };

  for (const slide of slides)
    slide.querySelector<HTMLElement>('.deck-title')?.setAttribute('tabindex', '-1');
  previous?.addEventListener('click', () => show(index - 1, true));
  next?.addEventListener('click', () => show(index + 1, true));
  document.addEventListener('keydown', (event) => {
    if (event.ctrlKey || event.metaKey || event.altKey || event.defaultPrevented) return;
    const target = event.target as HTMLElement | null;
    // Arrow keys belong to a focused control (a slider, a select); the deck takes them elsewhere.
    if (target?.closest('input, select, textarea, .sb-controls')) return;
    if (['ArrowRight', 'PageDown', ' '].includes(event.key)) {
      show(index + 1, true);
      event.preventDefault();
    } else if (['ArrowLeft', 'PageUp'].includes(event.key)) {
      show(index - 1, true);
      event.preventDefault();
    } else if (event.key === 'Home') {
      show(0, true);
      event.preventDefault();
    } else if (event.key === 'End') {
      show(slides.length - 1, true);
      event.preventDefault();
    }
  });
  show(index, false);
}
