// The registry of widgets, as data (no DOM): the chapter build checks widget tags
// against it, the tests iterate over it, and the element loader maps each name
// to its module. One entry per folder in src/widgets/.
import type { WidgetEntry } from './parameters.ts';
import { BEER_LAW } from './beer-law/schema.ts';
import { HG_LOBE } from './hg-lobe/schema.ts';
import { RAYLEIGH_SKY } from './rayleigh-sky/schema.ts';
import { VRE_RAY } from './vre-ray/schema.ts';
import { RAYMARCH_STEPS } from './raymarch-steps/schema.ts';
import { DELTA_TRACKING } from './delta-tracking/schema.ts';

export const WIDGET_CATALOG: Readonly<Record<string, WidgetEntry>> = {
  [BEER_LAW.name]: BEER_LAW,
  [HG_LOBE.name]: HG_LOBE,
  [RAYLEIGH_SKY.name]: RAYLEIGH_SKY,
  [VRE_RAY.name]: VRE_RAY,
  [RAYMARCH_STEPS.name]: RAYMARCH_STEPS,
  [DELTA_TRACKING.name]: DELTA_TRACKING,
};
