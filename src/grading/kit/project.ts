// The part of this project a grading machine needs, copied into a kit: the grading
// command line and the kit's driver with every module they import (followed from
// the source, so a new import is picked up without editing a list), all of
// exercises/ (statements, starters, hidden checks, known-wrong submissions for the
// self-test) and shaders/ (read from disk at run time), plus a package.json whose
// only dependencies are the npm packages those modules import (and tsx, which runs
// the TypeScript), and a package-lock.json pruned from this project's lockfile to
// exactly those packages, so `npm ci` on the grading machine installs the versions
// tested here.
import { existsSync, readFileSync, readdirSync, statSync } from 'node:fs';
import { dirname, join, posix, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

export const PROJECT_ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '../../..');

/** Entry points run on the grading machine. */
const ENTRY_POINTS = ['src/grading/cli.ts', 'src/grading/kit/driver.ts'];
/**
 * Not followed: writing a kit happens on the instructor's machine, never on the
 * grading machine (cli.ts loads it only for `grade kit`).
 */
const NOT_FOLLOWED = new Set(['src/grading/kit/index.ts']);
/** Folders copied whole: read from disk at run time, or loaded by the self-test. */
const WHOLE_FOLDERS = ['exercises', 'shaders'];
/** Runs the TypeScript sources without a build step. */
const RUNNER_PACKAGE = 'tsx';

export interface ProjectFile {
  /** '/'-separated path relative to the project root. */
  path: string;
  data: Uint8Array;
}

function listFiles(root: string, folder: string): string[] {
  const out: string[] = [];
  const walk = (dir: string): void => {
    for (const name of readdirSync(join(root, dir)).sort()) {
      const path = posix.join(dir, name);
      if (statSync(join(root, path)).isDirectory()) walk(path);
      else out.push(path);
    }
  };
  walk(folder);
  return out;
}

// Static and dynamic imports with a string literal; `import type` is matched
// separately so that a type-only package import adds no runtime dependency.
const IMPORT_FROM = /\b(import|export)(\s+type)?\s[^'"`;]*?\bfrom\s*['"]([^'"]+)['"]/g;
const IMPORT_BARE = /^\s*import\s*['"]([^'"]+)['"]/gm;
const IMPORT_DYNAMIC = /\bimport\s*\(\s*['"]([^'"]+)['"]\s*\)/g;
/**
 * A module named in a string and loaded at run time, e.g. a child process's script
 * `join(dirname(fileURLToPath(import.meta.url)), 'gradeWorker.ts')`: followed when
 * such a file exists next to the module that names it.
 */
const MODULE_STRING = /['"`]((?:\.{1,2}\/)?[\w./-]+\.(?:ts|mts|js|mjs))['"`]/g;

function packageName(specifier: string): string {
  const parts = specifier.split('/');
  return specifier.startsWith('@') ? parts.slice(0, 2).join('/') : (parts[0] ?? specifier);
}

/**
 * Every project source reachable from `entries` through relative imports, and the
 * npm packages imported at run time. A relative import of a missing file throws.
 */
export function sourceClosure(
  root: string,
  entries: readonly string[],
): { files: string[]; packages: string[] } {
  const files = new Set<string>();
  const packages = new Set<string>();
  const queue = [...entries];
  while (queue.length > 0) {
    const file = queue.pop() as string;
    if (files.has(file) || NOT_FOLLOWED.has(file)) continue;
    if (!existsSync(join(root, file))) throw new Error(`kit: ${file} is imported but missing`);
    files.add(file);
    if (!/\.(ts|mts|js|mjs)$/.test(file)) continue;
    // Comments may quote import syntax; drop them before matching.
    const text = readFileSync(join(root, file), 'utf8')
      .replace(/\/\*[\s\S]*?\*\//g, '')
      .replace(/(^|[^:'"`])\/\/.*$/gm, '$1');
    const found: { specifier: string; typeOnly: boolean }[] = [];
    for (const m of text.matchAll(IMPORT_FROM))
      found.push({ specifier: m[3] ?? '', typeOnly: Boolean(m[2]) });
    for (const m of text.matchAll(IMPORT_BARE))
      found.push({ specifier: m[1] ?? '', typeOnly: false });
    for (const m of text.matchAll(IMPORT_DYNAMIC))
      found.push({ specifier: m[1] ?? '', typeOnly: false });
    for (const m of text.matchAll(MODULE_STRING)) {
      const path = posix.normalize(posix.join(posix.dirname(file), m[1] ?? ''));
      if (
        !path.startsWith('..') &&
        existsSync(join(root, path)) &&
        statSync(join(root, path)).isFile()
      )
        queue.push(path);
    }
    for (const { specifier, typeOnly } of found) {
      if (specifier.startsWith('.')) {
        queue.push(posix.normalize(posix.join(posix.dirname(file), specifier)));
      } else if (!specifier.startsWith('node:') && !typeOnly) {
        packages.add(packageName(specifier));
      }
    }
  }
  return { files: [...files].sort(), packages: [...packages].sort() };
}

interface LockEntry {
  version?: string;
  dependencies?: Record<string, string>;
  optionalDependencies?: Record<string, string>;
  peerDependencies?: Record<string, string>;
  peerDependenciesMeta?: Record<string, { optional?: boolean }>;
  dev?: boolean;
  optional?: boolean;
  devOptional?: boolean;
  [key: string]: unknown;
}

interface Lockfile {
  name: string;
  version: string;
  lockfileVersion: number;
  requires?: boolean;
  packages: Record<string, LockEntry>;
}

/** Where Node finds package `name` from the package installed at `from` ('' = the root). */
function resolveInLock(packages: Record<string, LockEntry>, from: string, name: string) {
  let base = from;
  for (;;) {
    const candidate = `${base ? `${base}/` : ''}node_modules/${name}`;
    if (packages[candidate]) return candidate;
    if (!base) return undefined;
    const up = base.lastIndexOf('/node_modules/');
    base = up < 0 ? '' : base.slice(0, up);
  }
}

/**
 * A lockfile holding only `dependencies` (name → exact version, all present in
 * this project's lockfile) and what they need. Packages reached only through
 * optional edges (platform builds of esbuild, fsevents) stay optional.
 */
export function pruneLockfile(lock: Lockfile, name: string, dependencies: Record<string, string>) {
  const packages = lock.packages;
  const required = new Set<string>();
  const optional = new Set<string>();
  const visit = (from: string, deps: Record<string, string>, isOptional: boolean): void => {
    for (const dep of Object.keys(deps)) {
      const at = resolveInLock(packages, from, dep);
      if (!at) {
        if (isOptional) continue;
        throw new Error(`kit: ${dep} (needed by ${from || 'the kit'}) is not in package-lock.json`);
      }
      const target = isOptional ? optional : required;
      if (required.has(at) || target.has(at)) continue;
      target.add(at);
      if (!isOptional) optional.delete(at);
      const entry = packages[at] as LockEntry;
      visit(at, entry.dependencies ?? {}, isOptional);
      visit(at, entry.optionalDependencies ?? {}, true);
      const peers = entry.peerDependencies ?? {};
      for (const peer of Object.keys(peers)) {
        const peerOptional = entry.peerDependenciesMeta?.[peer]?.optional ?? false;
        visit(at, { [peer]: peers[peer] ?? '' }, isOptional || peerOptional);
      }
    }
  };
  visit('', dependencies, false);
  const out: Record<string, LockEntry> = {
    '': { name, version: '1.0.0', license: 'MIT', dependencies },
  };
  for (const key of Object.keys(packages).sort()) {
    if (!required.has(key) && !optional.has(key)) continue;
    const entry = { ...(packages[key] as LockEntry) };
    delete entry.dev;
    delete entry.devOptional;
    delete entry.optional;
    if (!required.has(key)) entry.optional = true;
    out[key] = entry;
  }
  return {
    name,
    version: '1.0.0',
    lockfileVersion: lock.lockfileVersion,
    requires: true,
    packages: out,
  };
}

export interface ProjectCopy {
  files: ProjectFile[];
  /** npm packages the kit installs, name → exact version. */
  dependencies: Record<string, string>;
}

/** The files a grading machine needs, relative to the copy's root. */
export function projectCopy(root = PROJECT_ROOT, extra: Record<string, string> = {}): ProjectCopy {
  const exerciseSources = WHOLE_FOLDERS.flatMap((folder) => listFiles(root, folder));
  const closure = sourceClosure(root, [
    ...ENTRY_POINTS,
    ...exerciseSources.filter((f) => f.endsWith('.ts')),
  ]);
  const paths = new Set([...closure.files, ...exerciseSources, 'tsconfig.json']);
  const lock = JSON.parse(readFileSync(join(root, 'package-lock.json'), 'utf8')) as Lockfile;
  const dependencies: Record<string, string> = {};
  for (const pkg of [...closure.packages, RUNNER_PACKAGE].sort()) {
    const version = lock.packages[`node_modules/${pkg}`]?.version;
    if (!version) throw new Error(`kit: package ${pkg} is imported but not in package-lock.json`);
    dependencies[pkg] = version;
  }
  const rootPackage = JSON.parse(readFileSync(join(root, 'package.json'), 'utf8')) as {
    engines?: Record<string, string>;
  };
  const kitName = 'scatterbook-grader';
  const packageJson = {
    name: kitName,
    version: '1.0.0',
    private: true,
    type: 'module',
    description: 'Scatterbook exercise grader (generated by `npm run grade -- kit`; do not edit)',
    license: 'MIT',
    engines: rootPackage.engines ?? { node: '>=20' },
    dependencies,
  };
  const encoder = new TextEncoder();
  const files: ProjectFile[] = [...paths].sort().map((path) => ({
    path,
    data: new Uint8Array(readFileSync(join(root, path))),
  }));
  files.push(
    { path: 'package.json', data: encoder.encode(`${JSON.stringify(packageJson, null, 2)}\n`) },
    {
      path: 'package-lock.json',
      data: encoder.encode(
        `${JSON.stringify(pruneLockfile(lock, kitName, dependencies), null, 2)}\n`,
      ),
    },
  );
  for (const [path, text] of Object.entries(extra))
    files.push({ path, data: encoder.encode(text) });
  return { files, dependencies };
}

/** `path` relative to the project root, '/'-separated (for messages). */
export function projectRelative(path: string): string {
  return relative(PROJECT_ROOT, path).split('\\').join('/');
}
