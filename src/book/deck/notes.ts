// Speaker notes for every deck slide: what to say, what to click, which number to
// point at. Keyed by slide (`<widget>/<slide title>` for a widget slide, as in its
// src/widgets/<name>/widget.ts, and `equation/<title>` for an equation slide of
// equationSlides.ts); tests/book/deckSlides.test.ts fails when a slide has no notes or
// a note names no slide, so renaming a slide means renaming its notes here.
// Inline Markdown with $math$, typeset at build time like the chapters.
import type { SlideKey } from './equationSlides.ts';

export const SPEAKER_NOTES: Readonly<Record<SlideKey, string>> = {
  // ---- Chapter 2 -------------------------------------------------------------
  'equation/Optical thickness and transmittance':
    'Everything in the lecture starts here. Say: $\\sigma_t$ is a probability of collision per metre, ' +
    '$\\tau$ counts mean free paths, and the transmittance depends on the medium only through $\\tau$. ' +
    'Point at the exponent: a segment twice as thick in $\\tau$ lets through the square of the light.',
  "beer-law/Beer's law":
    'Homogeneous slab, $\\sigma_t = 0.2 + 0.8 = 1$ per metre, $d = 2$ m. Point at ' +
    '“T(0→d), float64 reference”: 0.135335 $= e^{-2}$, and at the GPU value next to it (relative ' +
    'difference ~$10^{-7}$, float32). Drag the thickness slider and watch the curve T(s) stay an exponential.',
  'beer-law/Fog and smoke':
    'Now $\\sigma_a = 1.2$, $\\sigma_s = 0.8$: the same $\\sigma_t = 2$ whichever way you split it. ' +
    'Point at τ = 4 and T = 0.0183 $= e^{-4}$. Ask the room: does it matter for T whether the light ' +
    'is absorbed or scattered away? (No; it matters for where the light goes, chapter 3.) Keys 1 and 2 switch thin fog and smoke.',
  'beer-law/The multiplicative property':
    'Layered profile. Point at the row “T(0→s₀) · T(s₀→d)”: the two factors multiply to T(0→d) exactly, ' +
    'and the check row says so. Drag the split point s₀ across the layers: the factors change, the ' +
    'product does not. This is why a ray marcher may multiply step transmittances front to back.',
  'beer-law/Optically thick media':
    'τ = 100: $e^{-100} \\approx 3.7\\times10^{-44}$, below the smallest normal float32. Point at ' +
    '“T(0→d), this backend”: subnormal, then exactly 0 deeper in, never negative, never NaN. Say why it ' +
    'matters: a linearised update would go negative here (chapter 5).',

  // ---- Chapter 3 -------------------------------------------------------------
  'equation/The Henyey–Greenstein phase function':
    'One parameter, $g$, which is exactly the mean cosine. Point at the normalisation: the density is ' +
    'per steradian (units sr⁻¹) and integrates to one over the sphere, so scattering only redistributes ' +
    'light. Next three slides: $g = -0.3$, $0$, $0.6$.',
  'hg-lobe/Back scattering: g = −0.3':
    'Point at the two peak values: p(180°) = 0.211 backwards against p(0°) = 0.033 forwards. Then the ' +
    'sample mean cosine: −0.3 within its standard error. Press 1–5 for the presets.',
  'hg-lobe/Isotropic scattering: g = 0':
    'At $g = 0$ both peaks are $1/(4\\pi) = 0.0796$ sr⁻¹. The outline is Rayleigh: close to isotropic ' +
    'but with forward and backward bumps. Point at ∫ p dω = 1: normalised whatever g.',
  'hg-lobe/Forward scattering: g = 0.6':
    'Log radius, so the backward tail shows: p(0°) = 0.796 against p(180°) = 0.0124, a factor 64. Turn ' +
    'the 3D lobe with the arrow keys (click it first). Point at the χ² of the samples against the closed ' +
    'form; if time allows run the sweep: L1 error ∝ N^−½.',
  'mie-lobe/Mie scattering: a fog droplet':
    'A 1 µm water droplet in green light, $x = 2\\pi r/\\lambda \\approx 11$. Point at the log plot: the ' +
    'Lorenz–Mie lobe (orange, drawn on the GPU from the tabulated phase function) is a narrow forward ' +
    'peak with ripples and a raised back (the glory); HG with the same $g$ (blue, dashed) has neither. ' +
    'Point at “HG with the same g: error”: the backscatter ratio is far from 1. Press 5 for a molecule: ' +
    'the lobe becomes Rayleigh’s $1 + \\cos^2\\theta$.',
  'mie-lobe/Why clouds are white':
    'A 10 µm cloud droplet: point at “Colour of the scattered light”, R : G : B ≈ 1 : 1 : 1, because ' +
    '$Q_{sca} \\to 2$ once $x \\gg 1$ (the extinction paradox). Drag the radius down to 0.01 µm: the ratio ' +
    'turns to about $(550/440)^4 \\approx 2.4$ for blue — the sky. Same water, different size.',
  'rayleigh-sky/Why the sky is blue':
    'Sun at 60°. Point at “Zenith blue/red”: about 4.5, the $\\lambda^{-4}$ law of Rayleigh scattering. ' +
    'Single scattering only: no ozone, no aerosols, no multiple scattering (the widget says so). Press 4 ' +
    'to switch scattering off: the sky goes black.',
  'rayleigh-sky/Why sunsets are red':
    'Sun at 2°: sunlight crosses about 19 air masses. Point at “Direct sunlight T_sun”: about ' +
    '(0.42, 0.13, 0.007). Beer’s law takes the blue first; what is left near the sun is red. Press 1 for ' +
    'noon to compare.',
  'rayleigh-sky/The sky’s accuracy against its cost':
    'Press “Run sweep”. The error falls as $N^{-2}$ (midpoint rule), but each view sample also marches ' +
    'N/4 sun samples, so against GPU time the slope is between −2 and −1. Point at the two fitted ' +
    'exponents in the last readout rows: this is what accuracy costs in time.',

  // ---- Chapter 4 -------------------------------------------------------------
  'equation/The radiative transfer equation':
    'Read the three underbraces left to right: extinction removes, emission and in-scattering add. ' +
    'Emission carries $\\sigma_a$ by Kirchhoff: only what absorbs can glow. Stress that $L$ appears ' +
    'both under the derivative and under the integral: an integro-differential equation.',
  'equation/The volume rendering equation':
    'The same equation integrated along the ray with the transmittance as integrating factor. Point at ' +
    'the surface term: the background seen through the whole medium. The next slide evaluates every term ' +
    'of this equation on one ray.',
  'vre-ray/The volume rendering equation':
    'Chapter 4’s worked example: τ = 2.01062, T = 0.133905. Point at “Emission + in-scattering + ' +
    'background”: 0.216524 + 0.129914 + 0.133905 = 0.480343, and at the float64 value next to the GPU ' +
    'one. Press 3: a thick medium hides the background; press 4: vacuum shows only the background.',

  // ---- Chapter 5 -------------------------------------------------------------
  'raymarch-steps/Ray marching: left versus midpoint samples':
    'Eight steps per ray, midpoint samples. Point at the RMSE, then press 1 (left samples, same cost) and ' +
    'point again: first against second order. Run the sweep: the fitted order p is about −2 for the ' +
    'midpoint and −1 for the left rule.',
  'raymarch-steps/The linearised update fails':
    'T ← T·(1 − σt·h) with four steps: where σt·h > 1 the factor is negative. Point at “Clamped steps”: ' +
    'the book clamps to 0 and counts them, and the warning says so. Switch the update to exact: ' +
    '$e^{-\\sigma_t h}$ never fails, at the same cost.',

  // ---- Chapter 6 -------------------------------------------------------------
  'equation/Delta tracking':
    'Fill the medium up to a constant majorant with null collisions, sample free flights in the ' +
    'homogeneous medium, accept each tentative collision as real with probability $\\sigma_t/\\bar\\sigma$. ' +
    'The estimate is 0 or 1 with mean T, so its variance is $T(1-T)$ whatever the majorant.',
  'delta-tracking/Delta tracking: unbiased, binary transmittance':
    'Four samples per pixel. Point at “Mean bias (± 1 SE)”: zero within its standard error, and at the ' +
    'RMSE, about 0.15 at about 1.4 lookups per estimate. Press 3 for exp(−τ̂): the bias stays however many ' +
    'samples; run the sweep for both.',
  'equation/Ratio tracking':
    'Keep the probability of passing as a weight instead of flipping a coin. Unbiased for any majorant ' +
    '(Campbell’s theorem); the variance is below delta tracking’s wherever $\\sigma_t < \\bar\\sigma$, and ' +
    'a looser majorant lowers it further at the price of more lookups.',
  'delta-tracking/Five estimators at equal samples and equal time':
    'Top row: the same samples per pixel for all five; bottom row: the same GPU time as delta tracking. ' +
    'Point at exp(−τ̂): biased however long it runs. Run the sweep: four curves fall with slope −½, one ' +
    'levels off. Unbiased ray marching wins by orders of magnitude (RMSE near $5\\times10^{-4}$ at 4 spp).',
  'delta-tracking/A majorant that is too low':
    'The majorant is half the tight one, so it is below σt in places. Point at the mean bias: positive, ' +
    'the image is too bright, $\\mathbb{E}[X] = \\exp(-\\int \\min(\\sigma_t, \\bar\\sigma))$. Switch the ' +
    'estimator to ratio tracking and keep the majorant: unbiased again, at a higher variance.',

  // ---- Chapter 7 -------------------------------------------------------------
  'transfer-function/Transfer functions: from Hounsfield units to light':
    'A CT head phantom in Hounsfield units. Drag an opacity point over the histogram, or press 1–4 ' +
    '(tissue and bone, skin, bone, lesions). Drag the image to orbit. Point at the error image: the ' +
    'wood-grain rings of one-voxel steps, and at the RMSE against the fine-step reference.',
  'transfer-function/Early ray termination: the skin surface':
    'Skin transfer function; the panel shows the steps each ray took. Point at “Steps taken / without ' +
    'early termination” and at the termination bias bound ε·L_max. Switch termination off and compare the ' +
    'steps and the GPU time per frame.',

  // ---- Chapter 8 -------------------------------------------------------------
  'inverse-render/Inverse rendering: fit a grid to photographs':
    'Press Start. Adam fits 131,072 grid values to eight images through the gradient of the ray marcher. ' +
    'Point at “Reduction from the start”: tenfold within about a hundred iterations, and at the held-out ' +
    'view MSE, which tells what eight views pin down. Iterations per second depend on the GPU.',
  'inverse-render/A neural field: hash grid + tiny MLP':
    'Press Start. The model is a table of learned features on eight grids from 4³ to 45³ cells, hashed ' +
    'where a grid has more vertices than the table, read by a 16-unit MLP. Point at “Model size” (half the ' +
    'grid’s parameters) and at the plot: both models’ losses against wall time. Per iteration the network ' +
    'costs more; compare per second.',
  'inverse-render/Three views: low loss, wrong volume':
    'Same fit, three cameras. Press Start and wait for the training loss to fall; then point at the ' +
    'held-out view: haze in corners that are empty in the truth. Low loss, wrong volume: many volumes make ' +
    'the same three pictures. Press 5 or 6 to try a prior.',

  // ---- Chapter 9 -------------------------------------------------------------
  'equation/Single scattering with shadow rays':
    'One distance along the view ray, one shadow ray per light with an unbiased transmittance estimate: ' +
    'no nested loops of N·M lookups. Point at the shadow-ray factor: it is what the sphere on the next ' +
    'slide switches off.',
  'single-scatter/Single scattering: a shaft of shadow in the fog':
    'Spot light, fog, sphere: the dark cone is the sphere’s shadow in the medium. Point at the plan table ' +
    '(what the kernel compiled, and why) and at “Time the plan saves” against the general kernel. Watch ' +
    'the standard error fall as samples accumulate.',
  'single-scatter/Switch scattering off: the plan shrinks':
    'σs = 0 and no surfaces: nothing can scatter light to the eye. Point at the plan: no in-scattering, ' +
    'no phase function, no shadow rays, no lights; the kernel is emission–absorption in closed form. Point ' +
    'at the time per sample against the general kernel.',

  // ---- Chapter 10 ------------------------------------------------------------
  'volume-path-tracer/Clouds are white: single versus multiple scattering':
    'Albedo 0.99, g = 0.8, τ = 10. Left: one scattering event; right: all of them. Point at “Brightness ' +
    'where τ ≥ 1, multiple ÷ single”: most of the light that leaves a cloud has scattered many times. ' +
    'Press 2 for dark smoke (α = 0.3): the two images agree much better.',
  'volume-path-tracer/Path tracing converges as one over the square root of time':
    'The puffy cloud. Wait for the reference bar, then point at the log–log plot: both errors fall with ' +
    'slope −½ against accumulated GPU time; point at the fitted slope row. The path tracer pays more time ' +
    'per sample for its longer paths (“Density lookups per path sample”).',
  'photon-map/Volume caustics: photon mapping against path tracing':
    'A glass ball focuses a small sun into fog. Point at the two RMSE rows at equal time: photon mapping ' +
    'resolves the cone, path tracing is still noise. Press 2 (many photons, narrow radius): the blur ' +
    '(bias) turns into noise (variance). Run the sweep for the plateau at fixed radius.',

  // ---- Chapter 11 ------------------------------------------------------------
  'equation/The dipole (Jensen et al. 2001)':
    'A real isotropic source one reduced mean free path deep, and a negative mirror image above the ' +
    'extrapolated boundary so that the fluence vanishes there. Point at the two terms: real and virtual ' +
    'source. Per millimetre: the table of Jensen et al. is in mm⁻¹, so $R_d(r)$ comes out per mm².',
  'dipole-profile/Skin: the dipole against Monte Carlo':
    'R_d(r) per channel on log–log axes: red travels millimetres, blue barely one. Point at “Dipole − MC ' +
    '(R · G · B)”: close far from the beam, off within a mean free path. Press More photons and watch the ' +
    'Monte Carlo error bars shrink; the “better dipole” is also a single-source approximation.',
  'dipole-profile/Colour bleeding: marble and ketchup':
    'Ketchup: green and blue absorbed within a millimetre, red wanders a centimetre, so the glow is red ' +
    '(total $R_d$ = 0.164, 0.006, 0.002). Press 2 for marble: three channels spread alike into a broad ' +
    'white halo (0.830, 0.791, 0.753).',
  'translucent-render/A translucent sphere: Lambert, dipole BSSRDF, path tracing':
    'Three images of the same skin sphere: Lambert, dipole BSSRDF by the Jensen–Buhler octree gather, and ' +
    'the path-traced reference. Point past the terminator: light bleeds only with the BSSRDF and the path ' +
    'tracer. Drag ε and point at “Nodes visited per pixel” and the BSSRDF error.',
  // ---- Chapter 12: colour in a medium ------------------------------------------
  'chromatic-media/Colour in a medium: three ways to sample a chromatic path':
    'Blue is 16× thicker than red ($\\sigma_t$ = 0.5, 2, 8 per metre). Left to right: one walk per channel, ' +
    'hero wavelength, spectral tracking, and the reference. Point at “Colour noise” and “Variance × time”: ' +
    'here one channel at a time wins variance × time (0.32 against 0.40 and 1.26 in the chapter’s ' +
    'measurement) and hero wavelength has about the same colour noise. Drag the spread slider to 100, then to 1.',
  'chromatic-media/A grey medium: the three estimators agree':
    'Spread 1: all channels alike. Point at “Colour noise”: exactly 0 for hero wavelength and spectral ' +
    'tracking, because one walk serves all channels; one channel at a time shows coloured speckle and takes ' +
    'about 2.6× as long. The winner row names hero wavelength for variance × time.',
  'translucent-room/A translucent sphere in a lit room: path tracing vs the dipole':
    'The skin sphere in a small Cornell box: volumetric path tracing through its boundary on the left, ' +
    'the dipole fed by path-traced irradiance on the right. Point at the share of light from the walls ' +
    '(about 44%), then switch the walls to black: the dipole is still half as bright as the path tracer. ' +
    'Not a scale bug: both let the same power in, but the dipole gives back only its half-space R_d total ' +
    '(35% less power than the finite sphere returns), and what it gives back stays near the lit top, ' +
    'while the camera sees the front near the terminator.',
};
