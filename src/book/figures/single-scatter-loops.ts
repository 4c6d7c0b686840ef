// Figure for single scattering by two nested ray marchers (chapter 9, eq:nested-loops):
// the outer loop steps along the view ray from the camera in N steps of Δt; at every step
// an inner loop marches a shadow ray towards the light in M steps of Δs. One step i is
// highlighted with its shadow ray and inner samples; the shadow rays of the other steps
// are drawn faintly. Step positions are midpoints t_i = (i + ½)Δt, as in Listing 9.1.
import {
  arrow,
  circle,
  dimension,
  group,
  line,
  math,
  polygon,
  rect,
  text,
  type Diagram,
} from './svg.ts';

export interface SingleScatterLoopsParameters {
  /** View-ray steps N across the medium. */
  viewSteps: number;
  /** Shadow-ray steps M inside the medium. */
  shadowSteps: number;
  /** The highlighted outer step i (0-based). */
  highlighted: number;
}

export const SINGLE_SCATTER_LOOPS: SingleScatterLoopsParameters = {
  viewSteps: 8,
  shadowSteps: 5,
  highlighted: 3,
};

const WIDTH = 640;
const HEIGHT = 320;
const RAY_Y = 236;
const MEDIUM = { left: 120, right: 560, top: 96, bottom: 286 };
const LIGHT = { x: 566, y: 40 };
const CAMERA_X = 52;

/** Where the segment from (x, y) to the light leaves the medium's top edge. */
function exitPoint(x: number, y: number): [number, number] {
  const s = (y - MEDIUM.top) / (y - LIGHT.y);
  return [x + (LIGHT.x - x) * s, MEDIUM.top];
}

export function singleScatterLoops(
  p: SingleScatterLoopsParameters = SINGLE_SCATTER_LOOPS,
): Diagram {
  const dt = (MEDIUM.right - MEDIUM.left) / p.viewSteps;
  const points = Array.from({ length: p.viewSteps }, (_, i) => MEDIUM.left + (i + 0.5) * dt);
  const chosen = points[p.highlighted] ?? points[0] ?? MEDIUM.left;

  const faint = points
    .filter((_, i) => i !== p.highlighted)
    .map((x) => line(x, RAY_Y, LIGHT.x, LIGHT.y, 'fig-muted fig-thin fig-dash'));
  const [ex, ey] = exitPoint(chosen, RAY_Y);
  const inner = Array.from({ length: p.shadowSteps }, (_, j) => {
    const s = (j + 0.5) / p.shadowSteps;
    return circle(chosen + (ex - chosen) * s, RAY_Y + (ey - RAY_Y) * s, 3.2, 'fig-solid-accent');
  });
  const sun: string[] = [circle(LIGHT.x, LIGHT.y, 11, 'fig-hollow')];
  for (let k = 0; k < 8; k++) {
    const a = (k * Math.PI) / 4;
    sun.push(
      line(
        LIGHT.x + 15 * Math.cos(a),
        LIGHT.y + 15 * Math.sin(a),
        LIGHT.x + 21 * Math.cos(a),
        LIGHT.y + 21 * Math.sin(a),
        'fig-ink fig-thin',
      ),
    );
  }
  const camera = [
    rect(CAMERA_X - 34, RAY_Y - 12, 24, 24, 'fig-hollow', 3),
    polygon(
      [
        [CAMERA_X - 10, RAY_Y - 5],
        [CAMERA_X, RAY_Y - 11],
        [CAMERA_X, RAY_Y + 11],
        [CAMERA_X - 10, RAY_Y + 5],
      ],
      'fig-hollow',
    ),
  ];
  const midShadow: [number, number] = [(chosen + ex) / 2, (RAY_Y + ey) / 2];

  const body = [
    rect(
      MEDIUM.left,
      MEDIUM.top,
      MEDIUM.right - MEDIUM.left,
      MEDIUM.bottom - MEDIUM.top,
      'fig-medium',
      14,
    ),
    ...faint,
    group('fig-shadow-ray', [
      line(chosen, RAY_Y, LIGHT.x, LIGHT.y, 'fig-accent fig-thick'),
      ...inner,
    ]),
    arrow(CAMERA_X + 4, RAY_Y, WIDTH - 20, RAY_Y, { cls: 'fig-ink' }),
    ...points.map((x, i) =>
      circle(
        x,
        RAY_Y,
        i === p.highlighted ? 5.5 : 3.6,
        i === p.highlighted ? 'fig-solid-accent' : 'fig-solid',
      ),
    ),
    ...camera,
    group('fig-light', sun),
    text(CAMERA_X - 22, RAY_Y + 36, 'camera', 'middle'),
    text(LIGHT.x - 28, LIGHT.y + 4, 'light', 'end'),
    math(chosen - 6, RAY_Y + 26, 'x(t_i)', 'end'),
    dimension(points[0] ?? 0, RAY_Y + 34, points[1] ?? 0, RAY_Y + 34),
    math(((points[0] ?? 0) + (points[1] ?? 0)) / 2, RAY_Y + 56, 'Δt'),
    math(
      midShadow[0] - 14,
      midShadow[1] - 2,
      'Δs',
      'end',
      'fig-math fig-accent-text fig-halo-medium',
    ),
    math(ex - 12, ey + 22, 'T_ℓ', 'end', 'fig-math fig-accent-text fig-halo-medium'),
    math(
      (MEDIUM.left + chosen) / 2 - 8,
      RAY_Y - 14,
      'T(0, t_i)',
      'middle',
      'fig-math fig-halo-medium',
    ),
    text(
      MEDIUM.right - 10,
      MEDIUM.bottom - 12,
      'outer loop: i = 1 … N',
      'end',
      'fig-text fig-small',
    ),
    text(
      MEDIUM.left + 12,
      MEDIUM.top + 22,
      'inner loop: j = 1 … M on each shadow ray',
      'start',
      'fig-text fig-small',
    ),
  ];

  return {
    width: WIDTH,
    height: HEIGHT,
    title: 'Single scattering by two nested ray marchers',
    description:
      `A view ray leaves the camera on the left and crosses a medium. The outer loop places ` +
      `${p.viewSteps} sample points along it, Δt apart, and accumulates the view transmittance T(0, t_i) ` +
      `from the camera to each. From every sample point a shadow ray runs to a light above and to the ` +
      `right. For the highlighted point x(t_i) the inner loop marches that shadow ray in ` +
      `${p.shadowSteps} steps of length Δs up to the edge of the medium, giving the shadow ` +
      `transmittance T_ℓ. The cost is N view steps plus N·M shadow steps per light.`,
    body: body.join(''),
  };
}
