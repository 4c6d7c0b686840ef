// A box that grows with its content but does not shrink back while the content changes,
// so that a widget's height stays put from frame to frame.
//
// Why: readout values (and status lines, captions) wrap onto one line, then two, as
// their digits change, and the widget's height followed them, so the document was laid
// out anew at nearly every frame. Under DESIGN.md's Chromium flags the page is
// rasterised and composited on the same software GPU as WebGPU, and the GPU process's
// main thread waits for each swap. A document that changed height re-created the
// composited layers over the widget and rasterised them whole. In a Chromium trace of volume-path-tracer
// (bench/firstPictureProbe.ts --trace) that was a 90 ms swap every 270 ms, and an input
// that came during one had its WebGPU calls held back until it ended.
//
// The hold starts again from the content's own height when the box's width changes (a
// new layout: the content wraps differently) and on request (presentation mode changes
// the type size).

export class HeightHold {
  private readonly observer: ResizeObserver;
  private width = -1;
  private held = 0;

  constructor(private readonly element: HTMLElement) {
    this.observer = new ResizeObserver((entries) => {
      const size = entries.at(-1)?.borderBoxSize[0];
      if (size) this.resized(size.inlineSize, size.blockSize);
    });
    this.observer.observe(element, { box: 'border-box' });
  }

  /** Holds the content's own height from now on (one forced layout). */
  restart(): void {
    this.element.style.minHeight = '';
    this.held = 0;
    this.hold(this.element.offsetHeight);
  }

  disconnect(): void {
    this.observer.disconnect();
    this.element.style.minHeight = '';
    this.held = 0;
  }

  /** The height the box is held at (0: none); for tests. */
  get heldHeight(): number {
    return this.held;
  }

  private resized(width: number, height: number): void {
    if (width !== this.width) {
      // A new width: the held height belongs to the old line breaks. Hold the content's
      // own height at this width instead (one forced layout, on a resize only).
      this.width = width;
      if (this.held > 0) {
        this.restart();
        return;
      }
    }
    this.hold(height);
  }

  private hold(height: number): void {
    if (height <= this.held) return;
    this.held = height;
    // Border box: the page's styles set box-sizing: border-box on every element.
    this.element.style.minHeight = `${height}px`;
  }
}
