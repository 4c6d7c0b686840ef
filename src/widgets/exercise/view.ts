// The view of <sb-exercise exercise="ID"> (widget.ts): the statement the build
// rendered into the element is kept; the view adds a CodeMirror WGSL editor, Run checks (the public
// checks of the one grading core, src/grading/grade.ts, on a GPU device of its own),
// Cancel, Reset, Hints one at a time, export and import of all exercises' progress,
// and the results with the student's values next to the reference's. Code, hints and
// the last result persist in localStorage. Above the editor, a note says how the
// exercise is graded (public checks here, hidden ones by the course's grader) and which
// browsers run the checks, and whether this one can; Download submission saves the code
// as <exercise-id>.wgsl, the file the Gradescope and PrairieLearn kits grade
// (src/grading/kit/). Without WebGPU the editor, saving and downloading still work and
// a notice says the checks need WebGPU.
import type { FrameBackend } from '../base/definition.ts';
import type { ViewContext, WidgetView } from '../base/view.ts';
import type { ExerciseDefinition } from '../../grading/exercise.ts';
import { SUBMISSION_RULES } from '../../grading/instrument.ts';
import { STATUS_WORDS, allPassed, type ExerciseFrame } from './widget.ts';
import { createEditor, type ExerciseEditor } from './editor.ts';
import { ResultView, outcomeSummary } from './resultView.ts';
import { ExerciseRunner, WebGpuUnavailable, type RunOutcome } from './runner.ts';
import {
  GRADE_TIMEOUT_MS,
  exerciseIds,
  gradeOnPage,
  loadExerciseForPage,
} from './exerciseSource.ts';
import {
  collectProgress,
  loadProgress,
  parseProgressFile,
  saveProgress,
  summarizeOutcome,
  type ExerciseProgress,
  type StoredResult,
} from './progress.ts';

/** The checks run on a GPU device of the exercise's own, not the page's. */
const OWN_DEVICE: FrameBackend = { kind: 'gpu', adapterDescription: 'a device of its own' };

/** Debounce of saving the code while typing. */
const SAVE_DELAY_MS = 400;
/** Other exercises on the page reload their state after an import. */
const IMPORTED_EVENT = 'sb-exercise-progress-imported';

function button(label: string, action: string): HTMLButtonElement {
  const node = document.createElement('button');
  node.type = 'button';
  node.className = 'sb-button';
  node.dataset['action'] = action;
  node.textContent = label;
  return node;
}

function storage(): Storage | null {
  try {
    return window.localStorage;
  } catch {
    return null;
  }
}

function describeStored(result: StoredResult): string {
  const when = new Date(result.at).toLocaleString();
  if (result.status !== 'graded') return `Last run (${when}): ${STATUS_WORDS[result.status]}.`;
  return result.passed === result.total
    ? `Last run (${when}): public checks passed (${result.score} of ${result.maxScore} points) — hidden tests run when graded.`
    : `Last run (${when}): ${result.passed} of ${result.total} public checks passed (${result.score} of ${result.maxScore} points).`;
}

class ExerciseView implements WidgetView<ExerciseFrame> {
  private exerciseId = '';
  private exercise: ExerciseDefinition | null = null;
  private editor: ExerciseEditor | null = null;
  private results: ResultView | null = null;
  private statement: HTMLElement | null = null;
  private editorArea: HTMLElement | null = null;
  private hintList: HTMLOListElement | null = null;
  private hintButton: HTMLButtonElement | null = null;
  private runButton: HTMLButtonElement | null = null;
  private cancelButton: HTMLButtonElement | null = null;
  private progressBar: HTMLProgressElement | null = null;
  private readonly runner = new ExerciseRunner();
  private running: AbortController | null = null;
  private progress: ExerciseProgress = { code: '', hintsShown: 0, result: null };
  private saveTimer: ReturnType<typeof setTimeout> | null = null;
  private gpuReason: string | null = null;
  private gpuStatus: HTMLElement | null = null;
  private started = false;

  constructor(private readonly context: ViewContext) {
    // The statement the build rendered inside the tag (the shell replaced the children).
    this.statement =
      context.content.find(
        (child): child is HTMLElement =>
          child instanceof HTMLElement && child.matches('.sb-exercise-statement'),
      ) ?? null;
    this.exerciseId = context.host.getAttribute('exercise') ?? '';
  }

  build(stage: HTMLElement): void {
    const id = this.context.widgetId;
    this.context.host.querySelector('.sb-widget')?.classList.add('sb-exercise-widget');
    window.addEventListener('pagehide', this.flushSave);
    window.addEventListener(IMPORTED_EVENT, this.onImported);
    if (this.statement) stage.appendChild(this.statement);

    stage.append(this.buildGradingNote());

    const label = document.createElement('p');
    label.className = 'sb-exercise-editor-label';
    label.id = `${id}-editor-label`;
    label.textContent = 'Your code (WGSL)';
    this.editorArea = document.createElement('div');
    this.editorArea.className = 'sb-exercise-editor';
    // The editor handles its own keys; the widget's shortcuts (F, digits) must not fire while typing.
    this.editorArea.addEventListener('keydown', (event) => event.stopPropagation());
    const hint = document.createElement('p');
    hint.className = 'sb-exercise-keyhint';
    hint.id = `${id}-keyhint`;
    hint.textContent =
      'Tab indents inside the editor. To leave it with the keyboard, press Escape, then Tab.';

    const toolbar = document.createElement('div');
    toolbar.className = 'sb-exercise-toolbar';
    this.runButton = button('Run checks', 'run');
    this.cancelButton = button('Cancel', 'cancel');
    this.cancelButton.hidden = true;
    const reset = button('Reset', 'reset');
    this.hintButton = button('Show a hint', 'hint');
    const download = button('Download submission', 'download');
    download.title = `Save your code as ${this.exerciseId}.wgsl, the file your course's grader takes`;
    const exportButton = button('Export progress', 'export');
    const importButton = button('Import progress', 'import');
    const fileInput = document.createElement('input');
    fileInput.type = 'file';
    fileInput.accept = 'application/json,.json';
    fileInput.hidden = true;
    fileInput.setAttribute('aria-label', 'Progress file to import');
    this.progressBar = document.createElement('progress');
    this.progressBar.className = 'sb-exercise-progress';
    this.progressBar.hidden = true;
    this.progressBar.setAttribute('aria-label', 'Checks run so far');
    toolbar.append(
      this.runButton,
      this.cancelButton,
      this.progressBar,
      reset,
      this.hintButton,
      download,
      exportButton,
      importButton,
      fileInput,
    );

    this.runButton.addEventListener('click', () => void this.runChecks());
    this.cancelButton.addEventListener('click', () => this.running?.abort());
    reset.addEventListener('click', () => this.reset());
    this.hintButton.addEventListener('click', () => this.revealHint());
    download.addEventListener('click', () => this.downloadSubmission());
    exportButton.addEventListener('click', () => this.exportProgress());
    importButton.addEventListener('click', () => fileInput.click());
    fileInput.addEventListener('change', () => {
      const file = fileInput.files?.[0];
      fileInput.value = '';
      if (file) void file.text().then((text) => this.importProgress(text));
    });

    this.hintList = document.createElement('ol');
    this.hintList.className = 'sb-exercise-hints';
    this.hintList.setAttribute('aria-label', 'Hints');
    const results = document.createElement('div');
    results.className = 'sb-exercise-results';
    results.setAttribute('aria-live', 'polite');
    this.results = new ResultView(results, (line, column) => this.editor?.moveTo(line, column));
    stage.append(label, this.editorArea, hint, toolbar, this.hintList, results);
  }

  /**
   * Says, before the student writes code, how the exercise is graded (public checks
   * here, hidden checks by the course's grader, which takes the downloaded file) and
   * which browsers can run the checks; checkGpu() then says whether this one can.
   */
  private buildGradingNote(): HTMLElement {
    const note = document.createElement('div');
    note.className = 'sb-exercise-grading';
    const how = document.createElement('p');
    const howTitle = document.createElement('strong');
    howTitle.textContent = 'Where it is graded. ';
    const file = document.createElement('code');
    file.textContent = `${this.exerciseId}.wgsl`;
    how.append(
      howTitle,
      'Run checks runs the public checks here, on your own GPU. Your course grades your ' +
        'submission on its grader (Gradescope or PrairieLearn) with the same public checks ' +
        'and hidden ones: when you are done, press Download submission and hand in the file ',
      file,
      '.',
    );
    const browsers = document.createElement('p');
    const browsersTitle = document.createElement('strong');
    browsersTitle.textContent = 'Browsers. ';
    this.gpuStatus = document.createElement('span');
    this.gpuStatus.className = 'sb-exercise-gpu-status';
    this.gpuStatus.textContent = 'Checking this browser for WebGPU…';
    browsers.append(
      browsersTitle,
      'The checks need WebGPU: Chrome or Edge (113 or later), Safari 26 or later, Firefox 141 ' +
        'or later on Windows (elsewhere once WebGPU is enabled). Without WebGPU you can write, ' +
        'save and download your code, but the checks cannot run. ',
      this.gpuStatus,
    );
    const rules = document.createElement('p');
    const rulesTitle = document.createElement('strong');
    rulesTitle.textContent = 'What to submit. ';
    rules.append(rulesTitle, SUBMISSION_RULES);
    note.append(how, rules, browsers);
    return note;
  }

  onDisconnected(): void {
    this.flushSave();
  }

  destroy(): void {
    this.flushSave();
    this.running?.abort();
    window.removeEventListener('pagehide', this.flushSave);
    window.removeEventListener(IMPORTED_EVENT, this.onImported);
  }

  /** First time on screen: load the exercise, build the editor, check for WebGPU. */
  async renderWithoutBackend(): Promise<ExerciseFrame | null> {
    if (this.started) return null;
    this.started = true;
    const exercise = await loadExerciseForPage(this.exerciseId);
    this.exercise = exercise;
    const title = this.context.host.querySelector('.sb-widget-title');
    // The statement comes first and names the exercise; the header below it then
    // introduces the student's part. Without a statement, the title names the exercise.
    const header = this.context.host.querySelector('.sb-widget-header');
    if (this.statement && header) header.before(this.statement);
    if (title)
      title.textContent = this.statement
        ? 'Your solution and the public checks'
        : `Exercise: ${exercise.title}`;
    const store = storage();
    this.progress = (store && loadProgress(store, exercise.id)) ?? {
      code: exercise.starter,
      hintsShown: 0,
      result: null,
    };
    if (this.editorArea) {
      const id = this.context.widgetId;
      this.editor = createEditor(
        this.editorArea,
        this.progress.code,
        `Your WGSL code for “${exercise.title}”. Tab indents; press Escape, then Tab, to leave.`,
        (code) => {
          this.progress.code = code;
          this.scheduleSave();
        },
      );
      this.editor.view.contentDOM.setAttribute(
        'aria-describedby',
        `${id}-editor-label ${id}-keyhint`,
      );
    }
    this.showHints();
    this.showStoredResult();
    await this.checkGpu();
    return { result: this.progress.result };
  }

  /** Says up front, without creating a device, whether the checks can run here. */
  private async checkGpu(): Promise<void> {
    let reason: string | null = null;
    if (!('gpu' in navigator) || !navigator.gpu) {
      reason = 'this browser has no WebGPU (navigator.gpu is missing)';
    } else {
      const adapter = await navigator.gpu.requestAdapter().catch(() => null);
      if (!adapter) reason = 'WebGPU found no suitable GPU adapter';
    }
    this.gpuReason = reason;
    if (this.gpuStatus) {
      this.gpuStatus.textContent = reason
        ? `This browser cannot run them: ${reason}.`
        : 'This browser has WebGPU: the checks run here.';
      this.gpuStatus.dataset['webgpu'] = reason ? 'no' : 'yes';
    }
    if (reason) {
      this.context.cpuFallbackNotice(
        reason,
        'The editor works, your code is saved in this browser and Download submission works, but running the checks needs WebGPU.',
      );
      if (this.runButton) this.runButton.disabled = true;
      this.setCost(
        'CPU fallback: none for the checks — a WGSL function can only be run on a GPU; editing and saving work.',
      );
    } else {
      this.setCost('Checks run on this page’s GPU (WebGPU), on a device of their own.');
    }
  }

  private setCost(text: string): void {
    this.context.setCost(text);
  }

  private scheduleSave(): void {
    if (this.saveTimer) clearTimeout(this.saveTimer);
    this.saveTimer = setTimeout(this.flushSave, SAVE_DELAY_MS);
  }

  private readonly flushSave = (): void => {
    if (this.saveTimer) clearTimeout(this.saveTimer);
    this.saveTimer = null;
    const store = storage();
    if (!store || !this.exercise) return;
    try {
      saveProgress(store, this.exercise.id, this.progress);
    } catch (error) {
      this.context.showNotice(
        'save',
        'warning',
        `Your code could not be saved in this browser (${error instanceof Error ? error.message : String(error)}); export your progress to keep it.`,
      );
    }
  };

  private showHints(): void {
    if (!this.exercise || !this.hintList || !this.hintButton) return;
    const hints = this.exercise.hints;
    const shown = Math.min(this.progress.hintsShown, hints.length);
    this.hintList.replaceChildren(
      ...hints.slice(0, shown).map((text) => {
        const item = document.createElement('li');
        item.textContent = text;
        return item;
      }),
    );
    this.hintList.hidden = shown === 0;
    this.hintButton.textContent =
      shown < hints.length
        ? `Show a hint (${shown} of ${hints.length} shown)`
        : `All ${hints.length} hints shown`;
    this.hintButton.disabled = shown >= hints.length;
  }

  private revealHint(): void {
    if (!this.exercise) return;
    this.progress.hintsShown = Math.min(this.progress.hintsShown + 1, this.exercise.hints.length);
    this.showHints();
    this.flushSave();
    this.hintList?.lastElementChild?.setAttribute('tabindex', '-1');
    (this.hintList?.lastElementChild as HTMLElement | null)?.focus();
  }

  private showStoredResult(): void {
    const result = this.progress.result;
    if (!result) this.results?.clear();
    else this.results?.showMessage(describeStored(result), allPassed(result) ? 'ok' : 'bad');
    this.showScore(result);
  }

  /** The readouts (widget.ts formats them) from a stored result. */
  private showScore(result: StoredResult | null): void {
    this.context.report({ result } satisfies ExerciseFrame, OWN_DEVICE);
  }

  private reset(): void {
    if (!this.exercise || !this.editor) return;
    const confirmed = window.confirm(
      'Replace your code with the starter code? Your current code will be lost (export your progress first to keep it).',
    );
    if (!confirmed) return;
    this.editor.setCode(this.exercise.starter);
    this.editor.showDiagnostics([]);
    this.progress = { ...this.progress, code: this.exercise.starter, result: null };
    this.flushSave();
    this.showStoredResult();
  }

  /** The attribute timeout-ms overrides the core's watchdog (tests use a short one). */
  private timeoutMs(): number {
    const value = Number(this.context.host.getAttribute('timeout-ms'));
    return Number.isFinite(value) && value > 0 ? value : GRADE_TIMEOUT_MS;
  }

  private async runChecks(): Promise<void> {
    if (!this.exercise || !this.editor || this.running) return;
    if (this.gpuReason) return;
    const exercise = this.exercise;
    const controller = new AbortController();
    this.running = controller;
    this.context.host.dataset['state'] = 'running';
    if (this.runButton) this.runButton.disabled = true;
    if (this.cancelButton) this.cancelButton.hidden = false;
    if (this.progressBar) {
      this.progressBar.hidden = false;
      this.progressBar.removeAttribute('value');
    }
    this.editor.showDiagnostics([]);
    this.results?.showMessage('Running the public checks on the GPU…');
    const start = performance.now();
    let outcome: RunOutcome;
    try {
      outcome = await this.runner.run(
        (device, source, options) => gradeOnPage(device, exercise, source, options),
        this.editor.getCode(),
        {
          timeoutMs: this.timeoutMs(),
          signal: controller.signal,
          onProgress: (done, total) => {
            if (!this.progressBar) return;
            this.progressBar.max = Math.max(1, total);
            this.progressBar.value = done;
            this.progressBar.setAttribute('aria-valuetext', `${done} of ${total} checks`);
          },
        },
      );
    } catch (error) {
      const message = error instanceof Error ? error.message : String(error);
      if (error instanceof WebGpuUnavailable)
        this.context.cpuFallbackNotice(message, 'Checks need WebGPU.');
      outcome = { status: 'error', message };
    }
    const elapsed = performance.now() - start;
    this.running = null;
    this.context.host.dataset['state'] = outcome.status;
    if (this.runButton) this.runButton.disabled = false;
    if (this.cancelButton) this.cancelButton.hidden = true;
    if (this.progressBar) this.progressBar.hidden = true;
    this.context.recordFrameCost(elapsed, 'wall clock (compile + public checks + read-back)');
    this.showOutcome(outcome, elapsed);
  }

  private showOutcome(outcome: RunOutcome, elapsed: number): void {
    if (outcome.status === 'cancelled') {
      this.results?.showMessage(
        'Run cancelled: no checks were graded. Your code is unchanged.',
        'bad',
      );
      return;
    }
    if (outcome.status === 'error') {
      this.results?.showMessage(
        `The checks could not run (a problem of the grader or the browser, not of your code): ${outcome.message}`,
        'bad',
      );
      return;
    }
    this.results?.show(outcome);
    if (outcome.status === 'compile-error') this.editor?.showDiagnostics(outcome.diagnostics);
    const stored = summarizeOutcome(outcome, new Date());
    this.progress.result = stored;
    this.flushSave();
    this.showScore(stored);
    this.setCost(
      `Public checks on the GPU: ${elapsed.toFixed(0)} ms wall clock (compile, run, read-back)${outcome.status === 'graded' ? `, seed ${outcome.seed}` : ''}.`,
    );
    const summary = outcomeSummary(outcome);
    this.context.host.dataset['summary'] = summary.ok ? 'pass' : 'fail';
  }

  /** The editor's code as `<exercise-id>.wgsl`: the file the Gradescope and PrairieLearn kits grade. */
  private downloadSubmission(): void {
    if (!this.exercise || !this.editor) return;
    const name = `${this.exercise.id}.wgsl`;
    const blob = new Blob([this.editor.getCode()], { type: 'text/plain;charset=utf-8' });
    const link = document.createElement('a');
    link.href = URL.createObjectURL(blob);
    link.download = name;
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 10_000);
    this.context.showNotice(
      'download',
      'info',
      `Saved your code as ${name}: hand in this file to your course's grader.`,
      8000,
    );
  }

  private exportProgress(): void {
    const store = storage();
    if (!store) {
      this.context.showNotice(
        'export',
        'error',
        'This browser does not allow local storage; nothing to export.',
      );
      return;
    }
    this.flushSave();
    const file = collectProgress(store, new Date());
    const blob = new Blob([`${JSON.stringify(file, null, 2)}\n`], { type: 'application/json' });
    const link = document.createElement('a');
    link.href = URL.createObjectURL(blob);
    link.download = `scatterbook-progress-${file.exported.slice(0, 10)}.json`;
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 10_000);
    const count = Object.keys(file.exercises).length;
    this.context.showNotice(
      'export',
      'info',
      `Exported the progress of ${count} exercise${count === 1 ? '' : 's'}.`,
      6000,
    );
  }

  /** Validates a progress file, then replaces the stored progress of every exercise in it. */
  private importProgress(text: string): void {
    const parsed = parseProgressFile(text, exerciseIds());
    if (!parsed.ok) {
      this.context.showNotice(
        'import',
        'error',
        `Nothing was imported. ${parsed.errors.join(' ')}`,
      );
      return;
    }
    const store = storage();
    if (!store) {
      this.context.showNotice(
        'import',
        'error',
        'This browser does not allow local storage; nothing was imported.',
      );
      return;
    }
    for (const [id, progress] of Object.entries(parsed.file.exercises))
      saveProgress(store, id, progress);
    const count = Object.keys(parsed.file.exercises).length;
    const skipped = parsed.unknownIds.length
      ? ` Skipped exercises this book does not have: ${parsed.unknownIds.join(', ')}.`
      : '';
    this.context.showNotice(
      'import',
      'info',
      `Imported the progress of ${count} exercise${count === 1 ? '' : 's'}.${skipped}`,
      8000,
    );
    window.dispatchEvent(new Event(IMPORTED_EVENT));
  }

  private readonly onImported = (): void => {
    const store = storage();
    if (!store || !this.exercise || !this.editor) return;
    const progress = loadProgress(store, this.exercise.id);
    if (!progress) return;
    this.progress = progress;
    this.editor.setCode(progress.code);
    this.editor.showDiagnostics([]);
    this.showHints();
    this.showStoredResult();
  };
}

export function createView(context: ViewContext): WidgetView<ExerciseFrame> {
  return new ExerciseView(context);
}
