// Reads the shader library's doc comments: a module's leading `//` block
// describes it, and `///` lines document the declaration that follows them.
// Used by the "Shader library" appendix and by the test that every library
// function has a float64 twin (DESIGN.md contract 1).
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';

export interface ShaderDeclaration {
  kind: 'fn' | 'struct' | 'const';
  name: string;
  /** The declaration as written: a function's signature up to `{`, a struct's body, a const line. */
  signature: string;
  /** Markdown from the `///` lines above it. */
  doc: string;
}

export interface ShaderModuleDocs {
  /** Module name, e.g. `transmittance` (file `shaders/transmittance.wesl`). */
  name: string;
  description: string;
  declarations: ShaderDeclaration[];
}

const DECLARATION = /^(fn|struct|const)\s+([A-Za-z_][A-Za-z0-9_]*)/;

export function parseShaderModule(name: string, source: string): ShaderModuleDocs {
  const lines = source.split('\n');
  const description: string[] = [];
  let index = 0;
  while (index < lines.length && /^\s*\/\/(?!\/)/.test(lines[index] ?? '')) {
    description.push((lines[index] ?? '').replace(/^\s*\/\/ ?/, ''));
    index += 1;
  }
  const declarations: ShaderDeclaration[] = [];
  let doc: string[] = [];
  for (; index < lines.length; index++) {
    const line = lines[index] ?? '';
    if (/^\s*\/\/\//.test(line)) {
      doc.push(line.replace(/^\s*\/\/\/ ?/, ''));
      continue;
    }
    const match = DECLARATION.exec(line);
    if (match) {
      const kind = match[1] as ShaderDeclaration['kind'];
      let signature = line;
      if (kind === 'fn') {
        let end = index;
        while (!signature.includes('{') && end + 1 < lines.length)
          signature += `\n${lines[++end] ?? ''}`;
        signature = signature.slice(0, signature.indexOf('{')).trim();
      } else if (kind === 'struct') {
        let end = index;
        while (!/^\s*}/.test(lines[end] ?? '') && end + 1 < lines.length)
          signature += `\n${lines[++end] ?? ''}`;
      }
      declarations.push({
        kind,
        name: match[2] ?? '',
        signature: signature.trim(),
        doc: doc.join('\n').trim(),
      });
    }
    // Any other line ends the doc block: it documents only the declaration right below it.
    doc = [];
  }
  return { name, description: description.join('\n').trim(), declarations };
}

/** The library modules (not kernels), in alphabetical order. */
export function loadShaderDocs(shadersDirectory: string): ShaderModuleDocs[] {
  return readdirSync(shadersDirectory)
    .filter((file) => file.endsWith('.wesl'))
    .sort()
    .map((file) =>
      parseShaderModule(
        file.replace(/\.wesl$/, ''),
        readFileSync(join(shadersDirectory, file), 'utf8'),
      ),
    );
}
