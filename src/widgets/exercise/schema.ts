// The catalog entry of <sb-exercise exercise="ID">: an in-page exercise (issue 7).
// Its only attribute, `exercise`, names a folder of exercises/ and is read by the
// element and by the chapter build (which renders the statement into the page at
// build time); it is not a figure parameter, so the schema lists no parameters and
// the widget has no generated controls or URL state.
import type { WidgetEntry } from '../parameters.ts';

export const EXERCISE_WIDGET: WidgetEntry = {
  name: 'exercise',
  title: 'Exercise',
  description:
    'Write a WGSL function in the editor and run the public checks on the GPU against the reference solution; hidden tests run when the exercise is graded.',
  parameters: [],
};
