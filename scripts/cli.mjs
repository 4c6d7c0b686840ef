// Starts the book's command line (src/cli/main.ts) fast: `npm run render` and `npm run cli`
// run this file with plain Node. tsx compiles every TypeScript module of the command on
// every start, which took 0.6–0.8 s of an idle machine (1.9–2.5 s under load) before the
// first line of main.ts ran (issue 19, `render --stats`: startup). Instead, esbuild (in
// node_modules through tsx and vite) bundles the command once into the git-ignored
// .cache/cli/, keyed by a hash of every source file the bundle holds, the listing of their
// folders (a new file that a glob import would take) and the build settings; later starts
// hash those files, find the bundle and import it (its packages stay in node_modules).
// Without esbuild, or when the bundle cannot be built or written, it runs tsx as before,
// so the commands work on a fresh clone and in a read-only checkout; SCATTERBOOK_TSX=1
// asks for tsx.
//
// The bundle lives two folders below the root, as src/cli/main.ts does, so the command's
// paths relative to import.meta.url (../../shaders, ../../public/, ../../.cache/wgsl) mean
// the same files in both.
import { spawn } from 'node:child_process';
import { createHash } from 'node:crypto';
import { mkdirSync, readdirSync, readFileSync, renameSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join, relative } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const ROOT = fileURLToPath(new URL('..', import.meta.url));
const ENTRY = 'src/cli/main.ts';
const CACHE = join(ROOT, '.cache', 'cli');
const MANIFEST = join(CACHE, 'manifest.json');
/** Files that change how esbuild reads the sources, hashed with them. */
const SETTINGS_FILES = ['tsconfig.json', 'package.json', 'scripts/cli.mjs'];
const BUILD_OPTIONS = {
  entryPoints: [ENTRY],
  bundle: true,
  platform: 'node',
  format: 'esm',
  target: 'node20',
  // Packages load from node_modules as they do under tsx (webgpu is a native addon).
  packages: 'external',
  // Modules the command imports on demand (eval's WESL parser, slab, the float64 twins)
  // stay in chunks of their own: in one file, esbuild hoists their packages' imports to
  // the top, and every start would load WESL.
  splitting: true,
  outdir: '.cache/cli',
  entryNames: '[name]-[hash]',
  chunkNames: 'chunk-[hash]',
  metafile: true,
  write: false,
  logLevel: 'silent',
};

/** The hash of the sources: each file's path and bytes, and each folder's .ts listing. */
function sourceDigest(inputs) {
  const hash = createHash('sha256');
  hash.update(JSON.stringify(BUILD_OPTIONS));
  const files = [...new Set([...inputs, ...SETTINGS_FILES])].sort();
  for (const file of files) hash.update(`${file}\0`).update(readFileSync(join(ROOT, file)));
  const folders = [...new Set(inputs.map((file) => dirname(file)))].sort();
  for (const folder of folders) {
    const names = readdirSync(join(ROOT, folder)).filter((name) => name.endsWith('.ts'));
    hash.update(`${folder}/\0${names.sort().join('\0')}\0`);
  }
  return hash.digest('hex').slice(0, 32);
}

/** The current bundle's path, or null when there is none or the sources changed. */
function cachedBundle() {
  let manifest;
  try {
    manifest = JSON.parse(readFileSync(MANIFEST, 'utf8'));
    if (manifest.digest !== sourceDigest(manifest.inputs)) return null;
  } catch {
    // No manifest yet, or a listed file is gone: build again.
    return null;
  }
  return join(CACHE, manifest.bundle);
}

/** Writes `data` under a temporary name and renames it, so no reader sees half a file. */
function writeAtomically(path, data) {
  const temporary = `${path}.${process.pid}.tmp`;
  writeFileSync(temporary, data);
  renameSync(temporary, path);
}

/** Builds and stores the bundle; null when esbuild is missing or the build fails. */
async function buildBundle() {
  let esbuild;
  try {
    esbuild = await import('esbuild');
  } catch {
    return null;
  }
  try {
    const result = await esbuild.build({ ...BUILD_OPTIONS, absWorkingDir: ROOT });
    const inputs = Object.keys(result.metafile.inputs)
      .filter((file) => !file.startsWith('node_modules/'))
      .map((file) => relative(ROOT, join(ROOT, file)));
    const digest = sourceDigest(inputs);
    mkdirSync(CACHE, { recursive: true });
    // Named by their contents: files of another build never collide with these.
    const files = result.outputFiles.map((file) => relative(CACHE, file.path));
    for (const file of result.outputFiles) writeAtomically(file.path, file.contents);
    const bundle = files.find((name) => name.startsWith('main-'));
    // The manifest last: a reader that finds it finds every file it names.
    writeAtomically(MANIFEST, JSON.stringify({ digest, bundle, inputs }));
    // Files of earlier builds are never read again.
    for (const name of readdirSync(CACHE))
      if (name.endsWith('.js') && !files.includes(name)) rmSync(join(CACHE, name), { force: true });
    return join(CACHE, bundle);
  } catch {
    // A source that does not build (tsx prints its error) or a read-only checkout.
    return null;
  }
}

/** The command under tsx, with this process's arguments and exit status. */
function runWithTsx() {
  const tsx = join(ROOT, 'node_modules', '.bin', 'tsx');
  const child = spawn(tsx, [join(ROOT, ENTRY), ...process.argv.slice(2)], { stdio: 'inherit' });
  child.on('error', (error) => {
    console.error(`scatterbook: cannot run tsx: ${error.message}`);
    process.exitCode = 1;
  });
  child.on('exit', (code, signal) => {
    if (signal) process.kill(process.pid, signal);
    else process.exitCode = code ?? 1;
  });
}

// SCATTERBOOK_TSX=1 runs the sources under tsx (stack traces in TypeScript; the tests).
const bundle =
  process.env.SCATTERBOOK_TSX === '1' ? null : (cachedBundle() ?? (await buildBundle()));
if (bundle) await import(pathToFileURL(bundle).href);
else runWithTsx();
