// The "Material" choice of the subsurface widgets (chapters 11 and 12): one of the measured
// materials of Jensen et al. 2001, labelled with its relative index of refraction.
import { JENSEN_2001_MATERIALS } from '../../subsurface/materials.ts';
import type { ChoiceParameter } from '../parameters.ts';

/** A `material` parameter over Jensen et al.'s table, Skin 1 by default; `description` says what the widget does with it. */
export function measuredMaterialParameter(description: string): ChoiceParameter {
  return {
    kind: 'choice',
    name: 'material',
    label: 'Material',
    choices: JENSEN_2001_MATERIALS.map((m) => ({
      value: m.name,
      label: `${m.label} (η = ${m.eta})`,
    })),
    default: 'skin1',
    description,
  };
}
