// The entry points of linked WGSL and the pipelines a test builds from them: every
// @compute entry alone, and every @vertex / @fragment entry in a render pipeline with
// a partner whose interface matches (the fragment's @location inputs are a subset of
// the vertex's outputs). Pipelines are where some validation happens only (interface
// matching, the 'auto' layout, workgroup limits), so compiling a module is not enough.
import type { RenderPair } from './denoGpu.ts';

export interface EntryPoint {
  stage: 'compute' | 'vertex' | 'fragment';
  name: string;
  /** The parameter list as written. */
  params: string;
  /** The return type as written (with its attributes), or ''. */
  result: string;
}

/** Text from `open` (an opening parenthesis) to its matching `)`, exclusive. */
function balanced(code: string, open: number): { text: string; end: number } {
  let depth = 0;
  for (let i = open; i < code.length; i++) {
    if (code[i] === '(') depth++;
    else if (code[i] === ')' && --depth === 0) return { text: code.slice(open + 1, i), end: i + 1 };
  }
  throw new Error('unbalanced parentheses in WGSL');
}

export function entryPoints(code: string): EntryPoint[] {
  const found: EntryPoint[] = [];
  const stagePattern = /@(compute|vertex|fragment)\b/g;
  for (let match = stagePattern.exec(code); match; match = stagePattern.exec(code)) {
    // The next `fn` header; other attributes (e.g. @workgroup_size(8, 8)) lie between.
    const fn = /\bfn\s+([A-Za-z_][A-Za-z0-9_]*)\s*\(/g;
    fn.lastIndex = match.index;
    const header = fn.exec(code);
    if (!header) continue;
    const { text: params, end } = balanced(code, header.index + header[0].length - 1);
    const brace = code.indexOf('{', end);
    const arrow = code.slice(end, brace).trim();
    found.push({
      stage: match[1] as EntryPoint['stage'],
      name: header[1] as string,
      params,
      result: arrow.startsWith('->') ? arrow.slice(2).trim() : '',
    });
  }
  return found;
}

/** @location(n) → its type, from a struct declaration. */
function structLocations(code: string, name: string): Map<number, string> {
  const declaration = new RegExp(`\\bstruct\\s+${name}\\s*\\{([^}]*)\\}`).exec(code);
  const locations = new Map<number, string>();
  if (!declaration) return locations;
  const field =
    /@location\((\d+)\)(?:\s*@[a-z_]+(?:\([^)]*\))?)*\s*[A-Za-z_][A-Za-z0-9_]*\s*:\s*([^,}]+)/g;
  for (const m of (declaration[1] ?? '').matchAll(field))
    locations.set(Number(m[1]), (m[2] ?? '').trim());
  return locations;
}

/** Locations of a parameter list or a result: direct @location(n) T, or a struct's fields. */
function locationsOf(code: string, text: string): Map<number, string> {
  const locations = new Map<number, string>();
  const direct =
    /@location\((\d+)\)(?:\s*@[a-z_]+(?:\([^)]*\))?)*\s*(?:[A-Za-z_][A-Za-z0-9_]*\s*:\s*)?([A-Za-z0-9_<>]+)/g;
  for (const m of text.matchAll(direct)) locations.set(Number(m[1]), m[2] ?? '');
  // Struct-typed parameters (`in: SurfaceOut`) or a struct result (`-> SurfaceOut`).
  const withoutAttributes = text.replace(/@[a-z_]+(?:\([^)]*\))?/g, '');
  for (const m of withoutAttributes.matchAll(/(?::\s*|^\s*)([A-Z][A-Za-z0-9_]*)/g))
    for (const [k, v] of structLocations(code, m[1] ?? '')) locations.set(k, v);
  return locations;
}

/** The colour target format a fragment output of this WGSL type writes to. */
function targetFormat(type: string): GPUTextureFormat {
  if (/^(u32|vec[234]u|vec[234]<u32>)$/.test(type)) return 'rgba32uint';
  if (/^(i32|vec[234]i|vec[234]<i32>)$/.test(type)) return 'rgba32sint';
  return 'rgba8unorm';
}

/** Compute entries, and render pairs covering every vertex and fragment entry. */
export function pipelinesFor(code: string): { compute: string[]; render: RenderPair[] } {
  const entries = entryPoints(code);
  const compute = entries.filter((e) => e.stage === 'compute').map((e) => e.name);
  const vertices = entries.filter((e) => e.stage === 'vertex');
  const fragments = entries.filter((e) => e.stage === 'fragment');
  const outputs = new Map(vertices.map((v) => [v.name, locationsOf(code, v.result)]));
  const fits = (vertex: EntryPoint, fragment: EntryPoint): boolean => {
    const out = outputs.get(vertex.name) ?? new Map<number, string>();
    for (const [location, type] of locationsOf(code, fragment.params))
      if (out.get(location) !== type) return false;
    return true;
  };
  const targetsOf = (fragment: EntryPoint): GPUColorTargetState[] => {
    const locations = locationsOf(code, fragment.result);
    const count = Math.max(0, ...[...locations.keys()].map((k) => k + 1));
    return Array.from({ length: count }, (_, k) => ({
      format: targetFormat(locations.get(k) ?? 'vec4f'),
    }));
  };
  const render: RenderPair[] = [];
  const usedVertices = new Set<string>();
  for (const fragment of fragments) {
    const vertex = vertices.find((v) => fits(v, fragment));
    if (!vertex) throw new Error(`no vertex entry point matches fragment ${fragment.name}`);
    usedVertices.add(vertex.name);
    render.push({ vertex: vertex.name, fragment: fragment.name, targets: targetsOf(fragment) });
  }
  for (const vertex of vertices) {
    if (usedVertices.has(vertex.name)) continue;
    const fragment = fragments.find((f) => fits(vertex, f));
    if (!fragment) throw new Error(`no fragment entry point matches vertex ${vertex.name}`);
    render.push({ vertex: vertex.name, fragment: fragment.name, targets: targetsOf(fragment) });
  }
  return { compute, render };
}
