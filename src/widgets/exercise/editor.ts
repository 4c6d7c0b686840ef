// The WGSL editor of an exercise: CodeMirror 6 with the Lezer WGSL grammar
// (@iizukak/codemirror-lang-wgsl), compiler diagnostics as lint marks, and colours
// taken from the book's design tokens (src/book/styles/tokens.css), which resolve
// to light or dark with the page's theme, so the editor follows the theme switch
// without being rebuilt.
import { EditorState } from '@codemirror/state';
import {
  EditorView,
  drawSelection,
  highlightActiveLine,
  highlightActiveLineGutter,
  keymap,
  lineNumbers,
} from '@codemirror/view';
import { defaultKeymap, history, historyKeymap, indentWithTab } from '@codemirror/commands';
import {
  HighlightStyle,
  bracketMatching,
  indentOnInput,
  syntaxHighlighting,
} from '@codemirror/language';
import { lintGutter, setDiagnostics, type Diagnostic } from '@codemirror/lint';
import { tags } from '@lezer/highlight';
import { wgsl } from '@iizukak/codemirror-lang-wgsl';
import type { SourceDiagnostic } from '../../grading/types.ts';

/** Token colours: CSS variables defined in widgets.css with light-dark() values. */
const highlight = HighlightStyle.define([
  {
    tag: [tags.keyword, tags.controlKeyword, tags.definitionKeyword],
    color: 'var(--sb-code-keyword)',
  },
  { tag: [tags.typeName, tags.className], color: 'var(--sb-code-type)' },
  { tag: [tags.number, tags.bool], color: 'var(--sb-code-number)' },
  {
    tag: [tags.comment, tags.lineComment, tags.blockComment],
    color: 'var(--muted)',
    fontStyle: 'italic',
  },
  {
    tag: [tags.function(tags.variableName), tags.function(tags.propertyName)],
    color: 'var(--sb-code-function)',
  },
  { tag: [tags.attributeName, tags.meta], color: 'var(--sb-code-attribute)' },
]);

const theme = EditorView.theme({
  '&': {
    color: 'var(--text)',
    backgroundColor: 'var(--surface-2)',
    border: '1px solid var(--border-strong)',
    borderRadius: 'var(--radius)',
    fontSize: '0.9rem',
  },
  '&.cm-focused': { outline: '2px solid var(--focus)', outlineOffset: '2px' },
  '.cm-content': { fontFamily: 'var(--font-mono)', caretColor: 'var(--text)' },
  '.cm-cursor, .cm-dropCursor': { borderLeftColor: 'var(--text)' },
  '.cm-gutters': {
    backgroundColor: 'var(--surface-2)',
    color: 'var(--muted)',
    borderRight: '1px solid var(--border)',
  },
  '.cm-activeLine': { backgroundColor: 'var(--accent-soft)' },
  '.cm-activeLineGutter': { backgroundColor: 'var(--accent-soft)' },
  '&.cm-focused .cm-selectionBackground, .cm-selectionBackground, ::selection': {
    backgroundColor: 'var(--accent-line)',
  },
  '.cm-scroller': { maxHeight: '28rem', overflow: 'auto' },
  '.cm-tooltip': { backgroundColor: 'var(--surface)', color: 'var(--text)' },
});

export interface ExerciseEditor {
  view: EditorView;
  getCode(): string;
  setCode(code: string): void;
  /** Shows compiler diagnostics in the gutter and under the code; [] clears them. */
  showDiagnostics(diagnostics: readonly SourceDiagnostic[]): void;
  /** Moves the cursor to a 1-based line and column and focuses the editor. */
  moveTo(line: number, column: number): void;
}

/** The document offset of a 1-based (line, column), clamped into the document. */
export function offsetOf(state: EditorState, line: number, column: number): number {
  const lineInfo = state.doc.line(Math.min(Math.max(1, line), state.doc.lines));
  return Math.min(lineInfo.from + Math.max(0, column - 1), lineInfo.to);
}

export function createEditor(
  parent: HTMLElement,
  code: string,
  label: string,
  onChange: (code: string) => void,
): ExerciseEditor {
  const view = new EditorView({
    parent,
    state: EditorState.create({
      doc: code,
      extensions: [
        lineNumbers(),
        highlightActiveLineGutter(),
        history(),
        drawSelection(),
        indentOnInput(),
        bracketMatching(),
        highlightActiveLine(),
        // Tab indents; Escape then Tab moves focus out (CodeMirror's tab-trap escape),
        // stated in the visible hint under the editor.
        keymap.of([...defaultKeymap, ...historyKeymap, indentWithTab]),
        wgsl(),
        syntaxHighlighting(highlight),
        lintGutter(),
        // Long comment lines in the starters wrap rather than scroll sideways, so the
        // whole statement of the task stays visible in a narrow column.
        EditorView.lineWrapping,
        theme,
        EditorView.contentAttributes.of({ 'aria-label': label, 'aria-multiline': 'true' }),
        EditorView.updateListener.of((update) => {
          if (update.docChanged) onChange(update.state.doc.toString());
        }),
      ],
    }),
  });
  return {
    view,
    getCode: () => view.state.doc.toString(),
    setCode: (next) =>
      view.dispatch({ changes: { from: 0, to: view.state.doc.length, insert: next } }),
    showDiagnostics: (diagnostics) => {
      const marks: Diagnostic[] = diagnostics
        .filter((d) => d.line >= 1)
        .map((d) => {
          const from = offsetOf(view.state, d.line, d.column);
          const lineEnd = view.state.doc.lineAt(from).to;
          return {
            from,
            // One character at the compiler's position (none at the end of a line).
            to: Math.min(from + 1, lineEnd),
            severity: d.severity,
            message: d.message,
          };
        });
      view.dispatch(setDiagnostics(view.state, marks));
    },
    moveTo: (line, column) => {
      const at = offsetOf(view.state, line, column);
      view.dispatch({ selection: { anchor: at }, scrollIntoView: true });
      view.focus();
    },
  };
}
