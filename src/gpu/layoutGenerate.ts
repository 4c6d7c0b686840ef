// Derives the layout table src/gpu/layouts.generated.ts from the WGSL the kernels really
// compile: every kernel under shaders/kernels/ is linked (as the widgets link it), and each
// struct bound as var<uniform> or var<storage> (directly or as an array's element) gets its
// layout from the linked text. The linker keeps struct names (checked here: a bound struct
// that the linked text does not declare is an error). Uniform-bound structs must meet the
// uniform constraints. Run `npx tsx src/gpu/layoutGenerate.ts` after changing such a struct;
// tests/gpu/layout.test.ts fails while the table is stale.
import { fileURLToPath } from 'node:url';
import { writeFileSync } from 'node:fs';
import { format } from 'prettier';
import type { StructLayout, TypeLayout } from './layout.ts';
import { layoutOfStruct, parseDeclarations, uniformViolations } from './layoutDerive.ts';
import { linkLibraryKernel, type ShaderLibrary } from './link.ts';

export type KernelLayouts = Record<string, Record<string, StructLayout>>;

/** The bound structs of one linked kernel's WGSL, keyed by struct name. */
export function boundStructLayouts(wgsl: string, kernel: string): Record<string, StructLayout> {
  const declarations = parseDeclarations(wgsl);
  const layouts: Record<string, StructLayout> = {};
  for (const binding of declarations.bindings) {
    const name = /^(?:array\s*<\s*)?([A-Za-z_]\w*)/.exec(binding.type)?.[1] ?? '';
    if (!declarations.structs.has(name)) {
      if (/^[A-Z]/.test(name)) {
        throw new Error(
          `${kernel}: ${binding.name} is bound as ${name}, which it does not declare`,
        );
      }
      continue;
    }
    const layout = layoutOfStruct(name, declarations);
    if (binding.space === 'uniform') {
      const problems = uniformViolations(layout);
      if (problems.length > 0) throw new Error(`${kernel}: ${problems.join('; ')}`);
    }
    layouts[name] = layout;
  }
  return layouts;
}

export async function deriveKernelLayouts(library: ShaderLibrary): Promise<KernelLayouts> {
  const table: KernelLayouts = {};
  const kernels = Object.keys(library)
    .filter((path) => path.startsWith('kernels/'))
    .sort();
  for (const kernel of kernels) {
    const layouts = boundStructLayouts(await linkLibraryKernel(library, kernel), kernel);
    if (Object.keys(layouts).length > 0) table[kernel] = layouts;
  }
  return table;
}

/** `kernels/beer-law.wesl` → `beerLawKernel`. */
export function exportName(kernel: string): string {
  const base = kernel.replace(/^kernels\//, '').replace(/\.wesl$/, '');
  return `${base.replace(/[-_.]+(\w)/g, (_, c: string) => c.toUpperCase())}Kernel`;
}

/**
 * The table as TypeScript: each distinct scalar, vector, matrix and nested struct is one
 * constant that the structs reference by name (the page ships this file; gzip alone does
 * not remove the repeated type objects as well).
 */
export async function generatedSource(table: KernelLayouts): Promise<string> {
  const constants = new Map<string, { name: string; code: string }>();
  const names = new Set<string>();
  const constant = (key: string, preferred: string, code: () => string): string => {
    const known = constants.get(key);
    if (known) return known.name;
    let name = preferred;
    for (let n = 2; names.has(name); n++) name = `${preferred}${n}`;
    names.add(name);
    // Set after its code, so that the constants it references come first.
    constants.set(key, { name, code: code() });
    return name;
  };
  const expression = (type: TypeLayout): string => {
    switch (type.kind) {
      case 'scalar':
      case 'vector':
      case 'matrix': {
        const suffix = type.scalar === 'f16' ? 'h' : type.scalar[0]!;
        const preferred =
          type.kind === 'scalar'
            ? type.scalar
            : type.kind === 'vector'
              ? `vec${type.length}${suffix}`
              : `mat${type.columns}x${type.rows}${suffix}`;
        return constant(JSON.stringify(type), preferred, () => `${JSON.stringify(type)} as const`);
      }
      case 'array':
        return `/* @__PURE__ */ array(${expression(type.element)}, ${type.count}, ${type.stride})`;
      case 'struct':
        return constant(JSON.stringify(type), type.name, () => structCall(type));
    }
  };
  const structCall = (layout: StructLayout): string => {
    const members = Object.entries(layout.members).map(([name, member]) => {
      const size = member.size === member.type.size ? '' : `, ${member.size}`;
      return `${name}: [${member.offset}, ${expression(member.type)}${size}]`;
    });
    // Pure: the bundler drops the layouts no page imports.
    return `/* @__PURE__ */ struct('${layout.name}', ${layout.size}, ${layout.align}, { ${members.join(', ')} })`;
  };
  const exports: string[] = [];
  for (const [kernel, layouts] of Object.entries(table)) {
    const entries = Object.entries(layouts).map(
      ([name, layout]) => `${name}: ${expression(layout)}`,
    );
    exports.push(
      `/** Bound structs of ${kernel}. */`,
      `export const ${exportName(kernel)} = { ${entries.join(', ')} };`,
      '',
    );
  }
  const lines = [
    '// Generated by src/gpu/layoutGenerate.ts from the struct declarations of the linked',
    '// kernels (shaders/kernels/*.wesl): do not edit. After changing a bound struct run',
    '// `npx tsx src/gpu/layoutGenerate.ts`; tests/shaders/layout.test.ts fails while this is stale.',
    "import { array, struct } from './layout.ts';",
    '',
    ...[...constants.values()].map(({ name, code }) => `const ${name} = ${code};`),
    '',
    ...exports,
    'export const KERNEL_LAYOUTS = {',
    ...Object.keys(table).map((kernel) => `  '${kernel}': ${exportName(kernel)},`),
    '} as const;',
  ];
  return format(lines.join('\n'), { parser: 'typescript', singleQuote: true, printWidth: 100 });
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
  const { loadShaderLibrary } = await import('./shaderSourcesNode.ts');
  const library = loadShaderLibrary(fileURLToPath(new URL('../../shaders', import.meta.url)));
  const target = fileURLToPath(new URL('./layouts.generated.ts', import.meta.url));
  writeFileSync(target, await generatedSource(await deriveKernelLayouts(library)));
  process.stdout.write(`wrote ${target}\n`);
}
