// The deck's equation slides: the book's key equations between the widget slides
// that show them at work. Each equation is the chapter's own (by its \label), laid
// out in lines that fit a 1280×720 slide; tests/book/deckSlides.test.ts holds every
// slide's TeX against the chapter's, up to line breaks, spacing, bracket sizes and
// \underbrace annotations (equationLayoutFree), so a slide cannot drift from the book.

/** A widget slide is named `<widget>/<slide title>`, an equation slide `equation/<title>`. */
export type SlideKey = string;

export interface SlideEquation {
  /** The chapter's label, e.g. `eq:rte`: the slide shows its number and links to it. */
  label: string;
  /** The chapter's TeX, broken into lines (aligned/gathered) to fit the slide. */
  tex: string;
}

export interface EquationSlideSpec {
  title: string;
  /** Chapter slug; the slide links to `section` in it. */
  chapter: string;
  /** The heading (as written in the chapter) of the section that derives the equations. */
  section: string;
  /** The widget slide this slide comes before (several before one keep this order). */
  before: SlideKey;
  equations: readonly SlideEquation[];
  /** One or two sentences, inline Markdown with $math$: what the symbols are. */
  caption: string;
}

export const EQUATION_SLIDES: readonly EquationSlideSpec[] = [
  {
    title: 'Optical thickness and transmittance',
    chapter: '02-extinction-and-transmittance',
    section: 'Optical thickness and transmittance',
    before: "beer-law/Beer's law",
    equations: [
      {
        label: 'eq:optical-thickness',
        tex: String.raw`\tau(a,b) = \int_a^b \sigma_t(s)\,\mathrm{d}s`,
      },
      {
        label: 'eq:transmittance',
        tex: String.raw`T(a \to b) = \frac{L(b)}{L(a)} = e^{-\tau(a,b)}`,
      },
      { label: 'eq:beer', tex: String.raw`T(d) = e^{-\sigma_t d}` },
    ],
    caption:
      'Extinction $\\sigma_t = \\sigma_a + \\sigma_s$ per metre; $\\tau$ counts mean free paths. ' +
      "Beer's law is the constant-$\\sigma_t$ case.",
  },
  {
    title: 'The Henyey–Greenstein phase function',
    chapter: '03-phase-functions-and-in-scattering',
    section: 'One parameter for the asymmetry',
    before: 'hg-lobe/Back scattering: g = −0.3',
    equations: [
      {
        label: 'eq:henyey-greenstein',
        tex: String.raw`p_{HG}(\mu; g) = \frac{1}{4\pi}\,\frac{1 - g^2}{\left(1 + g^2 - 2g\mu\right)^{3/2}}, \qquad -1 < g < 1`,
      },
      {
        label: 'eq:hg-mean-cosine',
        tex: String.raw`\langle\mu\rangle = 2\pi\int_{-1}^{1} \mu\, p_{HG}(\mu; g)\, \mathrm{d}\mu = g`,
      },
    ],
    caption:
      '$\\mu = \\cos\\theta$ between the old and the new direction; $p$ is a density per steradian ' +
      'and integrates to one over the sphere.',
  },
  {
    title: 'The radiative transfer equation',
    chapter: '04-the-volume-rendering-equation',
    section: 'The radiative transfer equation',
    before: 'vre-ray/The volume rendering equation',
    equations: [
      {
        label: 'eq:rte',
        tex: String.raw`\begin{aligned}
\frac{\mathrm{d}L}{\mathrm{d}s}(x, \omega) = {}& \underbrace{-\sigma_t(x)\, L(x, \omega)}_{\text{extinction}} + \underbrace{\sigma_a(x)\, L_e(x, \omega)}_{\text{emission}} \\
&+ \underbrace{\sigma_s(x) \int_{S^2} p(\omega, \omega')\, L(x, \omega')\, \mathrm{d}\omega'}_{\text{in-scattering}}
\end{aligned}`,
      },
    ],
    caption:
      'One loss and two gains per metre of travel, $s$ along the direction of light. ' +
      'The unknown $L$ is both differentiated and integrated over the sphere.',
  },
  {
    title: 'The volume rendering equation',
    chapter: '04-the-volume-rendering-equation',
    section: 'The integral form',
    before: 'vre-ray/The volume rendering equation',
    equations: [
      {
        label: 'eq:vre',
        tex: String.raw`\begin{aligned}
L(x, \omega) = {}& \int_0^d T(x \to x_t) \Bigl[ \sigma_a(x_t)\, L_e(x_t, \omega) + \sigma_s(x_t)\, L_s(x_t, \omega) \Bigr] \mathrm{d}t \\
&+ \underbrace{T(x \to x_d)\, L(x_d, \omega)}_{\text{surface term}}
\end{aligned}`,
      },
    ],
    caption:
      'The RTE integrated along the ray, $x_t = x - t\\,\\omega$: what each point adds, times the ' +
      'transmittance to the eye, plus the surface behind the medium at $t = d$.',
  },
  {
    title: 'Delta tracking',
    chapter: '06-unbiased-transmittance',
    section: 'Delta tracking',
    before: 'delta-tracking/Delta tracking: unbiased, binary transmittance',
    equations: [
      {
        label: 'eq:null-collision',
        tex: String.raw`\sigma_n(s) = \bar\sigma - \sigma_t(s) \;\ge\; 0`,
      },
      {
        label: 'eq:delta-estimator',
        tex: String.raw`\begin{gathered}
\hat T_{\mathrm{delta}} = \begin{cases} 1 & \text{no real collision in } [0, d], \\ 0 & \text{otherwise,} \end{cases} \\
\mathbb{E}[\hat T_{\mathrm{delta}}] = T, \quad \operatorname{Var}[\hat T_{\mathrm{delta}}] = T(1 - T)
\end{gathered}`,
      },
    ],
    caption:
      'Tentative collisions at rate $\\bar\\sigma$; each is real with probability $\\sigma_t/\\bar\\sigma$. ' +
      'The variance does not depend on the majorant.',
  },
  {
    title: 'Ratio tracking',
    chapter: '06-unbiased-transmittance',
    section: 'Ratio tracking',
    before: 'delta-tracking/Five estimators at equal samples and equal time',
    equations: [
      {
        label: 'eq:ratio-tracking',
        tex: String.raw`\hat T_{\mathrm{ratio}} = \prod_{i} \Big(1 - \frac{\sigma_t(x_i)}{\bar\sigma}\Big)`,
      },
      {
        label: 'eq:ratio-variance',
        tex: String.raw`\operatorname{Var}[\hat T_{\mathrm{ratio}}] = T^2\Big(\exp\!\Big(\int_0^d \frac{\sigma_t(s)^2}{\bar\sigma}\,\mathrm{d}s\Big) - 1\Big)`,
      },
    ],
    caption:
      'The product runs over every tentative collision $x_i$ in $[0, d]$; unbiased for any ' +
      '$\\bar\\sigma > 0$, and less noisy than delta tracking where $\\sigma_t < \\bar\\sigma$.',
  },
  {
    title: 'Single scattering with shadow rays',
    chapter: '09-single-scattering',
    section: 'Shadow rays and the two nested loops',
    before: 'single-scatter/Single scattering: a shaft of shadow in the fog',
    equations: [
      {
        label: 'eq:ss-estimator',
        tex: String.raw`\begin{aligned}
\hat L = {}& \frac{T(0, t)\,\sigma_s(x_t)}{q(t)} \sum_\ell p\,E_\ell\,V_\ell\,\underbrace{\hat T_\ell(x_t)}_{\text{shadow ray}} \\
&+ T(0, D)\,L_D
\end{aligned}`,
      },
    ],
    caption:
      'One distance $t$ drawn with density $q(t)$, one shadow ray per light $\\ell$ with an ' +
      'unbiased transmittance estimate: error $\\propto \\mathrm{spp}^{-1/2}$.',
  },
  {
    title: 'The dipole (Jensen et al. 2001)',
    chapter: '11-subsurface-scattering',
    section: 'The dipole',
    before: 'dipole-profile/Skin: the dipole against Monte Carlo',
    equations: [
      {
        label: 'eq:dipole-sources',
        tex: String.raw`z_v = z_r + 4AD = z_r\Big(1 + \frac{4A}{3}\Big)`,
      },
      {
        label: 'eq:dipole-profile',
        tex: String.raw`\begin{aligned}
R_d(r) = \frac{\alpha'}{4\pi}\Biggl[ & \underbrace{\frac{z_r\,(1 + \sigma_{tr}d_r)\,e^{-\sigma_{tr}d_r}}{d_r^3}}_{\text{real source}} \\
& + \underbrace{\frac{z_v\,(1 + \sigma_{tr}d_v)\,e^{-\sigma_{tr}d_v}}{d_v^3}}_{\text{virtual source}} \Biggr]
\end{aligned}`,
      },
    ],
    caption:
      "Real source at depth $z_r = 1/\\sigma_t'$, its mirror image above the extrapolated boundary; " +
      '$d_{r,v} = \\sqrt{r^2 + z_{r,v}^2}$, $A = (1 + F_{dr})/(1 - F_{dr})$.',
  },
];

/**
 * The TeX of an equation with its layout taken out: line breaks and alignment
 * (aligned, gathered, `&`, `\\` with or without `[0.4em]`), spacing commands, bracket sizes (`\left`, `\Big`…),
 * `{}` and \underbrace annotations. Two forms of one equation that differ only in how
 * they are laid out give the same string.
 */
export function equationLayoutFree(tex: string): string {
  let text = tex.replace(/\\label\{[^}]*\}/g, '');
  // \underbrace{X}_{note} → X
  for (;;) {
    const start = text.indexOf('\\underbrace{');
    if (start < 0) break;
    const bodyStart = start + '\\underbrace'.length;
    const bodyEnd = closingBrace(text, bodyStart);
    let end = bodyEnd + 1;
    const rest = text.slice(end).match(/^\s*_\s*\{/);
    if (rest) end = closingBrace(text, end + rest[0].length - 1) + 1;
    text = text.slice(0, start) + text.slice(bodyStart + 1, bodyEnd) + text.slice(end);
  }
  return text
    .replace(/\\(?:begin|end)\{(?:aligned|gathered|split)\}/g, '')
    .replace(/\\(?:left|right)\s*\./g, '')
    .replace(/\\(?:left|right|[Bb]igg?[lrm]?)(?![A-Za-z])/g, '')
    .replace(/\\\\(?:\[[^\]]*\])?|&/g, '')
    .replace(/\\(?:[,;:!]|q?quad(?![A-Za-z]))/g, '')
    .replace(/\{\}/g, '')
    .replace(/\s+/g, '');
}

/** Index of the `}` that closes the `{` at `open`. */
function closingBrace(text: string, open: number): number {
  let depth = 0;
  for (let i = open; i < text.length; i++) {
    if (text[i] === '\\') i += 1;
    else if (text[i] === '{') depth += 1;
    else if (text[i] === '}' && --depth === 0) return i;
  }
  throw new Error(`unbalanced braces in "${text}"`);
}
