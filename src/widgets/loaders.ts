// Maps each widget in the catalog to the module that defines its element, so a
// page loads only the widgets it embeds.
export const WIDGET_LOADERS: Readonly<Record<string, () => Promise<{ define: () => void }>>> = {
  'beer-law': async () => {
    const module = await import('./beer-law/element.ts');
    return { define: module.defineBeerLaw };
  },
  'hg-lobe': async () => {
    const module = await import('./hg-lobe/element.ts');
    return { define: module.defineHgLobe };
  },
  'rayleigh-sky': async () => {
    const module = await import('./rayleigh-sky/element.ts');
    return { define: module.defineRayleighSky };
  },
  'vre-ray': async () => {
    const module = await import('./vre-ray/element.ts');
    return { define: module.defineVreRay };
  },
  'raymarch-steps': async () => {
    const module = await import('./raymarch-steps/element.ts');
    return { define: module.defineRaymarchSteps };
  },
  'delta-tracking': async () => {
    const module = await import('./delta-tracking/element.ts');
    return { define: module.defineDeltaTracking };
  },
  'dipole-profile': async () => {
    const module = await import('./dipole-profile/element.ts');
    return { define: module.defineDipoleProfile };
  },
  'translucent-render': async () => {
    const module = await import('./translucent-render/element.ts');
    return { define: module.defineTranslucentRender };
  },
  'inverse-render': async () => {
    const module = await import('./inverse-render/element.ts');
    return { define: module.defineInverseRender };
  },
  'transfer-function': async () => {
    const module = await import('./transfer-function/element.ts');
    return { define: module.defineTransferFunction };
  },
  'single-scatter': async () => {
    const module = await import('./single-scatter/element.ts');
    return { define: module.defineSingleScatter };
  },
  'volume-path-tracer': async () => {
    const module = await import('./volume-path-tracer/element.ts');
    return { define: module.defineVolumePathTracer };
  },
  'photon-map': async () => {
    const module = await import('./photon-map/element.ts');
    return { define: module.definePhotonMap };
  },
  exercise: async () => {
    const module = await import('./exercise/element.ts');
    return { define: module.defineExercise };
  },
};
