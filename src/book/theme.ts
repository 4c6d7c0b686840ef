// Light and dark themes: the system preference by default, and a button that
// overrides it (kept in localStorage).
const STORAGE_KEY = 'scatterbook:theme';

type Theme = 'light' | 'dark';

function systemTheme(): Theme {
  return matchMedia('(prefers-color-scheme: dark)').matches ? 'dark' : 'light';
}

function storedTheme(): Theme | null {
  try {
    const value = localStorage.getItem(STORAGE_KEY);
    return value === 'light' || value === 'dark' ? value : null;
  } catch {
    return null;
  }
}

export function setupThemeToggle(): void {
  const apply = (theme: Theme): void => {
    document.documentElement.dataset['theme'] = theme;
    const button = document.querySelector<HTMLButtonElement>('.theme-toggle');
    if (button) {
      button.textContent = theme === 'dark' ? 'Light theme' : 'Dark theme';
      button.setAttribute(
        'aria-label',
        `Switch to the ${theme === 'dark' ? 'light' : 'dark'} theme`,
      );
    }
  };
  apply(storedTheme() ?? systemTheme());
  const button = document.querySelector<HTMLButtonElement>('.theme-toggle');
  if (!button) return;
  button.hidden = false;
  button.addEventListener('click', () => {
    const next: Theme = document.documentElement.dataset['theme'] === 'dark' ? 'light' : 'dark';
    try {
      localStorage.setItem(STORAGE_KEY, next);
    } catch {
      // Private browsing may refuse storage; the theme still changes for this page.
    }
    apply(next);
  });
}
