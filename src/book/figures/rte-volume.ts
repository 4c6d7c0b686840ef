// Figure for the radiative transfer equation (chapter 4, eq:rte): what happens to radiance
// L(x, ω) over a short step ds of a ray through a differential volume. Two processes take
// light out of the beam (absorption, out-scattering: extinction σt = σa + σs) and two add
// light to it (emission and in-scattering from every other direction ω′). Losses are
// drawn in the theme's "bad" colour, gains in its "ok" colour, the beam in ink.
import {
  arrow,
  circle,
  group,
  line,
  math,
  num,
  path,
  polygon,
  rect,
  text,
  type Diagram,
} from './svg.ts';

export interface RteVolumeParameters {
  /** Left and right ends of the volume element along the ray (user units). */
  boxStart: number;
  boxEnd: number;
  /** Directions ω′ (degrees from the ray, measured below it) whose light is in-scattered. */
  inScatterAngles: readonly number[];
  /** Direction (degrees above the ray) of the out-scattered light. */
  outScatterAngle: number;
}

export const RTE_VOLUME: RteVolumeParameters = {
  boxStart: 170,
  boxEnd: 470,
  inScatterAngles: [125, 90, 55],
  outScatterAngle: 62,
};

const WIDTH = 640;
const HEIGHT = 330;
const RAY_Y = 160;
const BOX_TOP = 100;
const BOX_BOTTOM = 220;

/** A wavy line from (x1, y1) to (x2, y2): light turned into heat. */
function squiggle(x1: number, y1: number, x2: number, y2: number, cls: string): string {
  const length = Math.hypot(x2 - x1, y2 - y1);
  const [ux, uy] = [(x2 - x1) / length, (y2 - y1) / length];
  const waves = 4;
  const amplitude = 4;
  const points: string[] = [];
  for (let i = 0; i <= 48; i++) {
    const s = (i / 48) * length;
    const offset = amplitude * Math.sin((i / 48) * waves * 2 * Math.PI);
    points.push(`${num(x1 + ux * s - uy * offset)} ${num(y1 + uy * s + ux * offset)}`);
  }
  return path(`M${points.join('L')}`, `fig-stroke ${cls}`);
}

function star(cx: number, cy: number, outer: number, cls: string): string {
  const points: [number, number][] = [];
  for (let i = 0; i < 10; i++) {
    const radius = i % 2 === 0 ? outer : outer * 0.45;
    const angle = -Math.PI / 2 + (i * Math.PI) / 5;
    points.push([cx + radius * Math.cos(angle), cy + radius * Math.sin(angle)]);
  }
  return polygon(points, cls);
}

export function rteVolume(p: RteVolumeParameters = RTE_VOLUME): Diagram {
  const span = p.boxEnd - p.boxStart;
  const absorbX = p.boxStart + span * 0.16;
  const outX = p.boxStart + span * 0.38;
  const inX = p.boxStart + span * 0.64;
  const emitX = p.boxStart + span * 0.87;
  const rad = Math.PI / 180;

  const outLength = 108;
  const outEnd: [number, number] = [
    outX + outLength * Math.cos(p.outScatterAngle * rad),
    RAY_Y - outLength * Math.sin(p.outScatterAngle * rad),
  ];
  const inArrows = p.inScatterAngles.map((degrees) => {
    const angle = degrees * rad;
    const from: [number, number] = [inX - 96 * Math.cos(angle), RAY_Y + 96 * Math.sin(angle)];
    return arrow(from[0], from[1], inX - 7 * Math.cos(angle), RAY_Y + 7 * Math.sin(angle), {
      cls: 'fig-ok',
    });
  });

  const body = [
    rect(p.boxStart, BOX_TOP, span, BOX_BOTTOM - BOX_TOP, 'fig-medium', 6),
    // The beam: in at the left, out at the right.
    arrow(30, RAY_Y, p.boxStart - 8, RAY_Y, { cls: 'fig-ink fig-thick' }),
    line(p.boxStart, RAY_Y, p.boxEnd, RAY_Y, 'fig-ink fig-thin fig-dash'),
    arrow(p.boxEnd + 8, RAY_Y, WIDTH - 24, RAY_Y, { cls: 'fig-ink fig-thick' }),
    math(86, RAY_Y - 14, 'L(x, ω)'),
    math(WIDTH - 84, RAY_Y - 14, 'L + "d"L'),
    math(p.boxStart - 8, RAY_Y + 24, 's', 'end'),
    math(p.boxEnd + 8, RAY_Y + 24, 's + "d"s', 'start'),
    // Absorption: light becomes heat.
    group('fig-loss', [
      circle(absorbX, RAY_Y, 4, 'fig-solid-warm'),
      squiggle(absorbX, RAY_Y + 6, absorbX - 22, BOX_BOTTOM + 26, 'fig-warm'),
      text(absorbX - 30, BOX_BOTTOM + 50, 'absorption', 'middle'),
      math(absorbX - 30, BOX_BOTTOM + 74, '−σ_a L', 'middle', 'fig-math fig-warm-text'),
    ]),
    // Out-scattering: light leaves the ray's direction.
    group('fig-loss', [
      circle(outX, RAY_Y, 4, 'fig-solid-warm'),
      arrow(outX, RAY_Y, outEnd[0], outEnd[1], { cls: 'fig-warm' }),
      text(outEnd[0] - 8, 22, 'out-scattering', 'end'),
      math(outEnd[0] - 8, 44, '−σ_s L', 'end', 'fig-math fig-warm-text'),
    ]),
    // In-scattering: light from other directions ω′ turned into ω by the phase function.
    group('fig-gain', [
      ...inArrows,
      circle(inX, RAY_Y, 4, 'fig-solid'),
      math(inX + 40, BOX_BOTTOM + 38, 'ω′', 'start', 'fig-math fig-muted-text'),
      text(inX + 10, BOX_BOTTOM + 74, 'in-scattering', 'start'),
      math(inX + 10, BOX_BOTTOM + 98, '+σ_s ∫ p(ω, ω′) L(x, ω′) "d"ω′', 'start', 'fig-math'),
    ]),
    // Emission: the medium glows where it absorbs (Kirchhoff).
    group('fig-gain', [
      star(emitX, RAY_Y - 26, 9, 'fig-solid'),
      arrow(emitX + 10, RAY_Y - 26, emitX + 40, RAY_Y - 26, { cls: 'fig-ok' }),
      text(emitX + 8, 22, 'emission', 'middle'),
      math(emitX + 8, 44, '+σ_a L_e', 'middle', 'fig-math'),
    ]),
  ];

  return {
    width: WIDTH,
    height: HEIGHT,
    title: 'The four terms of the radiative transfer equation in a differential volume',
    description:
      'Radiance L(x, ω) enters a short piece of medium of length ds, from s to s + ds, travelling to ' +
      'the right, and leaves it as L + dL. Inside, four processes change it. Absorption turns some of the ' +
      'light into heat (loss −σa L). Out-scattering sends some of it into other directions (loss −σs L). ' +
      'In-scattering turns light arriving from other directions ω′ into the direction ω (gain ' +
      '+σs ∫ p(ω, ω′) L(x, ω′) dω′). Emission adds light produced in the medium (gain +σa Le). ' +
      'The two losses together are extinction, −σt L.',
    body: body.join(''),
  };
}
