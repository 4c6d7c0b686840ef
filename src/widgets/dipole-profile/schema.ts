// Parameters of <sb-dipole-profile> (chapter 11): the diffuse reflectance profile R_d(r)
// of a translucent material per RGB channel, from the classic dipole, the better dipole
// and the Christensen–Burley fit, against a Monte Carlo reference with error bars; the
// totals of each, the Monte Carlo's cost next to its error, and a disc of the material
// lit by a thin beam. Units: 1/mm and mm, as the Jensen et al. 2001 table.
import type { NumberParameter, WidgetEntry } from '../parameters.ts';
import { JENSEN_2001_MATERIALS, findMaterial } from '../../subsurface/materials.ts';

const CHANNELS = [
  ['r', 'red'],
  ['g', 'green'],
  ['b', 'blue'],
] as const;

const skin = findMaterial('skin1')!;

const sigmaSPrime: NumberParameter[] = CHANNELS.map(([key, name], c) => ({
  kind: 'number',
  name: `sigma-s-${key}`,
  label: `σs′ ${name}`,
  symbol: `σs′(${key.toUpperCase()})`,
  unit: '1/mm',
  min: 0.01,
  max: 25,
  step: 0.01,
  default: skin.sigmaSPrime[c]!,
  description: `Reduced scattering coefficient σs′ = σs(1 − g) of the ${name} channel. Setting it by hand switches the material to “Set by hand”.`,
}));

const sigmaA: NumberParameter[] = CHANNELS.map(([key, name], c) => ({
  kind: 'number',
  name: `sigma-a-${key}`,
  label: `σa ${name}`,
  symbol: `σa(${key.toUpperCase()})`,
  unit: '1/mm',
  min: 0,
  max: 2,
  step: 0.0001,
  default: skin.sigmaA[c]!,
  description: `Absorption coefficient σa of the ${name} channel. Setting it by hand switches the material to “Set by hand”.`,
}));

export const DIPOLE_PROFILE: WidgetEntry = {
  name: 'dipole-profile',
  title: 'The dipole and its profiles: Rd(r) against Monte Carlo',
  description:
    'The diffuse reflectance profile Rd(r) of a measured material (Jensen et al. 2001) or of coefficients set by hand, per RGB channel on log–log axes: the classic dipole, the better dipole and the Christensen–Burley fit, against a GPU Monte Carlo simulation of the same half-space with error bars; the total Rd of each, the Monte Carlo cost next to its error, and a disc of the material lit by a thin beam, showing the colour bleeding.',
  parameters: [
    {
      kind: 'choice',
      name: 'material',
      label: 'Material',
      choices: [
        ...JENSEN_2001_MATERIALS.map((m) => ({
          value: m.name,
          label: `${m.label} (η = ${m.eta})`,
        })),
        { value: 'manual', label: 'Set by hand' },
      ],
      default: 'skin1',
      description:
        'A measured material of Jensen et al. 2001 (σs′ and σa per channel in 1/mm), or the coefficients below set by hand.',
    },
    {
      kind: 'number',
      name: 'eta',
      label: 'Relative index η',
      symbol: 'η',
      unit: '',
      min: 1,
      max: 2,
      step: 0.01,
      default: skin.eta,
      description:
        'Index of refraction of the material relative to air; sets the Fresnel boundary of the diffusion models and of the Monte Carlo.',
    },
    {
      kind: 'number',
      name: 'g',
      label: 'Monte Carlo anisotropy g',
      symbol: 'g',
      unit: '',
      min: 0,
      max: 0.9,
      step: 0.05,
      default: 0,
      description:
        'Henyey–Greenstein g of the Monte Carlo, which scatters with σs = σs′/(1 − g); the diffusion models see only σs′ and do not change.',
    },
    ...sigmaSPrime,
    ...sigmaA,
    {
      kind: 'number',
      name: 'photons',
      label: 'Monte Carlo target: photons per channel (log₂)',
      symbol: 'log₂ N',
      unit: '',
      min: 12,
      max: 22,
      step: 1,
      default: 16,
      description:
        'How many photon packets per channel “More photons” runs up to, in doublings (16 is 65 536).',
    },
    {
      kind: 'number',
      name: 'exposure',
      label: 'Disc exposure',
      symbol: 'EV',
      unit: 'EV',
      min: -6,
      max: 6,
      step: 0.5,
      default: 0,
      description:
        'Brightness of the lit disc in stops; the tone curve keeps the ratio of the channels.',
    },
    {
      kind: 'number',
      name: 'view',
      label: 'Disc radius shown',
      symbol: 'R',
      unit: 'mm',
      min: 1,
      max: 50,
      step: 1,
      default: 10,
      description: 'Half the width of the disc picture.',
    },
    {
      kind: 'number',
      name: 'seed',
      label: 'Seed',
      symbol: 'seed',
      unit: '',
      min: 0,
      max: 1000000,
      step: 1,
      default: 0,
      description: 'Seed of the Monte Carlo’s random streams.',
    },
  ],
};
