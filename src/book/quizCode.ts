// What the quiz build (build/quiz.ts) and the quiz script (quiz.ts) must compute
// alike: opaque option ids, the seeded order of the options, and the encoding of
// the feedback. It runs in Node at build time and in the browser, so it uses no
// Node or DOM API beyond TextEncoder/TextDecoder, btoa and atob.

/**
 * cyrb53 (bryc, public domain): a fast 53-bit string hash with good avalanche.
 * Not cryptographic; it only has to spread ids, seeds and keys evenly.
 */
export function hashString(text: string, seed = 0): number {
  let h1 = 0xdeadbeef ^ seed;
  let h2 = 0x41c6ce57 ^ seed;
  for (let i = 0; i < text.length; i++) {
    const code = text.charCodeAt(i);
    h1 = Math.imul(h1 ^ code, 2654435761);
    h2 = Math.imul(h2 ^ code, 1597334677);
  }
  h1 = Math.imul(h1 ^ (h1 >>> 16), 2246822507) ^ Math.imul(h2 ^ (h2 >>> 13), 3266489909);
  h2 = Math.imul(h2 ^ (h2 >>> 16), 2246822507) ^ Math.imul(h1 ^ (h1 >>> 13), 3266489909);
  return 4294967296 * (2097151 & h2) + (h1 >>> 0);
}

/** mulberry32: a 32-bit generator of uniform numbers in [0, 1) from one 32-bit seed. */
export function mulberry32(seed: number): () => number {
  let state = seed >>> 0;
  return () => {
    state = (state + 0x6d2b79f5) >>> 0;
    let t = state;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/**
 * The id of an option: a hash of the quiz's key and the option's text, so that it
 * says nothing about the option's place in the source or whether it is right, and
 * stays the same across builds while the text does (the saved answer survives).
 */
export function optionId(quizKey: string, text: string): string {
  return hashString(`${quizKey}\u0000${text}`).toString(36).padStart(11, '0').slice(-8);
}

/** A seed for a new page load: 6 base-36 characters (2·10⁹ orders, 24 of them distinct for 4 options). */
export function randomSeed(random: () => number = Math.random): string {
  return Math.floor(random() * 36 ** 6)
    .toString(36)
    .padStart(6, '0');
}

/** Seeds that a link may carry: short, lower-case base 36 (anything else is ignored). */
export const SEED_PATTERN = /^[0-9a-z]{1,12}$/;

/**
 * The order in which a quiz shows its options for `seed`: a Fisher–Yates shuffle
 * driven by mulberry32(hash(seed, quiz)). It starts from the ids sorted, not from the
 * order of the page, so the result depends only on the seed, the quiz and its set of
 * options: the same link gives the same order to everyone, whatever order the
 * build wrote and whatever order the author listed them in.
 */
export function shuffledIds(ids: readonly string[], seed: string, quizKey: string): string[] {
  const order = [...ids].sort();
  const random = mulberry32(hashString(`${seed}|${quizKey}`));
  for (let i = order.length - 1; i > 0; i--) {
    const j = Math.floor(random() * (i + 1));
    const a = order[i] as string;
    order[i] = order[j] as string;
    order[j] = a;
  }
  return order;
}

/*
 * Why the feedback is encoded, and how far that goes. Before a student answers, the
 * page must not tell which option is right: not in an attribute (`data-correct`),
 * not by the order, not by an explanation sitting in the DOM. Without a server the
 * page has to carry the answer somehow, so it carries it encoded: each option has a
 * blob, its feedback as JSON ({"c":1} for the right one, {"c":0,"h":"why wrong"} for
 * the others), deflated, XORed with a keystream seeded by the quiz key and the
 * option's id, in base 64, all blobs of a quiz padded to the same length. The
 * explanation of the right answer is a separate blob, keyed by the right option's
 * id. The inspector and view-source show only equal-looking base-64 strings, and no
 * CSS selector or one-line query finds the answer; decoding needs this module's
 * code. That is obfuscation, not security: a student who reads the script can
 * decode every blob, which is the stated bar (a quiz for learning, not an exam).
 * Readers without JavaScript get the answers, folded, on the answer-key page.
 */

function keystream(key: string, length: number): Uint8Array {
  const random = mulberry32(hashString(key, 0x5eed));
  const bytes = new Uint8Array(length);
  for (let i = 0; i < length; i++) bytes[i] = Math.floor(random() * 256);
  return bytes;
}

function toBase64(bytes: Uint8Array): string {
  let binary = '';
  for (const byte of bytes) binary += String.fromCharCode(byte);
  return btoa(binary);
}

function fromBase64(text: string): Uint8Array {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

/** The key of an option's blob (and of the explanation blob, with the right option's id). */
export function blobKey(quizKey: string, id: string, purpose: 'option' | 'explanation'): string {
  return `${purpose}|${quizKey}|${id}`;
}

/**
 * Seals bytes (the build passes deflated UTF-8): a 4-byte big-endian length, the
 * bytes, zeros up to `padTo` bytes of payload (so that the blobs of a quiz cannot be
 * told apart by length), all XORed with the keystream of `key`, in base 64.
 */
export function sealBytes(payload: Uint8Array, key: string, padTo = 0): string {
  const bytes = new Uint8Array(4 + Math.max(payload.length, padTo));
  new DataView(bytes.buffer).setUint32(0, payload.length);
  bytes.set(payload, 4);
  const stream = keystream(key, bytes.length);
  for (let i = 0; i < bytes.length; i++) bytes[i] = (bytes[i] as number) ^ (stream[i] as number);
  return toBase64(bytes);
}

/** The bytes sealed by sealBytes(), or an error if the blob or the key is wrong. */
export function unsealBytes(blob: string, key: string): Uint8Array {
  const bytes = fromBase64(blob);
  const stream = keystream(key, bytes.length);
  for (let i = 0; i < bytes.length; i++) bytes[i] = (bytes[i] as number) ^ (stream[i] as number);
  if (bytes.length < 4) throw new Error('quiz blob too short');
  const length = new DataView(bytes.buffer).getUint32(0);
  if (length > bytes.length - 4) throw new Error('quiz blob does not match its key');
  return bytes.subarray(4, 4 + length);
}

/**
 * Inflates raw-deflate bytes to text with the platform's DecompressionStream (every
 * current browser, and Node 18+). The build deflates the feedback because KaTeX's
 * markup is long and an XORed blob no longer compresses on the wire.
 */
export async function inflateText(bytes: Uint8Array): Promise<string> {
  const copy = new Uint8Array(bytes.length);
  copy.set(bytes);
  const stream = new Blob([copy]).stream().pipeThrough(new DecompressionStream('deflate-raw'));
  return await new Response(stream).text();
}

/** Decodes a blob written by the build (build/quiz.ts: sealText). */
export async function openBlob(blob: string, key: string): Promise<string> {
  return await inflateText(unsealBytes(blob, key));
}

/** What an option's blob holds once decoded. */
export interface OptionFeedback {
  /** 1 for the right option. */
  c: 0 | 1;
  /** For a wrong option: why it is wrong (HTML). */
  h?: string;
}
