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
};
