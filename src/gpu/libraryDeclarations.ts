// A library function's WGSL text, with the declarations of its own module it needs,
// under prefixed names: for generated code that is compiled without the WESL linker
// next to text it does not control. The exercise grader appends its harness to a
// student's submission, which may declare any name (even pcgHash), so the harness
// takes rng.wesl's PCG hash as sbg_pcgHash and friends: the library's code, once,
// and no name a student could collide with.
import { parseSrcModule } from 'wesl';
import type { ShaderLibrary } from './link.ts';

const IDENTIFIER = /[A-Za-z_][A-Za-z0-9_]*/g;

interface Declaration {
  name: string;
  text: string;
}

function declarationsOf(library: ShaderLibrary, module: string): Map<string, Declaration> {
  const source = library[`${module}.wesl`];
  if (source === undefined) throw new Error(`no shader module "${module}" in the library`);
  const ast = parseSrcModule({
    modulePath: `package::${module.replace(/\//g, '::')}`,
    debugFilePath: `shaders/${module}.wesl`,
    src: source,
  });
  const declarations = new Map<string, Declaration>();
  const kinds = new Set(['fn', 'const', 'override', 'gvar', 'alias', 'struct']);
  for (const decl of ast.moduleElem.decls) {
    if (!kinds.has(decl.kind) || !('start' in decl)) continue;
    // fn, const, override, var, alias and struct declarations all name themselves first.
    const text = source.slice(decl.start, decl.end);
    const name =
      /^\s*(?:@[^\n]*\s+)?(?:fn|const|override|var(?:<[^>]*>)?|alias|struct)\s+([A-Za-z_]\w*)/.exec(
        text,
      )?.[1];
    if (name) declarations.set(name, { name, text });
  }
  return declarations;
}

/**
 * The WGSL of `names` in `shaders/<module>.wesl` and every declaration of that module
 * they use (transitively, in source order), each declared name and every use of it
 * renamed to `prefix + name`. Only same-module dependencies are followed (a name
 * imported from another module stays as it is, and the compiler reports it).
 */
export function prefixedDeclarations(
  library: ShaderLibrary,
  module: string,
  names: readonly string[],
  prefix: string,
): string {
  const declarations = declarationsOf(library, module);
  const needed = new Set<string>();
  const visit = (name: string): void => {
    if (needed.has(name)) return;
    const declaration = declarations.get(name);
    if (!declaration) throw new Error(`no declaration "${name}" in shaders/${module}.wesl`);
    needed.add(name);
    for (const word of declaration.text.match(IDENTIFIER) ?? [])
      if (word !== name && declarations.has(word)) visit(word);
  };
  for (const name of names) visit(name);
  const rename = (text: string): string =>
    text.replace(IDENTIFIER, (word) => (needed.has(word) ? `${prefix}${word}` : word));
  return [...declarations.values()]
    .filter((declaration) => needed.has(declaration.name))
    .map((declaration) => rename(declaration.text))
    .join('\n');
}
