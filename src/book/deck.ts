// The lecture deck page: one slide at a time, moved with the arrow keys, Page
// Up/Down, Space, Home/End, the buttons or the slide number field; `#slide=N` in the
// URL selects a slide, so each slide is a deep link (widget state rides along in the
// same hash). N shows the speaker notes, P presents the deck full screen with the
// slide title kept; `deck.html?notes` is a presenter window that follows the slides
// shown in any other window of the deck (BroadcastChannel).
import { fitToBox, stillFits, unfit } from './deck/fit.ts';

/** Where the slide layout fits the figure to the screen; below it the deck scrolls. */
const FITTED_LAYOUT = '(min-width: 900px) and (min-height: 560px)';
const CHANNEL = 'scatterbook-deck';

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
  if (params.get('slide') === String(slide)) return;
  params.set('slide', String(slide));
  // Keep the query (e.g. ?backend=cpu) so that a slide link reopens the same way.
  history.replaceState(
    history.state,
    '',
    `${location.pathname}${location.search}#${params.toString()}`,
  );
}

/** A key typed into a field or a widget's controls belongs to them, not to the deck. */
function isTyping(target: EventTarget | null): boolean {
  return (
    target instanceof HTMLElement &&
    (target.isContentEditable || target.closest('input, select, textarea, .sb-controls') !== null)
  );
}

/**
 * A figure that does not fit its slide even at the smallest readable zoom scrolls
 * inside its box (never over the caption): a labelled region that the keyboard can
 * focus and scroll, so that what lies below the fold is still reachable.
 */
function scrollRegion(slide: HTMLElement, box: HTMLElement, on: boolean): void {
  box.classList.toggle('deck-figure--scrolls', on);
  if (on) {
    const title = slide.querySelector('.deck-title')?.textContent?.replace(/^\s*\d+\s*/, '');
    box.setAttribute('role', 'region');
    box.setAttribute('aria-label', `${title?.trim() || 'Figure'} (scrolls)`);
    box.tabIndex = 0;
  } else {
    box.removeAttribute('role');
    box.removeAttribute('aria-label');
    box.removeAttribute('tabindex');
  }
}

export function setupDeck(): void {
  const deck = document.querySelector<HTMLElement>('main.deck');
  if (!deck) return;
  const slides = [...deck.querySelectorAll<HTMLElement>('.deck-slide')];
  if (slides.length === 0) return;
  const jump = deck.querySelector<HTMLInputElement>('.deck-jump');
  const previous = deck.querySelector<HTMLButtonElement>('.deck-previous');
  const next = deck.querySelector<HTMLButtonElement>('.deck-next');
  const notesToggle = deck.querySelector<HTMLButtonElement>('.deck-notes-toggle');
  const presentToggle = deck.querySelector<HTMLButtonElement>('.deck-present');
  const announcement = deck.querySelector<HTMLElement>('.deck-announcement');
  const root = document.documentElement;
  const fitted = matchMedia(FITTED_LAYOUT);
  const channel = typeof BroadcastChannel === 'function' ? new BroadcastChannel(CHANNEL) : null;
  let index = readSlide(slides.length) - 1;

  const figureOf = (slide: HTMLElement | undefined): [HTMLElement, HTMLElement] | null => {
    const box = slide?.querySelector<HTMLElement>('.deck-figure, .deck-equations');
    const content = box?.classList.contains('deck-equations')
      ? box.querySelector<HTMLElement>('.deck-equations-inner')
      : box?.firstElementChild;
    return box && content instanceof HTMLElement ? [content, box] : null;
  };

  // The sizes the last fit left, so that the ResizeObserver's report of the fit's own
  // change does not start another (a fit lays a heavy widget out a dozen times).
  let fittedSizes = '';
  const sizesOf = (figure: [HTMLElement, HTMLElement]): string =>
    figure.map((element) => `${element.offsetWidth}×${element.offsetHeight}`).join(' ');
  const fit = (): void => {
    const slide = slides[index];
    const figure = figureOf(slide);
    if (!slide || !figure) return;
    if (fitted.matches) {
      const start = performance.now();
      const result = fitToBox(...figure);
      // Read by the deck's end-to-end test, and handy when tuning a slide.
      slide.dataset['fit'] =
        `${result.fits ? 'fits' : `scrolls by ${result.overflow} px at`} zoom=${result.zoom} ` +
        `stage=${result.stage} width=${result.width} in ${Math.round(performance.now() - start)} ms`;
      scrollRegion(slide, figure[1], !result.fits);
    } else {
      unfit(figure[0]);
      scrollRegion(slide, figure[1], false);
    }
    fittedSizes = sizesOf(figure);
  };
  let fitFrame = 0;
  let contentTimer: ReturnType<typeof setTimeout> | undefined;
  // When the contents started changing without a refit since (0: not pending).
  let contentPendingSince = 0;
  const scheduleFit = (): void => {
    cancelAnimationFrame(fitFrame);
    clearTimeout(contentTimer);
    contentPendingSince = 0;
    fitFrame = requestAnimationFrame(() => {
      const figure = figureOf(slides[index]);
      if (figure && sizesOf(figure) !== fittedSizes) fit();
    });
  };
  // A change of the figure's contents (a widget being defined, a notice, readouts filled
  // in, a sweep's plot growing) refits only once the contents have held still for a
  // moment, and only if the current layout no longer fits: refitting on every frame of
  // a refinement or a sweep moved the controls under the pointer (a Cancel button
  // never held still long enough to be clicked).
  const CONTENT_SETTLE_MS = 400;
  // …but contents that never hold still (a widget refining for seconds) are refitted
  // after at most this long, so that a slide does not overflow for the whole refinement.
  const CONTENT_MAX_WAIT_MS = 1500;
  const scheduleContentFit = (): void => {
    clearTimeout(contentTimer);
    const now = performance.now();
    if (contentPendingSince === 0) contentPendingSince = now;
    const wait = Math.min(CONTENT_SETTLE_MS, contentPendingSince + CONTENT_MAX_WAIT_MS - now);
    contentTimer = setTimeout(
      () => {
        contentPendingSince = 0;
        const figure = figureOf(slides[index]);
        if (!figure || sizesOf(figure) === fittedSizes) return;
        // A scroll region whose contents shrank is refitted: it may fit again, larger.
        const scrolls = figure[1].classList.contains('deck-figure--scrolls');
        if (fitted.matches && !scrolls && stillFits(...figure)) fittedSizes = sizesOf(figure);
        else fit();
      },
      Math.max(0, wait),
    );
  };
  // The box (the room the slide leaves the figure) changes with the window, the notes
  // or presentation mode: that refits on the next frame. Its contents: see above.
  const observer = new ResizeObserver((entries) => {
    const figure = figureOf(slides[index]);
    if (figure && entries.some((entry) => entry.target === figure[1])) scheduleFit();
    else scheduleContentFit();
  });
  for (const slide of slides) {
    const figure = figureOf(slide);
    if (figure) {
      observer.observe(figure[0]);
      observer.observe(figure[1]);
    }
  }
  fitted.addEventListener('change', scheduleFit);

  const notesOpen = (): boolean => root.classList.contains('deck-notes-open');
  const showNotes = (open: boolean): void => {
    root.classList.toggle('deck-notes-open', open);
    notesToggle?.setAttribute('aria-expanded', String(open));
    slides.forEach((slide, i) => {
      const notes = slide.querySelector<HTMLElement>('.deck-notes');
      if (notes) notes.hidden = !(open && i === index);
    });
    scheduleFit();
  };

  const show = (target: number, how: { focus?: boolean; broadcast?: boolean } = {}): void => {
    const before = index;
    index = Math.min(Math.max(target, 0), slides.length - 1);
    const active = document.activeElement;
    const focusWasInSlide = active === document.body || slides[before]?.contains(active);
    slides.forEach((slide, i) => {
      slide.hidden = i !== index;
    });
    const slide = slides[index];
    if (jump) jump.value = String(index + 1);
    if (previous) previous.disabled = index === 0;
    if (next) next.disabled = index === slides.length - 1;
    notesToggle?.setAttribute('aria-controls', `slide-${index + 1}-notes`);
    showNotes(notesOpen());
    writeSlide(index + 1);
    fit();
    if (how.broadcast !== false) channel?.postMessage({ slide: index + 1 });
    if (!how.focus || before === index) return;
    const title = slide?.querySelector<HTMLElement>('.deck-title');
    if (focusWasInSlide || active === null) {
      // The heading is read on focus: no announcement besides it.
      title?.focus({ preventScroll: true });
    } else {
      if (active instanceof HTMLButtonElement && active.disabled)
        (active === next ? previous : next)?.focus();
      if (announcement)
        announcement.textContent = `Slide ${index + 1} of ${slides.length}: ${title?.textContent?.replace(/^\s*\d+\s*/, '') ?? ''}`;
    }
  };

  // Deck presentation: the whole page full screen, slide title and controls kept.
  const presenting = (): boolean => root.classList.contains('deck-presenting');
  const present = (on: boolean): void => {
    root.classList.toggle('deck-presenting', on);
    presentToggle?.setAttribute('aria-pressed', String(on));
    if (presentToggle) presentToggle.textContent = on ? 'Exit presentation' : 'Present';
    // The widgets' own Present buttons present the deck here (see the capture below).
    for (const button of deck.querySelectorAll<HTMLButtonElement>('[data-action="present"]')) {
      button.setAttribute('aria-pressed', String(on));
      button.textContent = on ? 'Exit presentation' : 'Present';
    }
    if (on && !document.fullscreenElement) void root.requestFullscreen?.().catch(() => undefined);
    else if (!on && document.fullscreenElement)
      void document.exitFullscreen().catch(() => undefined);
    scheduleFit();
  };
  document.addEventListener('fullscreenchange', () => {
    if (!document.fullscreenElement && presenting()) present(false);
  });

  for (const slide of slides)
    slide.querySelector<HTMLElement>('.deck-title')?.setAttribute('tabindex', '-1');
  previous?.addEventListener('click', () => show(index - 1, { focus: true }));
  next?.addEventListener('click', () => show(index + 1, { focus: true }));
  jump?.addEventListener('change', () => {
    const value = Number.parseInt(jump.value, 10);
    if (Number.isFinite(value)) show(value - 1, { focus: true });
    else jump.value = String(index + 1);
  });
  notesToggle?.addEventListener('click', () => showNotes(!notesOpen()));
  presentToggle?.addEventListener('click', () => present(!presenting()));
  window.addEventListener('hashchange', () => show(readSlide(slides.length) - 1));
  channel?.addEventListener('message', (event: MessageEvent<{ slide?: unknown }>) => {
    if (typeof event.data.slide === 'number') show(event.data.slide - 1, { broadcast: false });
  });

  // A widget on a slide presents the deck, not itself: its own presentation mode is a
  // fixed overlay (or its own full screen) that would hide the slide title and the
  // deck's controls. Caught before the widget's handlers see the key or the click.
  document.addEventListener(
    'keydown',
    (event) => {
      if (event.ctrlKey || event.metaKey || event.altKey) return;
      if (event.key !== 'f' && event.key !== 'F') return;
      const target = event.target as HTMLElement | null;
      const typingNumber = target instanceof HTMLInputElement && target.type === 'number';
      if (!target?.closest('.deck-slide') || typingNumber) return;
      event.preventDefault();
      event.stopPropagation();
      present(!presenting());
    },
    true,
  );
  deck.addEventListener(
    'click',
    (event) => {
      const button = (event.target as HTMLElement | null)?.closest('[data-action="present"]');
      if (!button || !deck.contains(button)) return;
      event.preventDefault();
      event.stopPropagation();
      present(!presenting());
    },
    true,
  );

  document.addEventListener('keydown', (event) => {
    if (event.ctrlKey || event.metaKey || event.altKey || event.defaultPrevented) return;
    const target = event.target as HTMLElement | null;
    // Arrow keys belong to a focused control (a slider, a select); the deck takes them elsewhere.
    if (isTyping(target)) return;
    const onButton = target?.closest('button, a, summary') !== null && target !== null;
    const key = event.key;
    let handled = true;
    if (key === 'ArrowRight' || key === 'PageDown' || (key === ' ' && !onButton))
      show(index + 1, { focus: true });
    else if (key === 'ArrowLeft' || key === 'PageUp') show(index - 1, { focus: true });
    else if (key === 'Home') show(0, { focus: true });
    else if (key === 'End') show(slides.length - 1, { focus: true });
    else if (key === 'n' || key === 'N') showNotes(!notesOpen());
    else if (key === 'p' || key === 'P' || key === 'f' || key === 'F') present(!presenting());
    else if (key === 'Escape' && presenting()) present(false);
    else if (/^[1-9]$/.test(key) && !target?.closest('.deck-figure')) {
      // Number keys recall the current figure's presets even when the focus is on the
      // slide title (where moving between slides leaves it), as inside the figure.
      const widget = slides[index]?.querySelector<HTMLElement>('.deck-figure > *');
      if (widget)
        widget.dispatchEvent(
          new KeyboardEvent('keydown', { key, bubbles: false, cancelable: true }),
        );
    } else handled = false;
    if (handled) event.preventDefault();
  });

  const query = new URLSearchParams(location.search);
  if (query.has('notes')) {
    root.classList.add('deck-presenter');
    showNotes(true);
  }
  show(index, { broadcast: false });
}
