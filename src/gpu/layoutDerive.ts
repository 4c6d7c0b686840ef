// Derives host-shareable layouts from WGSL source text: the struct declarations, the
// `const` integers their array sizes name, and the memory layout rules of the WGSL
// specification (§ "Memory Layout": alignment and size of each type, member offsets
// rounded up to the member's alignment, array stride = roundUp(align, size), struct size
// rounded up to the struct's alignment, @align and @size attributes). Uniform buffers add
// the spec's constraints (structs and arrays 16-byte aligned, array strides multiples of
// 16, 16 bytes' room after a nested struct); validateUniform reports a violation instead
// of leaving it to pipeline creation. Used at test time and by layoutGenerate.ts; pages
// ship only the derived table (layouts.generated.ts).
import type { ArrayLayout, MemberLayout, ScalarName, StructLayout, TypeLayout } from './layout.ts';

interface TypeSyntax {
  name: string;
  args: string[];
}

interface MemberSyntax {
  name: string;
  type: string;
  align: string | null;
  size: string | null;
}

export interface WgslDeclarations {
  structs: ReadonlyMap<string, readonly MemberSyntax[]>;
  consts: ReadonlyMap<string, string>;
  aliases: ReadonlyMap<string, string>;
  /** Module-scope `var<uniform>` / `var<storage, …>` declarations: name → type text. */
  bindings: readonly { name: string; space: 'uniform' | 'storage'; type: string }[];
}

/** Removes // and nested /* *\/ comments, keeping line structure irrelevant. */
export function stripComments(source: string): string {
  let out = '';
  let depth = 0;
  for (let i = 0; i < source.length; i++) {
    const two = source.slice(i, i + 2);
    if (depth === 0 && two === '//') {
      const end = source.indexOf('\n', i);
      i = end < 0 ? source.length : end - 1;
      continue;
    }
    if (two === '/*') {
      depth++;
      i++;
      continue;
    }
    if (depth > 0 && two === '*/') {
      depth--;
      i++;
      if (depth === 0) out += ' ';
      continue;
    }
    if (depth === 0) out += source[i];
  }
  return out;
}

/** Splits at commas that are not inside <…> or (…). */
function splitTopLevel(text: string): string[] {
  const parts: string[] = [];
  let depth = 0;
  let start = 0;
  for (let i = 0; i < text.length; i++) {
    const c = text[i];
    if (c === '<' || c === '(') depth++;
    else if (c === '>' || c === ')') depth--;
    else if (c === ',' && depth === 0) {
      parts.push(text.slice(start, i));
      start = i + 1;
    }
  }
  parts.push(text.slice(start));
  return parts.map((p) => p.trim()).filter((p) => p.length > 0);
}

export function parseDeclarations(source: string): WgslDeclarations {
  const text = stripComments(source);
  const structs = new Map<string, MemberSyntax[]>();
  for (const match of text.matchAll(/\bstruct\s+([A-Za-z_]\w*)\s*\{([^}]*)\}/g)) {
    const members = splitTopLevel(match[2]!).map((entry) => parseMember(match[1]!, entry));
    structs.set(match[1]!, members);
  }
  const consts = new Map<string, string>();
  for (const match of text.matchAll(/\bconst\s+([A-Za-z_]\w*)\s*(?::[^=]+)?=([^;]+);/g)) {
    consts.set(match[1]!, match[2]!.trim());
  }
  const aliases = new Map<string, string>();
  for (const match of text.matchAll(/\balias\s+([A-Za-z_]\w*)\s*=([^;]+);/g)) {
    aliases.set(match[1]!, match[2]!.trim());
  }
  const bindings: WgslDeclarations['bindings'][number][] = [];
  for (const match of text.matchAll(
    /\bvar\s*<\s*(uniform|storage)\b[^>]*>\s*([A-Za-z_]\w*)\s*:([^;]+);/g,
  )) {
    bindings.push({
      name: match[2]!,
      space: match[1] as 'uniform' | 'storage',
      type: match[3]!.trim(),
    });
  }
  return { structs, consts, aliases, bindings };
}

function parseMember(struct: string, entry: string): MemberSyntax {
  let rest = entry;
  let align: string | null = null;
  let size: string | null = null;
  for (;;) {
    const attribute = /^@\s*(\w+)\s*(?:\(([^()]*)\))?\s*/.exec(rest);
    if (!attribute) break;
    if (attribute[1] === 'align') align = attribute[2] ?? null;
    if (attribute[1] === 'size') size = attribute[2] ?? null;
    rest = rest.slice(attribute[0].length);
  }
  const member = /^([A-Za-z_]\w*)\s*:\s*([\s\S]+)$/.exec(rest);
  if (!member) throw new SyntaxError(`struct ${struct}: cannot read member "${entry}"`);
  return { name: member[1]!, type: member[2]!.trim(), align, size };
}

function parseType(text: string): TypeSyntax {
  const match = /^([A-Za-z_]\w*)\s*(?:<([\s\S]*)>)?$/.exec(text.trim());
  if (!match) throw new SyntaxError(`cannot read type "${text}"`);
  return { name: match[1]!, args: match[2] === undefined ? [] : splitTopLevel(match[2]) };
}

/** Evaluates an integer const-expression: literals, named consts, + - * / % and parentheses. */
export function evaluateInteger(expression: string, consts: ReadonlyMap<string, string>): number {
  const tokens = expression.match(/0[xX][0-9a-fA-F]+[iu]?|\d+[iu]?|[A-Za-z_]\w*|[-+*/%()]/g) ?? [];
  if (tokens.join('') !== expression.replace(/\s+/g, '')) {
    throw new SyntaxError(`not an integer constant expression: "${expression}"`);
  }
  let at = 0;
  const primary = (): number => {
    const token = tokens[at++];
    if (token === undefined) throw new SyntaxError(`unexpected end of "${expression}"`);
    if (token === '(') {
      const value = sum();
      if (tokens[at++] !== ')') throw new SyntaxError(`missing ) in "${expression}"`);
      return value;
    }
    if (token === '-') return -primary();
    if (/^\d|^0[xX]/.test(token)) return Number.parseInt(token.replace(/[iu]$/, ''));
    const named = consts.get(token);
    if (named === undefined) throw new Error(`unknown constant ${token} in "${expression}"`);
    return evaluateInteger(named, consts);
  };
  const product = (): number => {
    let value = primary();
    while (tokens[at] === '*' || tokens[at] === '/' || tokens[at] === '%') {
      const op = tokens[at++];
      const right = primary();
      value = op === '*' ? value * right : op === '/' ? Math.trunc(value / right) : value % right;
    }
    return value;
  };
  const sum = (): number => {
    let value = product();
    while (tokens[at] === '+' || tokens[at] === '-') {
      const op = tokens[at++];
      const right = product();
      value = op === '+' ? value + right : value - right;
    }
    return value;
  };
  const value = sum();
  if (at !== tokens.length) throw new SyntaxError(`cannot evaluate "${expression}"`);
  return value;
}

const SCALARS: Readonly<Record<string, ScalarName>> = {
  f32: 'f32',
  u32: 'u32',
  i32: 'i32',
  f16: 'f16',
};
const SUFFIX: Readonly<Record<string, ScalarName>> = { f: 'f32', u: 'u32', i: 'i32', h: 'f16' };

const roundUp = (alignment: number, n: number): number => Math.ceil(n / alignment) * alignment;

function vectorSizes(scalar: ScalarName, length: number): { size: number; align: number } {
  const bytes = scalar === 'f16' ? 2 : 4;
  return { size: length * bytes, align: (length === 3 ? 4 : length) * bytes };
}

/** The layout of a WGSL type named in `declarations` (a struct, alias, scalar, vector, …). */
export function layoutOfType(typeText: string, declarations: WgslDeclarations): TypeLayout {
  const { name, args } = parseType(typeText);
  const alias = declarations.aliases.get(name);
  if (alias !== undefined && args.length === 0) return layoutOfType(alias, declarations);
  const scalar = SCALARS[name];
  if (scalar) {
    const { size, align } = vectorSizes(scalar, 1);
    return { kind: 'scalar', scalar, size, align };
  }
  if (name === 'atomic') return layoutOfType(args[0] ?? '', declarations);
  const vector = /^vec([234])([fuih])?$/.exec(name);
  if (vector) {
    const element = vector[2] ? SUFFIX[vector[2]]! : SCALARS[args[0] ?? ''];
    if (!element) throw new Error(`${typeText}: not a host-shareable vector`);
    const length = Number(vector[1]);
    return { kind: 'vector', scalar: element, length, ...vectorSizes(element, length) };
  }
  const matrix = /^mat([234])x([234])([fh])?$/.exec(name);
  if (matrix) {
    const element = matrix[3] ? SUFFIX[matrix[3]]! : SCALARS[args[0] ?? ''];
    if (!element) throw new Error(`${typeText}: not a host-shareable matrix`);
    const columns = Number(matrix[1]);
    const rows = Number(matrix[2]);
    const column = vectorSizes(element, rows);
    const columnStride = roundUp(column.align, column.size);
    return {
      kind: 'matrix',
      scalar: element,
      columns,
      rows,
      columnStride,
      size: columns * columnStride,
      align: column.align,
    };
  }
  if (name === 'array') {
    const element = layoutOfType(args[0] ?? '', declarations);
    const count = args[1] === undefined ? 0 : evaluateInteger(args[1], declarations.consts);
    if (args[1] !== undefined && count < 1) throw new Error(`${typeText}: array size ${count}`);
    const stride = roundUp(element.align, element.size);
    const array: ArrayLayout = {
      kind: 'array',
      element,
      count,
      stride,
      size: count * stride,
      align: element.align,
    };
    return array;
  }
  const members = declarations.structs.get(name);
  if (members) return layoutOfStruct(name, declarations);
  throw new Error(`${typeText}: no layout (not a host-shareable type, or not declared here)`);
}

/** The layout of struct `name`, derived from its declaration in `declarations`. */
export function layoutOfStruct(name: string, declarations: WgslDeclarations): StructLayout {
  const syntax = declarations.structs.get(name);
  if (!syntax) throw new Error(`no struct ${name} in the WGSL source`);
  const members: Record<string, MemberLayout> = {};
  let end = 0;
  let align = 1;
  syntax.forEach((member, index) => {
    const type = layoutOfType(member.type, declarations);
    if (type.kind === 'array' && type.count === 0 && index !== syntax.length - 1) {
      throw new Error(`${name}.${member.name}: a runtime-sized array must be the last member`);
    }
    const memberAlign =
      member.align === null ? type.align : evaluateInteger(member.align, declarations.consts);
    const size =
      member.size === null ? type.size : evaluateInteger(member.size, declarations.consts);
    const offset = roundUp(memberAlign, end);
    members[member.name] = { offset, size, type };
    end = offset + size;
    align = Math.max(align, memberAlign);
  });
  return { kind: 'struct', name, size: roundUp(align, end), align, members };
}

/** Parses `source` and derives the layout of struct `name`. */
export function deriveStruct(source: string, name: string): StructLayout {
  return layoutOfStruct(name, parseDeclarations(source));
}

/**
 * The violations of the uniform address space's extra layout constraints (WGSL spec
 * "Address Space Layout Constraints") in a value of `type`, each naming the member.
 */
export function uniformViolations(type: TypeLayout, path = ''): string[] {
  const problems: string[] = [];
  if (type.kind === 'array') {
    if (type.count === 0) problems.push(`${path}: a runtime-sized array cannot be uniform`);
    if (type.stride % 16 !== 0) {
      problems.push(`${path}: array stride ${type.stride} is not a multiple of 16 in a uniform`);
    }
    problems.push(...uniformViolations(type.element, `${path}[]`));
  }
  if (type.kind === 'struct') {
    const entries = Object.entries(type.members);
    entries.forEach(([name, member], i) => {
      const at = path ? `${path}.${name}` : `${type.name}.${name}`;
      const nested = member.type.kind === 'struct' || member.type.kind === 'array';
      if (nested && member.offset % 16 !== 0) {
        problems.push(`${at}: offset ${member.offset} is not a multiple of 16 in a uniform`);
      }
      const next = entries[i + 1];
      if (member.type.kind === 'struct' && next) {
        const room = roundUp(16, member.type.size);
        if (next[1].offset - member.offset < room) {
          problems.push(`${at}: the next member must start ${room} bytes after it in a uniform`);
        }
      }
      problems.push(...uniformViolations(member.type, at));
    });
  }
  return problems;
}
