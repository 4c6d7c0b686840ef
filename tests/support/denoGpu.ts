// The second WebGPU engine of the tests: wgpu with the naga shader compiler (the
// engine of Firefox), reached through Deno's navigator.gpu in a child process
// (scripts/naga-check.js). Callers send one batch: shader modules to compile (with
// the pipelines to create from them) and compute jobs to run; the answer comes back
// as JSON. Deno starts in ~0.2 s, so each test file sends one batch.
//
// Vulkan driver (wgpu's Vulkan backend only, as Firefox on Linux): lavapipe (Mesa's
// CPU driver, Debian's mesa-vulkan-drivers) when it is installed, else the SwiftShader
// driver Debian's chromium ships; SB_WGPU_ICD names another manifest. Without Deno or
// without an adapter the batch fails with a message that says what to install: a
// second engine that silently skips would hide exactly the failures it is for.
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, readdirSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const ROOT = fileURLToPath(new URL('../../', import.meta.url));
const SCRIPT = join(ROOT, 'scripts/naga-check.js');

export interface RenderPair {
  vertex: string;
  fragment: string;
  targets: GPUColorTargetState[];
}

export interface CompileRequest {
  /** Names the source in test titles and errors, e.g. `kernel delta-tracking`. */
  name: string;
  code: string;
  /** Compute entry points to build a pipeline for (layout 'auto'). */
  compute?: readonly string[];
  /** Vertex + fragment pairs to build a render pipeline for (layout 'auto'). */
  render?: readonly RenderPair[];
}

export interface CompileMessage {
  type: 'error' | 'warning' | 'info';
  line: number;
  column: number;
  message: string;
}

export interface CompileAnswer {
  name: string;
  messages: CompileMessage[];
  pipelines: { kind: 'compute' | 'render'; entry: string; error: string | null }[];
}

export interface EvaluateJob {
  name: string;
  code: string;
  entryPoint: string;
  /** Read-only storage buffers at bindings 0..n-1; the output is binding n. */
  inputs: readonly Uint32Array[];
  outputWords: number;
  workgroups: readonly [number, number?, number?];
}

export interface EvaluateAnswer {
  name: string;
  output: Uint32Array | null;
  error: string | null;
}

export interface WgpuAnswer {
  engine: { adapter: string; fallback: boolean; icd: string };
  /** Set when the device was lost during the batch. */
  lost: string | null;
  compile: CompileAnswer[];
  evaluate: EvaluateAnswer[];
}

/** The Deno executable: $DENO_BIN, the npm package `deno` (a dev dependency), or PATH. */
export function denoBinary(): string | null {
  const fromEnv = process.env.DENO_BIN;
  if (fromEnv && existsSync(fromEnv)) return fromEnv;
  const candidates = [join(ROOT, 'node_modules/deno/deno')];
  try {
    const require = createRequire(import.meta.url);
    const target = `@deno/${process.platform}-${process.arch === 'arm64' ? 'arm64' : 'x64'}${process.platform === 'linux' ? '-glibc' : ''}`;
    candidates.push(join(dirname(require.resolve(`${target}/package.json`)), 'deno'));
  } catch {
    // The platform package is optional; the other candidates remain.
  }
  for (const path of (process.env.PATH ?? '').split(':'))
    if (path) candidates.push(join(path, 'deno'));
  return candidates.find((path) => existsSync(path)) ?? null;
}

/** The Vulkan driver manifest for wgpu: $SB_WGPU_ICD, else lavapipe when installed, else SwiftShader. */
export function vulkanIcd(): string | null {
  const forced = process.env.SB_WGPU_ICD;
  if (forced) return existsSync(forced) ? forced : null;
  const folder = '/usr/share/vulkan/icd.d';
  const lavapipe = existsSync(folder)
    ? readdirSync(folder).find((name) => /^lvp_icd\..*\.json$/.test(name))
    : undefined;
  if (lavapipe) return join(folder, lavapipe);
  const swiftShader = '/usr/lib/chromium/vk_swiftshader_icd.json';
  return existsSync(swiftShader) ? swiftShader : null;
}

const toBase64 = (words: Uint32Array): string =>
  Buffer.from(words.buffer, words.byteOffset, words.byteLength).toString('base64');

function fromBase64(text: string): Uint32Array {
  const bytes = Buffer.from(text, 'base64');
  const words = new Uint32Array(bytes.length >> 2);
  new Uint8Array(words.buffer).set(bytes.subarray(0, words.length * 4));
  return words;
}

/** Sends one batch to wgpu (Deno) and returns its answer; throws with what to install. */
export async function runOnWgpu(
  batch: { compile?: readonly CompileRequest[]; evaluate?: readonly EvaluateJob[] },
  timeoutMs = 240_000,
): Promise<WgpuAnswer> {
  const deno = denoBinary();
  if (!deno)
    throw new Error(
      'wgpu tests need Deno: run `npm install` (the dev dependency `deno` brings the binary) or set DENO_BIN',
    );
  const icd = vulkanIcd();
  if (!icd)
    throw new Error(
      'wgpu tests need a Vulkan driver: `sudo apt-get install -y mesa-vulkan-drivers` (lavapipe) or chromium (SwiftShader)',
    );
  const request = JSON.stringify({
    compile: batch.compile ?? [],
    evaluate: (batch.evaluate ?? []).map((job) => ({
      ...job,
      inputs: job.inputs.map(toBase64),
    })),
  });
  const child = spawn(deno, ['run', '--allow-read', '--allow-env', '--unstable-webgpu', SCRIPT], {
    cwd: ROOT,
    env: {
      ...process.env,
      VK_ICD_FILENAMES: icd,
      // Vulkan only, as Firefox on Linux: without this wgpu quietly falls back to its
      // OpenGL backend (Mesa's llvmpipe) when the Vulkan driver does not load.
      DENO_WEBGPU_BACKEND: 'vulkan',
      // Deno warns on stderr when this is unset or not private; a fresh folder is both.
      XDG_RUNTIME_DIR: mkdtempSync(join(tmpdir(), 'sb-deno-')),
      NO_COLOR: '1',
    },
    stdio: ['pipe', 'pipe', 'pipe'],
  });
  const stdout: Buffer[] = [];
  const stderr: Buffer[] = [];
  child.stdout.on('data', (chunk: Buffer) => stdout.push(chunk));
  child.stderr.on('data', (chunk: Buffer) => stderr.push(chunk));
  const exit = new Promise<number | null>((resolve, reject) => {
    child.on('error', reject);
    child.on('close', (code) => resolve(code));
  });
  const timer = setTimeout(() => child.kill('SIGKILL'), timeoutMs);
  child.stdin.end(request);
  let code: number | null;
  try {
    code = await exit;
  } finally {
    clearTimeout(timer);
  }
  const errorText = Buffer.concat(stderr).toString('utf8').trim();
  if (code !== 0) {
    const hint = /no WebGPU adapter/.test(errorText)
      ? ' (the Vulkan driver did not load: `sudo apt-get install -y mesa-vulkan-drivers`, or set SB_WGPU_ICD to a working ICD manifest)'
      : '';
    throw new Error(
      `wgpu (Deno ${deno}, VK_ICD_FILENAMES=${icd}) exited with ${code ?? 'a signal (time limit?)'}: ${errorText || 'no message'}${hint}`,
    );
  }
  const answer = JSON.parse(Buffer.concat(stdout).toString('utf8')) as Omit<
    WgpuAnswer,
    'evaluate' | 'engine'
  > & {
    engine: { adapter: string; fallback: boolean };
    evaluate: { name: string; output: string | null; error: string | null }[];
  };
  return {
    ...answer,
    engine: { ...answer.engine, icd },
    evaluate: answer.evaluate.map((result) => ({
      ...result,
      output: result.output === null ? null : fromBase64(result.output),
    })),
  };
}
