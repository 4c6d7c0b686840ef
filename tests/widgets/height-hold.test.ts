// HeightHold (src/widgets/base/heightHold.ts): a widget's body grows with its content
// and does not shrink back while its numbers change; a new width or a restart holds
// the content's own height instead. The ResizeObserver is a stand-in driven by hand;
// the behaviour in a browser is in tests/e2e/widget-layout.spec.ts.
import { afterEach, beforeEach, describe, expect, it } from 'vitest';
import { HeightHold } from '../../src/widgets/base/heightHold.ts';

type Callback = (entries: { borderBoxSize: { inlineSize: number; blockSize: number }[] }[]) => void;

/** The observers made, so that a test can report sizes to them. */
let observers: FakeObserver[] = [];

class FakeObserver {
  observed: unknown = null;
  disconnected = false;
  constructor(readonly callback: Callback) {
    observers.push(this);
  }
  observe(target: unknown): void {
    this.observed = target;
  }
  disconnect(): void {
    this.disconnected = true;
  }
}

/** An element whose laid-out height is its content's, or its min-height when larger. */
class FakeElement {
  content = 0;
  width = 300;
  style = { minHeight: '' };
  get offsetHeight(): number {
    return Math.max(this.content, parseFloat(this.style.minHeight) || 0);
  }
}

/** Lays the element out with new content and reports its size, as a browser would. */
function layOut(element: FakeElement, content: number, width = element.width): void {
  const before = { width: element.width, height: element.offsetHeight };
  element.content = content;
  element.width = width;
  const after = { width, height: element.offsetHeight };
  if (before.width === after.width && before.height === after.height) return;
  for (const observer of observers)
    if (observer.observed === element && !observer.disconnected)
      observer.callback([{ borderBoxSize: [{ inlineSize: width, blockSize: after.height }] }]);
}

const original = globalThis.ResizeObserver;
beforeEach(() => {
  observers = [];
  globalThis.ResizeObserver = FakeObserver as unknown as typeof ResizeObserver;
});
afterEach(() => {
  globalThis.ResizeObserver = original;
});

function held(content: number): { element: FakeElement; hold: HeightHold } {
  const element = new FakeElement();
  const hold = new HeightHold(element as unknown as HTMLElement);
  // A browser reports the first size on observe.
  element.content = content;
  observers
    .at(-1)!
    .callback([{ borderBoxSize: [{ inlineSize: element.width, blockSize: content }] }]);
  return { element, hold };
}

describe('HeightHold', () => {
  it('grows with the content and keeps its height when the content shrinks', () => {
    const { element, hold } = held(320);
    expect(hold.heldHeight).toBe(320);
    layOut(element, 340); // a readout wraps onto a second line
    expect(element.offsetHeight).toBe(340);
    layOut(element, 320); // and back: the box stays
    expect(element.offsetHeight).toBe(340);
    expect(element.style.minHeight).toBe('340px');
    layOut(element, 360);
    layOut(element, 300);
    expect(element.offsetHeight).toBe(360);
  });

  it('holds the new layout’s own height after a change of width', () => {
    const { element, hold } = held(320);
    layOut(element, 380);
    // Wider: the rows wrap less; the hold follows the content at the new width.
    layOut(element, 300, 480);
    expect(hold.heldHeight).toBe(300);
    expect(element.offsetHeight).toBe(300);
    layOut(element, 280, 480);
    expect(element.offsetHeight).toBe(300);
  });

  it('restart holds the present content’s height; disconnect lets the box go', () => {
    const { element, hold } = held(320);
    layOut(element, 400);
    element.content = 250; // presentation mode's type, laid out
    hold.restart();
    expect(element.offsetHeight).toBe(250);
    layOut(element, 240);
    expect(element.offsetHeight).toBe(250);
    hold.disconnect();
    expect(element.style.minHeight).toBe('');
    expect(observers[0]!.disconnected).toBe(true);
  });
});
