// <sb-exercise exercise="ID">: an autograded exercise in the page (issue 7). The
// statement was rendered into the element at build time (src/book/build/exercises.ts)
// and is kept; the element adds a CodeMirror WGSL editor, Run checks (the public
// checks of the one grading core, src/grading/grade.ts, on a GPU device of its own),
// Cancel, Reset, Hints one at a time, export and import of all exercises' progress,
// and the results with the student's values next to the reference's. Code, hints and
// the last result persist in localStorage. Above the editor, a note says how the
// exercise is graded (public checks here, hidden ones by the course's grader) and which
//
// Not yet ported to a view: load() returns the widget's own element class, which
// keeps its shell code (see /work/briefs/porting.md); the data below is already
// the definition's (deck slides, schema).
import { defineWidget } from '../base/definition.ts';
import { EXERCISE_WIDGET } from './schema.ts';

export const widget = defineWidget({
  entry: EXERCISE_WIDGET,
  slides: [],
  load: async () => ({ element: (await import('./element.ts')).ExerciseElement }),
});
