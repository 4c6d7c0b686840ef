// Compiler messages that need a sentence for students. The same submission is
// compiled by Tint in Chrome and Edge and by naga in Firefox; where naga rejects a
// program Tint accepts, its message names naga's internals, not the student's code.

/**
 * naga (Firefox) rejects a function with a result whose body ends in a loop, even
 * when the loop leaves only by `return` ("The `return` expression None does not
 * match the declared return type …", older versions "Returning None where Some(..)
 * is expected"); Tint accepts it. README, WGSL pitfalls.
 */
const LOOP_WITHOUT_RETURN = /return.*\bNone\b.*(does not match|where Some)/is;

/** The compiler's message, with an explanation appended when it is one of the above. */
export function withEngineNote(message: string): string {
  if (!LOOP_WITHOUT_RETURN.test(message)) return message;
  return (
    `${message}\nIn words: this browser's WGSL compiler (naga, in Firefox) needs a \`return\` ` +
    'at the end of a function whose body ends in a loop, even when the loop only exits by ' +
    '`return`. Leave the loop with `break` and return once after it.'
  );
}
