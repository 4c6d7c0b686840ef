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
import { DIPOLE_PROFILE } from './dipole-profile/schema.ts';
import { TRANSLUCENT_RENDER } from './translucent-render/schema.ts';
import { INVERSE_RENDER } from './inverse-render/schema.ts';
import { TRANSFER_FUNCTION } from './transfer-function/schema.ts';
import { SINGLE_SCATTER } from './single-scatter/schema.ts';
import { VOLUME_PATH_TRACER } from './volume-path-tracer/schema.ts';
import { PHOTON_MAP } from './photon-map/schema.ts';
import { EXERCISE_WIDGET } from './exercise/schema.ts';

export const WIDGET_CATALOG: Readonly<Record<string, WidgetEntry>> = {
  [BEER_LAW.name]: BEER_LAW,
  [HG_LOBE.name]: HG_LOBE,
  [RAYLEIGH_SKY.name]: RAYLEIGH_SKY,
  [VRE_RAY.name]: VRE_RAY,
  [RAYMARCH_STEPS.name]: RAYMARCH_STEPS,
  [DELTA_TRACKING.name]: DELTA_TRACKING,
  [DIPOLE_PROFILE.name]: DIPOLE_PROFILE,
  [TRANSLUCENT_RENDER.name]: TRANSLUCENT_RENDER,
  [INVERSE_RENDER.name]: INVERSE_RENDER,
  [TRANSFER_FUNCTION.name]: TRANSFER_FUNCTION,
  [SINGLE_SCATTER.name]: SINGLE_SCATTER,
  [VOLUME_PATH_TRACER.name]: VOLUME_PATH_TRACER,
  [PHOTON_MAP.name]: PHOTON_MAP,
  [EXERCISE_WIDGET.name]: EXERCISE_WIDGET,
};
