// `npm run grade -- kit …`: writes a deployment kit for a course platform.
//   grade kit gradescope --exercise ID --out DIR [--time-limit S] [--node-version X.Y.Z]
//   grade kit prairielearn --out DIR [--time-limit S] [--image NAME]
// Returns the exit status: 0 written, 2 usage error (message on stderr).
import { existsSync, mkdirSync, readdirSync } from 'node:fs';
import { resolve } from 'node:path';
import { parseArgs } from 'node:util';
import { EXERCISE_IDS } from '../../../exercises/index.ts';
import { DEFAULT_TIME_LIMIT_S } from './driver.ts';
import { writeGradescopeKit } from './gradescope.ts';
import { writePrairieLearnKit } from './prairielearn.ts';

export const KIT_USAGE = `usage:
  grade kit gradescope --exercise ID --out DIR [--time-limit S] [--node-version X.Y.Z]
  grade kit prairielearn --out DIR [--time-limit S] [--image NAME]
--time-limit: wall-clock seconds per submission (default ${DEFAULT_TIME_LIMIT_S}).
exercises: ${EXERCISE_IDS.join(', ')}`;

/** Image name the PrairieLearn questions use unless --image says otherwise. */
export const DEFAULT_IMAGE = 'scatterbook-grader:1';

class KitUsageError extends Error {}

function nodeVersion(requested: string | undefined): string {
  if (requested !== undefined) {
    if (!/^\d+\.\d+\.\d+$/.test(requested) || Number(requested.split('.')[0]) < 20)
      throw new KitUsageError('--node-version must be X.Y.Z with X ≥ 20');
    return requested;
  }
  // The version that wrote (and, in the tests, ran) the kit, when it is new enough.
  const own = process.versions.node;
  return Number(own.split('.')[0]) >= 20 ? own : '20.20.2';
}

async function run(argv: string[]): Promise<number> {
  const platform = argv[0];
  let values;
  try {
    ({ values } = parseArgs({
      args: argv.slice(1),
      options: {
        exercise: { type: 'string' },
        out: { type: 'string' },
        'time-limit': { type: 'string' },
        'node-version': { type: 'string' },
        image: { type: 'string' },
      },
      strict: true,
      allowPositionals: false,
    }));
  } catch (error) {
    throw new KitUsageError((error as Error).message);
  }
  if (platform !== 'gradescope' && platform !== 'prairielearn')
    throw new KitUsageError('the kit is "gradescope" or "prairielearn"');
  if (!values.out) throw new KitUsageError('--out DIR is required');
  const out = resolve(values.out);
  if (existsSync(out) && readdirSync(out).length > 0)
    throw new KitUsageError(`--out ${values.out} exists and is not empty`);
  let timeLimitS = DEFAULT_TIME_LIMIT_S;
  if (values['time-limit'] !== undefined) {
    timeLimitS = /^\d+$/.test(values['time-limit']) ? Number(values['time-limit']) : Number.NaN;
    if (!(timeLimitS >= 5 && timeLimitS <= 540))
      throw new KitUsageError('--time-limit must be whole seconds in [5, 540]');
  }
  if (platform === 'gradescope') {
    if (values.image) throw new KitUsageError('--image is for the prairielearn kit');
    if (!values.exercise) throw new KitUsageError('--exercise ID is required');
    if (!EXERCISE_IDS.includes(values.exercise))
      throw new KitUsageError(`unknown exercise "${values.exercise}"`);
    mkdirSync(out, { recursive: true });
    const kit = await writeGradescopeKit({
      exercise: values.exercise,
      out,
      timeLimitS,
      nodeVersion: nodeVersion(values['node-version']),
    });
    process.stderr.write(
      `Gradescope autograder for ${values.exercise}: ${kit.folder} (${kit.files.length} files)\n` +
        `upload ${kit.zip} (see ${kit.folder}/README.txt)\n`,
    );
    return 0;
  }
  if (values.exercise)
    throw new KitUsageError('the prairielearn kit holds every exercise; drop --exercise');
  if (values['node-version']) throw new KitUsageError('--node-version is for the gradescope kit');
  const image = values.image ?? DEFAULT_IMAGE;
  if (!/^[a-z0-9][a-z0-9._\-/:@]*$/.test(image))
    throw new KitUsageError('--image must be a Docker image name, e.g. user/scatterbook-grader:1');
  mkdirSync(out, { recursive: true });
  const kit = await writePrairieLearnKit({ out, timeLimitS, image });
  process.stderr.write(
    `PrairieLearn course folder: ${kit.folder} (${EXERCISE_IDS.length} questions, image ${image})\n` +
      `follow ${kit.folder}/README.md` +
      (values.image
        ? '\n'
        : `; pass --image YOUR-USER/NAME:TAG for an image PrairieLearn can pull\n`),
  );
  return 0;
}

/** The `kit` subcommand of the grade command line. */
export async function runKit(argv: string[]): Promise<number> {
  if (argv.includes('--help')) {
    process.stdout.write(`${KIT_USAGE}\n`);
    return 0;
  }
  try {
    return await run(argv);
  } catch (error) {
    if (error instanceof KitUsageError) {
      process.stderr.write(`grade kit: ${error.message}\n${KIT_USAGE}\n`);
      return 2;
    }
    throw error;
  }
}
