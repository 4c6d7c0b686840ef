// The "Shader library" appendix, generated from the modules' doc comments
// (shaders/*.wesl): each module's purpose, then each function with its
// signature, its documentation (equations typeset by KaTeX at build time), and
// the float64 twin that the tests hold it against.
import type MarkdownIt from 'markdown-it';
import type { ShaderModuleDocs } from './shaderDocs.ts';
import type { TocEntry } from './markdown.ts';
import { replaceReferenceCitations, type ChapterLink } from './citations.ts';

function escapeHtml(text: string): string {
  return text.replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
}

export const APPENDIX_FILE = 'appendix/shader-library.html';
export const APPENDIX_TITLE = 'Appendix: the shader library';
export const APPENDIX_SUMMARY =
  'Every function of the WGSL library that the figures draw from, with its equation, units, hard cases and float64 twin.';

export function renderAppendix(
  md: MarkdownIt,
  modules: readonly ShaderModuleDocs[],
  env: unknown,
  chapters: readonly ChapterLink[] = [],
): { html: string; toc: TocEntry[] } {
  const toc: TocEntry[] = [];
  // The doc comments cite the developers' numerical reference; readers get chapters.
  const doc = (markdown: string): string => replaceReferenceCitations(markdown, chapters);
  const parts: string[] = [
    md.render(
      'Each figure in this book is computed by kernels that import these modules; each function has a float64 ' +
        'TypeScript twin of the same name in `src/reference/`, and the test suite runs both on a table of inputs ' +
        'that includes the hard cases of the numerical reference. Shaders compute in f32, twins in f64.',
      env,
    ),
  ];
  for (const module of modules) {
    const id = `module-${module.name}`;
    toc.push({ level: 2, id, text: module.name });
    parts.push(`<h2 id="${id}"><code>${module.name}</code></h2>`);
    if (module.description) parts.push(md.render(doc(module.description), env));
    parts.push(
      `<p class="twin-note">Source <code>shaders/${module.name}.wesl</code>; twin <code>src/reference/${module.name}.ts</code>.</p>`,
    );
    const documented = module.declarations.filter((d) => d.kind === 'fn' || d.doc);
    for (const declaration of documented) {
      const declarationId = `${module.name}-${declaration.name}`;
      if (declaration.kind === 'fn')
        toc.push({ level: 3, id: declarationId, text: declaration.name });
      parts.push(
        `<section class="api-entry" id="${declarationId}">` +
          `<h3><code>${declaration.name}</code> <span class="api-kind">${declaration.kind}</span></h3>` +
          `<pre class="api-signature"><code>${escapeHtml(declaration.signature)}</code></pre>` +
          (declaration.doc ? md.render(doc(declaration.doc), env) : '') +
          `</section>`,
      );
    }
  }
  return { html: parts.join('\n'), toc };
}
