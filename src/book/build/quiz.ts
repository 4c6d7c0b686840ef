// Quizzes: a fenced block with info string `quiz` becomes a form that works
// without JavaScript (the answer sits in a <details>) and is checked in place
// when JavaScript runs (src/book/quiz.ts).
//
//   ? question            (one line, Markdown inline)
//   + correct option      (exactly one)
//   - wrong option
//   > explanation         (Markdown, any number of lines)

export interface Quiz {
  question: string;
  options: { text: string; correct: boolean }[];
  explanation: string;
}

export function parseQuiz(source: string, where: string): Quiz {
  let question = '';
  const options: Quiz['options'] = [];
  const explanation: string[] = [];
  for (const raw of source.split('\n')) {
    const line = raw.trimEnd();
    if (line.trim() === '') continue;
    const marker = line[0];
    const rest = line.slice(1).trim();
    if (marker === '?') question = question ? `${question} ${rest}` : rest;
    else if (marker === '+' || marker === '-')
      options.push({ text: rest, correct: marker === '+' });
    else if (marker === '>') explanation.push(line.slice(1).replace(/^ /, ''));
    else throw new Error(`${where}: quiz line must start with ?, +, - or >: "${line}"`);
  }
  if (!question) throw new Error(`${where}: quiz has no "? question" line`);
  if (options.length < 2) throw new Error(`${where}: quiz needs at least two options`);
  const correct = options.filter((option) => option.correct).length;
  if (correct !== 1) throw new Error(`${where}: quiz needs exactly one "+" option, has ${correct}`);
  if (explanation.length === 0) throw new Error(`${where}: quiz needs a "> explanation"`);
  return { question, options, explanation: explanation.join('\n') };
}
