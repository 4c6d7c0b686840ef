// Offline reading's status line and update flow (src/book/offline.ts), driven by
// fake Workbox events, a fake service-worker registration and a fake browser: what
// the reader is told when a new version downloads, waits, is activated here or in
// another tab, and when the network goes away; and the precache patterns
// (src/book/build/pwa.ts) against every file in public/.
import { readdirSync, statSync } from 'node:fs';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { getManifest } from 'workbox-build';
import { describe, expect, it } from 'vitest';
import {
  statusMessages,
  UPDATE_CHECK_MS,
  watchOffline,
  type OfflineHost,
  type OfflineState,
  type RegistrationLike,
  type StatusAction,
  type StatusMessage,
  type WorkboxEventLike,
  type WorkboxLike,
  type WorkerLike,
} from '../../src/book/offline.ts';
import { PRECACHE_MAX_FILE_BYTES, PRECACHE_PATTERNS } from '../../src/book/build/pwa.ts';

const SAVED = new Date('2026-11-30T08:15:00Z');
const format = (date: Date): string => date.toISOString().slice(0, 16);

class FakeWorker extends EventTarget implements WorkerLike {
  constructor(public state: string) {
    super();
  }
  moveTo(state: string): void {
    this.state = state;
    this.dispatchEvent(new Event('statechange'));
  }
}

class FakeRegistration extends EventTarget implements RegistrationLike {
  installing: FakeWorker | null = null;
  waiting: FakeWorker | null = null;
  active: FakeWorker | null = null;
  readonly scope = 'http://localhost/courses/book/';
  updates = 0;
  update(): Promise<void> {
    this.updates++;
    return Promise.resolve();
  }
  /** The browser found a newer worker script and starts installing it. */
  findUpdate(): FakeWorker {
    const worker = new FakeWorker('installing');
    this.installing = worker;
    this.dispatchEvent(new Event('updatefound'));
    return worker;
  }
  /** The installing worker finished installing and now waits. */
  finishInstall(worker: FakeWorker): void {
    this.installing = null;
    this.waiting = worker;
    worker.moveTo('installed');
  }
}

class FakeWorkbox implements WorkboxLike {
  readonly registration = new FakeRegistration();
  skipWaitingMessages = 0;
  failRegistration = false;
  private readonly listeners = new Map<string, ((event: WorkboxEventLike) => void)[]>();
  addEventListener(type: 'waiting' | 'controlling', listener: (e: WorkboxEventLike) => void) {
    this.listeners.set(type, [...(this.listeners.get(type) ?? []), listener]);
  }
  emit(type: 'waiting' | 'controlling', event: WorkboxEventLike = {}): void {
    for (const listener of this.listeners.get(type) ?? []) listener(event);
  }
  register(): Promise<RegistrationLike | undefined> {
    if (this.failRegistration) return Promise.reject(new Error('SecurityError'));
    return Promise.resolve(this.registration);
  }
  messageSkipWaiting(): void {
    this.skipWaitingMessages++;
  }
}

class FakeBrowser implements OfflineHost {
  online = true;
  controlled = false;
  savedAt: Date | null = SAVED;
  reloads = 0;
  shows = 0;
  scopesAsked: (string | null)[] = [];
  messages: StatusMessage[] = [];
  private act: ((action: StatusAction) => void) | null = null;
  private readonly connectivity: (() => void)[] = [];
  isOnline = (): boolean => this.online;
  isControlled = (): boolean => this.controlled;
  onConnectivityChange(listener: () => void): void {
    this.connectivity.push(listener);
  }
  savedCopyDate(scope: string | null): Promise<Date | null> {
    this.scopesAsked.push(scope);
    return Promise.resolve(this.controlled ? this.savedAt : null);
  }
  reload(): void {
    this.reloads++;
  }
  show(messages: StatusMessage[], act: (action: StatusAction) => void): void {
    this.shows++;
    this.messages = messages;
    this.act = act;
  }
  setOnline(online: boolean): void {
    this.online = online;
    for (const listener of this.connectivity) listener();
  }
  /** Presses the button of the message that has one. */
  press(): void {
    const action = this.messages.find((message) => message.action)?.action;
    if (!action || !this.act) throw new Error('no button shown');
    this.act(action.run);
  }
  texts(): string[] {
    return this.messages.map((message) => message.text);
  }
}

const flush = (): Promise<void> => new Promise((resolve) => setTimeout(resolve, 0));

describe('statusMessages', () => {
  const base: OfflineState = { online: true, controlled: true, savedAt: SAVED, update: 'none' };

  it('says nothing while online with no newer version', () => {
    expect(statusMessages(base, format)).toEqual([]);
    expect(statusMessages({ ...base, controlled: false }, format)).toEqual([]);
  });

  it('offline: the saved copy and its date, or that the book is not saved yet', () => {
    expect(statusMessages({ ...base, online: false }, format)).toEqual([
      { kind: 'offline', text: 'Offline — showing the saved copy from 2026-11-30T08:15.' },
    ]);
    expect(statusMessages({ ...base, online: false, savedAt: null }, format)[0]?.text).toBe(
      'Offline — showing the saved copy of the book.',
    );
    expect(statusMessages({ ...base, online: false, controlled: false }, format)[0]?.text).toBe(
      'Offline — this book is not saved for offline reading yet, so other pages may not open.',
    );
  });

  it('a waiting version: a Reload button that activates it, and the page says it is the saved copy', () => {
    expect(statusMessages({ ...base, update: 'waiting' }, format)).toEqual([
      {
        kind: 'update',
        text: 'A new version of the book is available — this page is the saved copy from 2026-11-30T08:15.',
        action: { label: 'Reload', run: 'activate' },
      },
    ]);
    // Offline as well: both lines, the update first (it has the button).
    const both = statusMessages({ ...base, update: 'waiting', online: false }, format);
    expect(both.map((message) => message.kind)).toEqual(['update', 'offline']);
  });

  it('replaced in another tab: a plain reload; downloading: only while online', () => {
    expect(statusMessages({ ...base, update: 'replaced' }, format)[0]?.action).toEqual({
      label: 'Reload',
      run: 'reload',
    });
    expect(statusMessages({ ...base, update: 'downloading' }, format)[0]?.text).toBe(
      'Downloading a new version of the book…',
    );
    expect(
      statusMessages({ ...base, update: 'downloading', online: false }, format).map((m) => m.kind),
    ).toEqual(['offline']);
  });
});

describe('watchOffline', () => {
  it('first visit: registers, says nothing, and takes control without reloading', async () => {
    const workbox = new FakeWorkbox();
    const browser = new FakeBrowser();
    const watch = await watchOffline(workbox, browser, { setInterval: () => 0 });
    expect(browser.messages).toEqual([]);
    expect(watch.registration).toBe(workbox.registration);
    // The first installation: updatefound without an active worker is not an update.
    const worker = workbox.registration.findUpdate();
    expect(browser.messages).toEqual([]);
    worker.moveTo('activated');
    browser.controlled = true;
    workbox.emit('controlling', { isUpdate: false });
    await flush();
    expect(watch.state()).toMatchObject({ controlled: true, savedAt: SAVED, update: 'none' });
    expect(browser.scopesAsked.at(-1)).toBe('http://localhost/courses/book/');
    expect(browser.reloads).toBe(0);
    browser.setOnline(false);
    expect(browser.texts()).toHaveLength(1);
    expect(browser.texts()[0]).toMatch(/^Offline — showing the saved copy from .*2026.*\.$/);
  });

  it('an update downloads, waits, and Reload activates it and reloads once it controls', async () => {
    const workbox = new FakeWorkbox();
    workbox.registration.active = new FakeWorker('activated');
    const browser = new FakeBrowser();
    browser.controlled = true;
    const watch = await watchOffline(workbox, browser, { setInterval: () => 0 });
    expect(watch.state().savedAt).toEqual(SAVED);
    const worker = workbox.registration.findUpdate();
    expect(browser.texts()).toEqual(['Downloading a new version of the book…']);
    workbox.registration.finishInstall(worker);
    expect(browser.messages[0]?.action).toEqual({ label: 'Reload', run: 'activate' });
    expect(browser.messages[0]?.text).toMatch(/^A new version of the book is available — /);
    // Workbox reports the same waiting worker too: the line is not rewritten.
    const shows = browser.shows;
    workbox.emit('waiting', {});
    expect(browser.shows).toBe(shows);
    browser.press();
    expect(workbox.skipWaitingMessages).toBe(1);
    expect(browser.reloads).toBe(0);
    workbox.emit('controlling', { isUpdate: true });
    expect(browser.reloads).toBe(1);
  });

  it('a version that was already waiting before the page loaded is announced', async () => {
    const workbox = new FakeWorkbox();
    const browser = new FakeBrowser();
    browser.controlled = true;
    await watchOffline(workbox, browser, { setInterval: () => 0 });
    workbox.registration.waiting = new FakeWorker('installed');
    workbox.emit('waiting', { isUpdate: true });
    expect(browser.messages).toHaveLength(1);
    expect(browser.messages[0]?.kind).toBe('update');
  });

  it('another tab activates the new version: this page says it is the older one', async () => {
    const workbox = new FakeWorkbox();
    const browser = new FakeBrowser();
    browser.controlled = true;
    await watchOffline(workbox, browser, { setInterval: () => 0 });
    workbox.emit('controlling', { isExternal: true });
    expect(browser.reloads).toBe(0);
    expect(browser.texts()).toEqual([
      'The book was updated in another tab; this page is still the older version.',
    ]);
    browser.press();
    expect(workbox.skipWaitingMessages).toBe(0);
    expect(browser.reloads).toBe(1);
  });

  it('Reload with nothing waiting any more reloads directly', async () => {
    const workbox = new FakeWorkbox();
    const browser = new FakeBrowser();
    browser.controlled = true;
    await watchOffline(workbox, browser, { setInterval: () => 0 });
    workbox.emit('waiting', {});
    workbox.registration.waiting = null;
    browser.press();
    expect(workbox.skipWaitingMessages).toBe(0);
    expect(browser.reloads).toBe(1);
  });

  it('a failed download clears the notice', async () => {
    const workbox = new FakeWorkbox();
    workbox.registration.active = new FakeWorker('activated');
    const browser = new FakeBrowser();
    browser.controlled = true;
    await watchOffline(workbox, browser, { setInterval: () => 0 });
    const worker = workbox.registration.findUpdate();
    expect(browser.messages).toHaveLength(1);
    worker.moveTo('redundant');
    expect(browser.messages).toEqual([]);
  });

  it('going offline and back: the line follows, and coming back online checks for updates', async () => {
    const workbox = new FakeWorkbox();
    const browser = new FakeBrowser();
    browser.controlled = true;
    const timer = { hourly: (): void => undefined, ms: 0 };
    await watchOffline(workbox, browser, {
      setInterval: (callback, ms) => {
        timer.hourly = callback;
        timer.ms = ms;
      },
    });
    expect(timer.ms).toBe(UPDATE_CHECK_MS);
    browser.setOnline(false);
    expect(browser.messages).toHaveLength(1);
    expect(browser.messages[0]?.kind).toBe('offline');
    expect(workbox.registration.updates).toBe(0);
    // No update checks while offline.
    timer.hourly();
    expect(workbox.registration.updates).toBe(0);
    browser.setOnline(true);
    expect(browser.messages).toEqual([]);
    expect(workbox.registration.updates).toBe(1);
    timer.hourly();
    expect(workbox.registration.updates).toBe(2);
  });

  it('a browser that refuses the worker: the page still says when it is offline', async () => {
    const workbox = new FakeWorkbox();
    workbox.failRegistration = true;
    const browser = new FakeBrowser();
    const watch = await watchOffline(workbox, browser, { setInterval: () => 0 });
    expect(watch.registration).toBeUndefined();
    browser.setOnline(false);
    expect(browser.texts()[0]).toMatch(/not saved for offline reading/);
  });
});

describe('precache patterns', () => {
  const publicDir = fileURLToPath(new URL('../../public', import.meta.url));
  const files = (dir: string): string[] =>
    readdirSync(dir).flatMap((name) => {
      const path = join(dir, name);
      return statSync(path).isDirectory() ? files(path) : [relative(publicDir, path)];
    });

  it('cover every file in public/ (scenes, volumes, reference images, icons) within the size limit', async () => {
    const expected = files(publicDir).sort();
    expect(expected).toEqual(expect.arrayContaining(['volumes/smoke-24.f32']));
    const { manifestEntries, warnings } = await getManifest({
      globDirectory: publicDir,
      globPatterns: PRECACHE_PATTERNS,
      maximumFileSizeToCacheInBytes: PRECACHE_MAX_FILE_BYTES,
    });
    expect(warnings).toEqual([]);
    expect((manifestEntries ?? []).map((entry) => entry.url).sort()).toEqual(expected);
  });
});
