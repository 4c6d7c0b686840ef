// Scenes from disk in Node (command line, tests, benchmarks): the JSON file, validated,
// and grid files read from the project's public/ folder. Never imported by browser code.
import { readFile } from 'node:fs/promises';
import { fileURLToPath } from 'node:url';
import { resolveScene, type ResolvedScene } from './load.ts';
import { SceneValidationError, parseScene } from './validate.ts';

export const PUBLIC_DIRECTORY = fileURLToPath(new URL('../../public/', import.meta.url));

/** Reads files under public/ (the validator has already refused ".." and absolute paths). */
export async function nodeFileReader(path: string): Promise<Uint8Array> {
  return new Uint8Array(await readFile(new URL(path, `file://${PUBLIC_DIRECTORY}`)));
}

/** Parses JSON text as a scene; syntax errors become validation errors. */
export function parseSceneText(text: string): ReturnType<typeof parseScene> {
  let json: unknown;
  try {
    json = JSON.parse(text);
  } catch (error) {
    throw new SceneValidationError([`scene: not valid JSON (${(error as Error).message})`]);
  }
  return parseScene(json);
}

/** Reads, validates and resolves a scene file. */
export async function loadSceneFile(path: string): Promise<ResolvedScene> {
  const text = await readFile(path, 'utf8');
  return resolveScene(parseSceneText(text), nodeFileReader);
}
