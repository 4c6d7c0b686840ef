// The Gradescope autograder kit of one exercise: a folder and the same files as a
// zip to upload (Gradescope's "Configure Autograder" → "Zip file upload"). Per the
// spec (https://gradescope-autograders.readthedocs.io/en/latest/specs/), the zip's
// root holds `setup.sh`, run once as root on the base image (Ubuntu 22.04) with the
// zip unpacked at /autograder/source, and `run_autograder`, which Gradescope copies
// to /autograder/run_autograder and runs for each submission (files in
// /autograder/submission), expecting /autograder/results/results.json.
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { loadExercise } from '../../../exercises/index.ts';
import {
  PROJECT_ENV,
  PROJECT_FOLDER,
  driverInvocation,
  lastResortReport,
  shellQuote,
  text,
  writeTree,
  type KitFile,
} from './common.ts';
import { projectCopy } from './project.ts';
import { createZip } from './zip.ts';

export interface GradescopeKitOptions {
  exercise: string;
  out: string;
  timeLimitS: number;
  /** Node.js version setup.sh installs (default: the one that wrote the kit, if ≥ 20). */
  nodeVersion: string;
}

export interface WrittenKit {
  folder: string;
  zip?: string;
  files: string[];
}

function setupScript(options: GradescopeKitOptions): string {
  return `#!/usr/bin/env bash
# Gradescope autograder setup for the Scatterbook exercise "${options.exercise}" (written by
# \`npm run grade -- kit gradescope\`). Gradescope runs it once, as root, when it builds
# the autograder image: base image Ubuntu 22.04, this folder unpacked at /autograder/source.
set -euo pipefail
HERE="$(cd "$(dirname "\${BASH_SOURCE[0]}")" && pwd)"
NODE_VERSION=${shellQuote(options.nodeVersion)}
export DEBIAN_FRONTEND=noninteractive

apt-get update
apt-get install -y --no-install-recommends ca-certificates curl xz-utils libvulkan1

# 1. Node.js >= 20 from the official binary archive (https://nodejs.org/dist/), checked
#    against the release's SHASUMS256.txt, unpacked into /usr/local.
if ! command -v node >/dev/null 2>&1 || [ "$(node -p 'process.versions.node.split(".")[0]')" -lt 20 ]; then
  case "$(uname -m)" in
    x86_64) arch=x64 ;;
    aarch64) arch=arm64 ;;
    *) echo "setup.sh: no Node.js build for $(uname -m)" >&2; exit 1 ;;
  esac
  tarball="node-v\${NODE_VERSION}-linux-\${arch}.tar.xz"
  cd /tmp
  curl -fsSLO "https://nodejs.org/dist/v\${NODE_VERSION}/\${tarball}"
  curl -fsSL "https://nodejs.org/dist/v\${NODE_VERSION}/SHASUMS256.txt" | grep " \${tarball}\\$" | sha256sum -c -
  tar -xJf "\${tarball}" -C /usr/local --strip-components=1 --no-same-owner
  rm -f "\${tarball}"
fi
node --version

# 2. WebGPU without a GPU: Dawn (the \`webgpu\` npm package) runs on SwiftShader, the
#    software Vulkan driver Chromium ships. Ubuntu's chromium is a snap (no snaps in
#    Gradescope's container), so SwiftShader comes from Google Chrome's .deb, which
#    installs it as /opt/google/chrome/vk_swiftshader_icd.json.
ICD=/opt/google/chrome/vk_swiftshader_icd.json
if [ ! -f "$ICD" ]; then
  curl -fsSL -o /tmp/google-chrome.deb https://dl.google.com/linux/direct/google-chrome-stable_current_amd64.deb
  apt-get install -y --no-install-recommends /tmp/google-chrome.deb
  rm -f /tmp/google-chrome.deb
fi
if [ ! -f "$ICD" ]; then
  echo "setup.sh: $ICD is missing after installing Google Chrome; grading needs SwiftShader" >&2
  exit 1
fi

# 3. The grader, with the package versions of the bundled lockfile.
cd "$HERE/${PROJECT_FOLDER}"
npm ci --no-audit --no-fund

# 4. Prove the installation grades: the exercise's self-test (the reference scores full
#    marks, every known-wrong submission its expected score). A failure fails the build.
VK_ICD_FILENAMES="$ICD" node --import tsx src/grading/cli.ts --self-test --exercise ${shellQuote(options.exercise)}
`;
}

function runScript(options: GradescopeKitOptions, fallback: string): string {
  return `#!/usr/bin/env bash
# Gradescope runs this for every submission (as /autograder/run_autograder). It grades
# the one .wgsl file under $AUTOGRADER_ROOT/submission (default /autograder) for the
# Scatterbook exercise "${options.exercise}" within ${options.timeLimitS} s and writes
# $AUTOGRADER_ROOT/results/results.json, also when grading fails.
# $${PROJECT_ENV} points at another installed copy of the project (the kit tests use it).
ROOT="\${AUTOGRADER_ROOT:-/autograder}"
PROJECT="\${${PROJECT_ENV}:-$ROOT/source/${PROJECT_FOLDER}}"
export AUTOGRADER_ROOT="$ROOT"
${driverInvocation({
  platform: 'gradescope',
  exerciseWord: shellQuote(options.exercise),
  timeLimitS: options.timeLimitS,
  results: '$ROOT/results/results.json',
  fallback,
})}`;
}

function readme(options: GradescopeKitOptions, zipName: string): string {
  return `Scatterbook autograder for Gradescope — exercise "${options.exercise}"

1. In Gradescope, create a "Programming Assignment"; in its settings allow file
   submissions and set the autograder timeout to at least ${options.timeLimitS + 120} s.
2. Configure Autograder → Base image: Ubuntu 22.04 → upload ${zipName} → Update Autograder.
   The build runs setup.sh (Node.js ${options.nodeVersion}, Google Chrome for SwiftShader,
   npm ci, then the exercise's self-test); it must end with "self-test passed".
3. Test Autograder with the reference solution, then with a wrong one.
Students submit one file, ${options.exercise}.wgsl (the exercise page's "Download
submission" button). Hidden checks appear when grades are published. A "Grading failed
— will be regraded" test marks a grader-side failure: regrade those submissions.
`;
}

export async function writeGradescopeKit(options: GradescopeKitOptions): Promise<WrittenKit> {
  const exercise = await loadExercise(options.exercise);
  const fallback = lastResortReport('gradescope', exercise.id, exercise.title);
  const zipName = `scatterbook-${exercise.id}-gradescope.zip`;
  const copy = projectCopy();
  const files: KitFile[] = [
    text('setup.sh', setupScript(options), 0o755),
    text('run_autograder', runScript(options, fallback), 0o755),
    text('README.txt', readme(options, zipName)),
    ...copy.files.map((f) => ({ path: `${PROJECT_FOLDER}/${f.path}`, data: f.data })),
  ];
  const folder = join(options.out, 'autograder');
  writeTree(folder, files);
  const zip = join(options.out, zipName);
  writeFileSync(
    zip,
    createZip(
      files.map((f) => ({ name: f.path, data: f.data, ...(f.mode ? { mode: f.mode } : {}) })),
    ),
  );
  return { folder, zip, files: files.map((f) => f.path) };
}
