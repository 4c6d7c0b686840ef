import { writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { loadShaderLibrary } from '../src/gpu/shaderSourcesNode.ts';
import { linkSceneKernel } from '../src/scene/gpuRenderer.ts';
import { parseSceneText } from '../src/scene/loadNode.ts';
import { plan } from '../src/scene/plan.ts';
import { peerScenes } from './peers.ts';
const lib = loadShaderLibrary(fileURLToPath(new URL('../shaders', import.meta.url)));
let i = 0;
for (const { name, json } of peerScenes(64)) {
  const scene = parseSceneText(JSON.stringify(json));
  const p = plan(scene as never);
  const code = await linkSceneKernel(lib as never, p.conditions);
  writeFileSync(`/tmp/k${i}.wgsl`, code);
  const on = Object.entries(p.conditions).filter(([, v]) => v).map(([k]) => k);
  console.log(i++, name, code.length, code.split('\n').length, on.join(','));
}
