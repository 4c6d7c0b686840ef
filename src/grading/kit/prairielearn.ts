// The PrairieLearn kit: a course folder with one externally graded question per
// exercise and the definition of the external-grader image. Per PrairieLearn's docs
// (externalGrading.md, elements/pl-file-editor.md): a question's info.json sets
// gradingMethod "External" and externalGradingOptions {image, entrypoint, timeout};
// question.html holds the statement, a pl-file-editor whose file-name is the file the
// grader receives in /grade/student, and pl-external-grader-results in the submission
// panel. The grader container gets /grade/data/data.json and /grade/student/, and must
// write /grade/results/results.json.
import { createHash } from 'node:crypto';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import MarkdownIt from 'markdown-it';
import { tex } from '@mdit/plugin-tex';
import { EXERCISE_IDS, loadExercise } from '../../../exercises/index.ts';
import { EXERCISES_DIR } from '../node.ts';
import {
  PROJECT_ENV,
  PROJECT_FOLDER,
  driverInvocation,
  lastResortReport,
  text,
  writeTree,
  type KitFile,
} from './common.ts';
import type { WrittenKit } from './gradescope.ts';
import { projectCopy } from './project.ts';

export interface PrairieLearnKitOptions {
  out: string;
  timeLimitS: number;
  /** Docker image name the questions use (the instructor pushes it there). */
  image: string;
}

/** Where the image installs the grader's npm packages (package.json, node_modules). */
export const IMAGE_PROJECT = '/opt/scatterbook';
export const IMAGE_NODE_MODULES = `${IMAGE_PROJECT}/node_modules`;
/** Overrides IMAGE_NODE_MODULES for entrypoint.sh (the kit tests use this checkout's). */
export const NODE_MODULES_ENV = 'SCATTERBOOK_NODE_MODULES';
/** PrairieLearn's largest external-grading timeout, seconds. */
const PL_MAX_TIMEOUT_S = 600;
/** The question folder's topic; it must exist in the course's infoCourse.json. */
export const PL_TOPIC = 'Scatterbook';

/**
 * A UUID that is the same every time the kit is written for `id` (RFC 4122 §4.3,
 * name-based with SHA-1, version 5), so regenerating the kit updates the questions
 * instead of creating new ones.
 */
export function questionUuid(id: string): string {
  // Namespace: the UUID of the URL namespace (RFC 4122 appendix C).
  const namespace = Buffer.from('6ba7b8119dad11d180b400c04fd430c8', 'hex');
  const hash = createHash('sha1')
    .update(namespace)
    .update(`https://scatterbook/exercises/${id}`)
    .digest();
  hash[6] = ((hash[6] ?? 0) & 0x0f) | 0x50;
  hash[8] = ((hash[8] ?? 0) & 0x3f) | 0x80;
  const hex = hash.subarray(0, 16).toString('hex');
  return `${hex.slice(0, 8)}-${hex.slice(8, 12)}-${hex.slice(12, 16)}-${hex.slice(16, 20)}-${hex.slice(20)}`;
}

function escapeHtml(value: string): string {
  return value.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
}

/**
 * The statement as HTML for PrairieLearn: Markdown rendered here, TeX left for
 * PrairieLearn's MathJax as \( … \) and \[ … \], headings demoted under the page's
 * own, and `{{` / `}}` split because question.html is a Mustache template.
 */
export function statementHtml(markdown: string): string {
  const md = new MarkdownIt({ html: false, linkify: false, typographer: false });
  md.use(tex, {
    delimiters: 'dollars',
    render: (content: string, displayMode: boolean) =>
      displayMode ? `<p>\\[${escapeHtml(content)}\\]</p>` : `\\(${escapeHtml(content)}\\)`,
  });
  return md
    .render(markdown)
    .replace(
      /<(\/?)h([1-6])\b/g,
      (_all, slash: string, level: string) => `<${slash}h${Math.min(6, Number(level) + 2)}`,
    )
    .replace(/\{(?=\{)/g, '{ ')
    .replace(/\}(?=\})/g, '} ');
}

function questionHtml(id: string, statement: string): string {
  return `<pl-question-panel>
${statementHtml(statement)}
<p>Write your function in the editor below and submit it. The exercise's page in
Scatterbook runs the <strong>public checks</strong> in your browser (it needs WebGPU:
Chrome or Edge, Firefox or Safari with WebGPU); PrairieLearn grades the submission with
the public and the <strong>hidden checks</strong> on its own grader.</p>
<pl-file-editor file-name="${id}.wgsl" ace-mode="ace/mode/rust" source-file-name="starter.wgsl" min-lines="12"></pl-file-editor>
</pl-question-panel>

<pl-submission-panel>
<pl-external-grader-results></pl-external-grader-results>
<pl-file-preview></pl-file-preview>
</pl-submission-panel>
`;
}

function entrypointScript(options: PrairieLearnKitOptions, fallback: string): string {
  return `#!/bin/bash
# PrairieLearn external-grader entrypoint (written by \`npm run grade -- kit prairielearn\`).
# Usage: entrypoint.sh EXERCISE-ID (the question's info.json passes it). Reads
# $GRADE_ROOT/student/*.wgsl (else the _files of $GRADE_ROOT/data/data.json), default
# GRADE_ROOT=/grade; writes $GRADE_ROOT/results/results.json, also when grading fails.
# The grader's sources (hidden checks included) come from the course's serverFilesCourse,
# which students cannot read; the image, which may be public, holds only the installed
# packages ($${NODE_MODULES_ENV}, default ${IMAGE_NODE_MODULES}).
# $${PROJECT_ENV} points at another installed copy of the project (the kit tests use it).
ROOT="\${GRADE_ROOT:-/grade}"
HERE="$(cd "$(dirname "\${BASH_SOURCE[0]}")" && pwd)"
PROJECT="\${${PROJECT_ENV}:-$HERE}"
MODULES="\${${NODE_MODULES_ENV}:-${IMAGE_NODE_MODULES}}"
export GRADE_ROOT="$ROOT"
EXERCISE="\${1:-}"
if [ ! -e "$PROJECT/node_modules" ] && [ -d "$MODULES" ]; then
  # A private copy with the image's packages, so nothing is written into /grade.
  WORK="$(mktemp -d)"
  trap 'rm -rf "$WORK"' EXIT
  cp -R "$PROJECT/." "$WORK/"
  ln -s "$MODULES" "$WORK/node_modules"
  if ! cmp -s "$MODULES/../package-lock.json" "$WORK/package-lock.json"; then
    echo "entrypoint: the image's packages were not built from this kit; rebuild the image" >&2
  fi
  PROJECT="$WORK"
fi
${driverInvocation({
  platform: 'prairielearn',
  exerciseWord: '"$EXERCISE"',
  timeLimitS: options.timeLimitS,
  results: '$ROOT/results/results.json',
  fallback,
})}`;
}

/** The image's Dockerfile; its build context is the kit's root folder. */
function dockerfile(): string {
  return `# PrairieLearn external-grader image for the Scatterbook exercises (written by
# \`npm run grade -- kit prairielearn\`). From the kit's root folder:
#   docker build -f grader-image/Dockerfile -t YOUR-USER/scatterbook-grader:1 .
#   docker push YOUR-USER/scatterbook-grader:1
# The image holds Node.js, SwiftShader and the grader's npm packages, but none of the
# grader's sources: the hidden checks stay in the course's serverFilesCourse, because an
# image on Docker Hub can be pulled by anyone.
FROM node:20-bookworm-slim AS runtime
# Debian's chromium ships SwiftShader, the software Vulkan driver Dawn (the \`webgpu\`
# npm package) uses for WebGPU without a GPU; libvulkan1 is the Vulkan loader.
RUN apt-get update \\
 && apt-get install -y --no-install-recommends chromium libvulkan1 ca-certificates \\
 && rm -rf /var/lib/apt/lists/*
ENV VK_ICD_FILENAMES=/usr/lib/chromium/vk_swiftshader_icd.json
WORKDIR ${IMAGE_PROJECT}
COPY grader-image/package.json grader-image/package-lock.json ./
RUN npm ci --no-audit --no-fund

# A throwaway stage proves the image grades: every exercise's reference scores full
# marks and every known-wrong submission its expected score. Its files (the sources)
# do not reach the final image.
FROM runtime AS self-test
COPY serverFilesCourse/${PROJECT_FOLDER}/ /tmp/${PROJECT_FOLDER}/
RUN ln -s ${IMAGE_NODE_MODULES} /tmp/${PROJECT_FOLDER}/node_modules \\
 && cd /tmp/${PROJECT_FOLDER} \\
 && node --import tsx src/grading/cli.ts --self-test \\
 && echo passed > ${IMAGE_PROJECT}/self-test

FROM runtime
COPY --from=self-test ${IMAGE_PROJECT}/self-test ${IMAGE_PROJECT}/self-test
`;
}

function courseReadme(options: PrairieLearnKitOptions, ids: readonly string[]): string {
  return `# Scatterbook exercises for PrairieLearn

Written by \`npm run grade -- kit prairielearn\`. Steps:

1. Build and push the grader image (needs Docker), from this folder:
   \`docker build -f grader-image/Dockerfile -t ${options.image} . && docker push ${options.image}\`
   (the build runs the grader's self-test). If you pushed under another name, write the
   kit again with \`--image NAME\`. The image holds no hidden checks and may be public.
2. Copy \`questions/scatterbook/\` into your course's \`questions/\` folder and
   \`serverFilesCourse/scatterbook/\` into its \`serverFilesCourse/\` (the grader's sources,
   hidden checks included: students cannot read serverFilesCourse). Add the
   topic "${PL_TOPIC}" to \`infoCourse.json\` (\`"topics": [{"name": "${PL_TOPIC}", "color": "blue1", "description": "Scatterbook WGSL exercises"}]\`).
3. Add the questions to an assessment, e.g. in \`infoAssessment.json\`:
   \`"zones": [{"questions": [${ids.map((id) => `{"id": "scatterbook/${id}", "points": 10}`).join(', ')}]}]\`
4. Sync the course, open a question as a student, submit the starter (it scores low)
   and a correct solution (full marks).

Each question grades within ${options.timeLimitS} s (timeout ${Math.min(PL_MAX_TIMEOUT_S, options.timeLimitS + 30)} s).
Hidden checks show only their name and pass/fail. A grader-side failure is reported as
"not gradable" with the reason and costs the student no attempt.
`;
}

export async function writePrairieLearnKit(options: PrairieLearnKitOptions): Promise<WrittenKit> {
  const timeout = Math.min(PL_MAX_TIMEOUT_S, options.timeLimitS + 30);
  if (options.timeLimitS + 10 > PL_MAX_TIMEOUT_S)
    throw new Error(
      `--time-limit must leave PrairieLearn's ${PL_MAX_TIMEOUT_S} s timeout 10 s of room`,
    );
  const files: KitFile[] = [];
  for (const id of EXERCISE_IDS) {
    const exercise = await loadExercise(id);
    const folder = `questions/scatterbook/${id}`;
    const info = {
      uuid: questionUuid(id),
      title: exercise.title,
      topic: PL_TOPIC,
      tags: ['scatterbook', 'wgsl', exercise.chapter],
      type: 'v3',
      singleVariant: true,
      gradingMethod: 'External',
      externalGradingOptions: {
        enabled: true,
        image: options.image,
        serverFilesCourse: [`${PROJECT_FOLDER}/`],
        entrypoint: `/grade/serverFilesCourse/${PROJECT_FOLDER}/entrypoint.sh ${id}`,
        timeout,
      },
    };
    const statement = readFileSync(join(EXERCISES_DIR, id, 'statement.md'), 'utf8');
    files.push(
      text(`${folder}/info.json`, `${JSON.stringify(info, null, 2)}\n`),
      text(`${folder}/question.html`, questionHtml(id, statement)),
      text(`${folder}/starter.wgsl`, exercise.starter),
    );
  }
  const fallback = lastResortReport('prairielearn', 'unknown', 'Scatterbook exercise');
  const copy = projectCopy();
  const installFiles = copy.files.filter(
    (f) => f.path === 'package.json' || f.path === 'package-lock.json',
  );
  files.push(
    text('grader-image/Dockerfile', dockerfile()),
    ...installFiles.map((f) => ({ path: `grader-image/${f.path}`, data: f.data })),
    text('.dockerignore', 'questions/\n**/node_modules\n'),
    text(
      `serverFilesCourse/${PROJECT_FOLDER}/entrypoint.sh`,
      entrypointScript(options, fallback),
      0o755,
    ),
    ...copy.files.map((f) => ({
      path: `serverFilesCourse/${PROJECT_FOLDER}/${f.path}`,
      data: f.data,
    })),
    text('README.md', courseReadme(options, EXERCISE_IDS)),
  );
  writeTree(options.out, files);
  return { folder: options.out, files: files.map((f) => f.path) };
}
