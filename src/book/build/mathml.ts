// MathML structure checks and one repair for KaTeX's output.
//
// MathML Core gives the scripted and fraction elements a fixed number of children
// (msub, msup, mfrac, mroot, munder, mover: 2; msubsup, munderover: 3). Firefox lays
// out the MathML itself and logs "Invalid markup: Incorrect number of children for
// <msub/> tag" as a page error for each violation; screen readers read the MathML.
//
// KaTeX 0.19 breaks the rule for an operator name alone in a script: `L_{\max}`
// becomes <msub><mi>L</mi><mi>max</mi><mo>&#x2061;</mo></msub>, the function name
// and its invisible "apply function" operator as two loose children instead of one
// <mrow> (with more in the script, `b_{\min,k}`, KaTeX does wrap them). The same
// happens for every \operatorname-like command (\max, \min, \sin, \log, \lim,
// \operatorname{…}) in a sub- or superscript, under or over a limit, in a
// fraction or a root. `repairMathml` groups such pairs in an <mrow> wherever the
// parent has too many children, and `mathmlArityProblems` reports what is still
// wrong, so the build can refuse it (see markdown.ts) and the tests can scan every
// page (tests/book/mathml.test.ts).

/** Children MathML Core requires of each fixed-arity element. */
export const MATHML_ARITY: Readonly<Record<string, number>> = {
  msub: 2,
  msup: 2,
  msubsup: 3,
  mfrac: 2,
  mroot: 2,
  munder: 2,
  mover: 2,
  munderover: 3,
};

interface ElementNode {
  kind: 'element';
  name: string;
  /** The opening tag as written, e.g. `<mi mathvariant="normal">`. */
  open: string;
  /** The closing tag as written; empty for a self-closing tag. */
  close: string;
  children: MathNode[];
}

interface TextNode {
  kind: 'text';
  text: string;
}

type MathNode = ElementNode | TextNode;

export interface ArityProblem {
  element: string;
  children: number;
  expected: number;
  /** The TeX source from KaTeX's annotation, when the <math> carries one. */
  tex: string;
}

const MATH = /<math\b[\s\S]*?<\/math>/g;
const TAG = /<(\/?)([A-Za-z][\w:-]*)((?:\s[^>]*?)?)(\/?)>/g;
// U+2061 FUNCTION APPLICATION, written literally by KaTeX (or as a reference).
const APPLY_FUNCTION = /^(?:\u2061|&#x2061;|&#8289;|&ApplyFunction;|&af;)$/i;

/** Parses one `<math>…</math>` string into a tree that serializes back verbatim. */
function parse(math: string): MathNode[] {
  const root: ElementNode = { kind: 'element', name: '#root', open: '', close: '', children: [] };
  const stack: ElementNode[] = [root];
  let last = 0;
  for (const match of math.matchAll(TAG)) {
    const top = stack[stack.length - 1] ?? root;
    const index = match.index;
    if (index > last) top.children.push({ kind: 'text', text: math.slice(last, index) });
    last = index + match[0].length;
    const [whole, slash, name = ''] = match;
    if (slash) {
      if (top.name !== name || stack.length === 1) {
        throw new Error(`malformed MathML: </${name}> closes <${top.name}>`);
      }
      top.close = whole;
      stack.pop();
    } else {
      const node: ElementNode = { kind: 'element', name, open: whole, close: '', children: [] };
      top.children.push(node);
      if (!match[4]) stack.push(node);
    }
  }
  if (last < math.length) root.children.push({ kind: 'text', text: math.slice(last) });
  if (stack.length !== 1) throw new Error(`malformed MathML: <${stack.at(-1)?.name}> not closed`);
  return root.children;
}

function serialize(nodes: MathNode[]): string {
  return nodes
    .map((node) =>
      node.kind === 'text' ? node.text : node.open + serialize(node.children) + node.close,
    )
    .join('');
}

function elements(nodes: MathNode[]): ElementNode[] {
  return nodes.filter((node): node is ElementNode => node.kind === 'element');
}

function textOf(node: ElementNode): string {
  return node.children
    .map((child) => (child.kind === 'text' ? child.text : textOf(child)))
    .join('')
    .trim();
}

function isApplyFunction(node: MathNode | undefined): boolean {
  return node?.kind === 'element' && node.name === 'mo' && APPLY_FUNCTION.test(textOf(node));
}

/** Groups "name, apply-function" pairs of an over-full fixed-arity element, in place. */
function repairNodes(nodes: MathNode[]): void {
  for (const node of elements(nodes)) {
    repairNodes(node.children);
    const expected = MATHML_ARITY[node.name];
    if (expected === undefined || elements(node.children).length <= expected) continue;
    const grouped: MathNode[] = [];
    const children = elements(node.children);
    for (let i = 0; i < children.length; i++) {
      const child = children[i];
      if (!child) continue;
      const next = children[i + 1];
      if (child.name !== 'mo' && isApplyFunction(next) && next) {
        grouped.push({
          kind: 'element',
          name: 'mrow',
          open: '<mrow>',
          close: '</mrow>',
          children: [child, next],
        });
        i += 1;
      } else grouped.push(child);
    }
    node.children = grouped;
  }
}

/**
 * KaTeX's HTML with every `<math>` repaired: an operator name and its U+2061 that
 * stand as two children of a fixed-arity element become one <mrow>. Math that
 * already has the right structure comes back unchanged, byte for byte.
 */
export function repairMathml(html: string): string {
  return html.replace(MATH, (math) => {
    const nodes = parse(math);
    repairNodes(nodes);
    return serialize(nodes);
  });
}

/** Every fixed-arity MathML element in `html` with the wrong number of element children. */
export function mathmlArityProblems(html: string): ArityProblem[] {
  const problems: ArityProblem[] = [];
  for (const [math] of html.matchAll(MATH)) {
    const tex = /<annotation\b[^>]*>([\s\S]*?)<\/annotation>/.exec(math)?.[1]?.trim() ?? '';
    const visit = (nodes: MathNode[]): void => {
      for (const node of elements(nodes)) {
        const expected = MATHML_ARITY[node.name];
        const children = elements(node.children).length;
        if (expected !== undefined && children !== expected) {
          problems.push({ element: node.name, children, expected, tex });
        }
        visit(node.children);
      }
    };
    visit(parse(math));
  }
  return problems;
}
