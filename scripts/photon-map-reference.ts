// Converged reference of <sb-photon-map>'s caustic scene at the default parameters:
// the unbiased path tracer of shaders/kernels/photon-map.wesl (pathTrace), run through
// Dawn (SwiftShader without a GPU) in passes of PASS_SPP paths per pixel with
// independent streams, accumulated in float64. Writes public/photon-map/reference.bin:
// a 16-byte header (u32 width, height, samples per pixel, seed) then width·height
// float32 means and width·height float32 standard errors (√(sample variance / n)),
// row 0 at the top; the file is rewritten every CHECKPOINT passes, so a run cut short
// leaves a valid reference with the samples so far. Reproducible: `sh scripts/gpu-env.sh npx tsx scripts/photon-map-reference.ts [spp]`.
import { writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { linkLibraryKernel } from '../src/gpu/link.ts';
import { nodeDevice, releaseNodeDevice } from '../src/gpu/nodeDevice.ts';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { pathTraceGpu } from '../src/widgets/photon-map/gpuBackend.ts';
import { DEFAULT_INPUTS, GPU_SIZE, REFERENCE_SEED } from '../src/widgets/photon-map/model.ts';

const PASS_SPP = 64;
// The committed reference (public/photon-map/reference.bin) has 131072 paths per pixel.
const spp = Number(process.argv[2] ?? 131072);
const { width, height } = GPU_SIZE;
const library = loadShaderLibrary(fileURLToPath(new URL('../shaders', import.meta.url)));
const code = await linkLibraryKernel(library, 'kernels/photon-map.wesl');
const device = await nodeDevice();
const sum = new Float64Array(width * height);
const sumSq = new Float64Array(width * height);
const passes = Math.ceil(spp / PASS_SPP);
const path = fileURLToPath(new URL('../public/photon-map/reference.bin', import.meta.url));

/** Writes the file for the passes so far (a checkpoint every CHECKPOINT passes and at the end). */
function save(done: number): string {
  const n = done * PASS_SPP;
  const header = new Uint32Array([width, height, n, REFERENCE_SEED]);
  const mean = new Float32Array(width * height);
  const se = new Float32Array(width * height);
  let meanSe = 0;
  let meanL = 0;
  for (let i = 0; i < mean.length; i++) {
    const m = sum[i]! / n;
    mean[i] = m;
    se[i] = Math.sqrt(Math.max(0, sumSq[i]! / n - m * m) / (n - 1));
    meanSe += se[i]! / mean.length;
    meanL += m / mean.length;
  }
  const out = new Uint8Array(16 + 8 * width * height);
  out.set(new Uint8Array(header.buffer), 0);
  out.set(new Uint8Array(mean.buffer), 16);
  out.set(new Uint8Array(se.buffer), 16 + 4 * width * height);
  writeFileSync(path, out);
  return `${width}×${height}, ${n} spp, mean L ${meanL.toExponential(4)}, mean SE ${meanSe.toExponential(3)}`;
}

const CHECKPOINT = 32;
for (let pass = 0; pass < passes; pass++) {
  // Stream REFERENCE_SEED + pass: disjoint from the widget's progressive passes (seeds < 2^20).
  const r = await pathTraceGpu(
    device,
    code,
    DEFAULT_INPUTS,
    width,
    height,
    PASS_SPP,
    REFERENCE_SEED + pass,
  );
  for (let i = 0; i < sum.length; i++) {
    sum[i]! += r.sum[i]!;
    sumSq[i]! += r.sumSq[i]!;
  }
  if ((pass + 1) % CHECKPOINT === 0 && pass + 1 < passes)
    process.stderr.write(`checkpoint: ${save(pass + 1)}\n`);
}
console.log(`wrote ${path}: ${save(passes)}`);
releaseNodeDevice();
