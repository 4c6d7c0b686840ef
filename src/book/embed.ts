// The script of an embed page (embed/<widget>.html, built by src/book/build/embeds.ts):
// the theme from the `theme=` hash key or the reader's system, the instance of the
// widget that the hash names (a deep link copied in a chapter names `<widget>-<n>`),
// the widget itself, and the "Open in the book" link carrying the current state.

// The widgets' host rules (display: block), generated from their definitions.
import 'virtual:scatterbook/widget-hosts.css';
import { defineWidgetElement, widgetNamed } from '../widgets/registry.ts';

type Theme = 'light' | 'dark';

function hashParams(): URLSearchParams {
  const hash = location.hash.replace(/^#/, '');
  return new URLSearchParams(hash.includes('=') ? hash : '');
}

/** `theme=light|dark` in the hash fixes the theme (a slide deck's); otherwise the system decides. */
function setupTheme(): void {
  const media = matchMedia('(prefers-color-scheme: dark)');
  const apply = (): void => {
    const requested = hashParams().get('theme');
    const theme: Theme =
      requested === 'light' || requested === 'dark' ? requested : media.matches ? 'dark' : 'light';
    document.documentElement.dataset['theme'] = theme;
  };
  apply();
  media.addEventListener('change', apply);
  window.addEventListener('hashchange', apply);
}

/**
 * The instance the link is for: a bare `#<widget>-<n>` (a link without changes), or
 * the first `<widget>-<n>.<param>=…` key. Anything else keeps the page's first instance.
 */
function chooseInstance(): void {
  const templates = [...document.querySelectorAll<HTMLTemplateElement>('template.embed-instance')];
  if (templates.length === 0) return;
  const hash = decodeURIComponent(location.hash.replace(/^#/, ''));
  const ids = hash.includes('=')
    ? [...hashParams().keys()].map((key) => key.slice(0, key.indexOf('.')))
    : [hash];
  const chosen = ids
    .map((id) => templates.find((template) => template.dataset['instance'] === id))
    .find((template) => template !== undefined);
  const main = document.querySelector('main.embed-main');
  // The page already shows the first instance; replacing it by its own copy would only
  // detach the element that is there.
  if (!chosen || !main || main.querySelector(`[id="${chosen.dataset['instance'] ?? ''}"]`)) return;
  main.replaceChildren(chosen.content.cloneNode(true));
}

/**
 * The back link opens the chapter with the figure's current state: the same hash,
 * less this page's own keys (theme, presentation mode). The state changes without
 * events (history.replaceState), so the link is brought up to date when it is used.
 */
function setupChapterLink(): void {
  const link = document.querySelector<HTMLAnchorElement>('a.embed-chapter-link');
  if (!link) return;
  const chapter = link.getAttribute('href') ?? '';
  const update = (): void => {
    const params = hashParams();
    for (const key of [...params.keys()])
      if (key === 'theme' || key.endsWith('.present')) params.delete(key);
    const state = [...params.keys()].some((key) => key !== 'v') ? params.toString() : '';
    link.href = state ? `${chapter}#${state}` : chapter;
  };
  for (const event of ['pointerdown', 'focus', 'contextmenu', 'mouseenter'])
    link.addEventListener(event, update);
}

async function loadWidget(): Promise<void> {
  const name = document.body.dataset['widget'] ?? '';
  const definition = widgetNamed(name);
  const elements = document.querySelectorAll(`sb-${name}`);
  if (!definition || elements.length === 0) return;
  try {
    await defineWidgetElement(definition);
  } catch (error) {
    for (const element of elements) {
      const message = document.createElement('p');
      message.className = 'sb-notice sb-notice--error';
      message.setAttribute('role', 'alert');
      message.textContent = `This figure could not be loaded: ${error instanceof Error ? error.message : String(error)}`;
      element.replaceChildren(message);
    }
  }
}

setupTheme();
chooseInstance();
setupChapterLink();
void loadWidget();
