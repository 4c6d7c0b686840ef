// Widget parameters: invalid attributes are clamped or replaced and reported,
// never thrown (DESIGN.md contract 2).
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  encodeParameters,
  parseParameters,
  withCurrentNames,
} from '../../src/widgets/parameters.ts';
import { BEER_LAW } from '../../src/widgets/beer-law/schema.ts';
import { VOLUME_PATH_TRACER } from '../../src/widgets/volume-path-tracer/schema.ts';

const parse = (attributes: Record<string, string>) =>
  parseParameters(BEER_LAW.parameters, (name) => attributes[name]);

describe('parseParameters', () => {
  it('uses defaults for missing attributes without warnings', () => {
    const { values, warnings } = parse({});
    expect(warnings).toEqual([]);
    expect(values['sigma-a']).toBe(0.2);
    expect(values['profile']).toBe('homogeneous');
  });

  it('clamps out-of-range numbers and says so', () => {
    const { values, warnings } = parse({ 'sigma-a': '-3', thickness: '1e9' });
    expect(values['sigma-a']).toBe(0);
    expect(values['thickness']).toBe(10);
    expect(warnings).toHaveLength(2);
    expect(warnings[0]).toMatch(/Absorption σa -3 is outside \[0, 10\] 1\/m; clamped to 0/);
  });

  it('replaces non-numbers and unknown choices by the default and says so', () => {
    const { values, warnings } = parse({ 'sigma-s': 'lots', profile: 'spiral' });
    expect(values['sigma-s']).toBe(0.8);
    expect(values['profile']).toBe('homogeneous');
    expect(warnings.join(' ')).toMatch(/not a number.*not one of homogeneous, smooth, layered/);
  });

  it('never throws and always yields in-range values, whatever the strings', () => {
    fc.assert(
      fc.property(
        fc.dictionary(
          fc.constantFrom('sigma-a', 'sigma-s', 'thickness', 'split', 'profile'),
          fc.string(),
        ),
        (attributes) => {
          const { values } = parse(attributes);
          return BEER_LAW.parameters.every((p) =>
            p.kind === 'number'
              ? (values[p.name] as number) >= p.min && (values[p.name] as number) <= p.max
              : p.choices.some((c) => c.value === values[p.name]),
          );
        },
      ),
    );
  });

  it('round-trips through the URL encoding', () => {
    const values = { ...parse({}).values, 'sigma-a': 1.25, profile: 'layered' };
    const encoded = encodeParameters(BEER_LAW.parameters, values);
    expect(encoded).toBe('sigma-a=1.25&profile=layered');
    const search = new URLSearchParams(encoded);
    expect(parseParameters(BEER_LAW.parameters, (name) => search.get(name)).values).toEqual(values);
  });
});

describe('renamed parameters', () => {
  const VPT = VOLUME_PATH_TRACER.parameters;
  it('reads a former name (alias) from attributes when the current name is absent', () => {
    const attributes: Record<string, string> = { density: '12' };
    const { values, warnings } = parseParameters(VPT, (name) => attributes[name]);
    expect(warnings).toEqual([]);
    expect(values['optical-thickness']).toBe(12);
    expect(values['density']).toBeUndefined();
  });

  it('prefers the current name over its alias, and clamps an alias like the name', () => {
    const both: Record<string, string> = { density: '12', 'optical-thickness': '3' };
    expect(parseParameters(VPT, (name) => both[name]).values['optical-thickness']).toBe(3);
    const outside: Record<string, string> = { density: '99' };
    const parsed = parseParameters(VPT, (name) => outside[name]);
    expect(parsed.values['optical-thickness']).toBe(30);
    expect(parsed.warnings).toHaveLength(1);
  });

  it('renames an old link’s keys so that they override the page’s attributes', () => {
    const link = withCurrentNames(
      VPT,
      new Map([
        ['density', '12'],
        ['spp', '3'],
      ]),
    );
    expect([...link]).toEqual([
      ['spp', '3'],
      ['optical-thickness', '12'],
    ]);
    const attributes: Record<string, string> = { 'optical-thickness': '8' };
    const merged = parseParameters(VPT, (name) => link.get(name) ?? attributes[name]);
    expect(merged.values['optical-thickness']).toBe(12);
    const current = withCurrentNames(
      VPT,
      new Map([
        ['optical-thickness', '4'],
        ['density', '12'],
      ]),
    );
    expect(current.get('optical-thickness')).toBe('4');
    expect(current.has('density')).toBe(false);
  });
});
