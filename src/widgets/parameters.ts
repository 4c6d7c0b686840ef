// Parameter schemas: every widget attribute is a physical quantity with a unit
// and a range (STYLE.md "What that means here" 1, 7). The schema drives the
// element's attribute parsing, its form controls, its URL-hash state and the docs.

export interface NumberParameter {
  kind: 'number';
  /** Attribute name on the element and key in the URL hash, e.g. `sigma-a`. */
  name: string;
  /** Label of the form control. */
  label: string;
  /** Symbol as KaTeX-free text, e.g. `σa`. */
  symbol: string;
  /** Unit as text, e.g. `1/m`; empty for dimensionless quantities. */
  unit: string;
  min: number;
  max: number;
  step: number;
  default: number;
  description: string;
  /** Former names, still read from attributes and links so that old pages and links keep working. */
  aliases?: readonly string[];
}

export interface ChoiceParameter {
  kind: 'choice';
  name: string;
  label: string;
  choices: readonly { value: string; label: string }[];
  default: string;
  description: string;
  /** Former names, still read from attributes and links. */
  aliases?: readonly string[];
}

export type Parameter = NumberParameter | ChoiceParameter;

export interface WidgetEntry {
  /** Element name without the `sb-` prefix. */
  name: string;
  title: string;
  description: string;
  parameters: readonly Parameter[];
}

export type ParameterValues = Record<string, number | string>;

export interface ParsedParameters {
  values: ParameterValues;
  /** One sentence per attribute that was invalid or out of range and was replaced. */
  warnings: string[];
}

function formatValue(value: number): string {
  return Number.isInteger(value) ? String(value) : String(Number(value.toPrecision(6)));
}

/**
 * Reads raw attribute strings into typed values: numbers are parsed and clamped
 * to their range, choices must be one of the listed values. Invalid input never
 * throws; it is replaced by the nearest valid value (or the default) and reported.
 */
export function parseParameters(
  parameters: readonly Parameter[],
  raw: (name: string) => string | null | undefined,
): ParsedParameters {
  const values: ParameterValues = {};
  const warnings: string[] = [];
  for (const parameter of parameters) {
    const text = rawValue(parameter, raw);
    if (text === null || text === undefined || text.trim() === '') {
      values[parameter.name] = parameter.default;
      continue;
    }
    if (parameter.kind === 'number') {
      const value = Number(text);
      // ±Infinity (e.g. "1e400") is out of range and clamped below; only NaN has no nearest value.
      if (Number.isNaN(value)) {
        values[parameter.name] = parameter.default;
        warnings.push(
          `${parameter.label} “${text}” is not a number; using ${formatValue(parameter.default)} ${parameter.unit}`.trim(),
        );
      } else if (value < parameter.min || value > parameter.max) {
        const clamped = Math.min(parameter.max, Math.max(parameter.min, value));
        values[parameter.name] = clamped;
        warnings.push(
          `${parameter.label} ${formatValue(value)} is outside [${formatValue(parameter.min)}, ${formatValue(parameter.max)}] ${parameter.unit}; clamped to ${formatValue(clamped)}`.trim(),
        );
      } else {
        values[parameter.name] = value;
      }
    } else {
      const choice = parameter.choices.find((c) => c.value === text.trim());
      if (choice) {
        values[parameter.name] = choice.value;
      } else {
        values[parameter.name] = parameter.default;
        warnings.push(
          `${parameter.label} “${text}” is not one of ${parameter.choices.map((c) => c.value).join(', ')}; using ${parameter.default}`,
        );
      }
    }
  }
  return { values, warnings };
}

/** The raw text under the parameter's name, else under its first alias that has one. */
function rawValue(
  parameter: Parameter,
  raw: (name: string) => string | null | undefined,
): string | null | undefined {
  const text = raw(parameter.name);
  if (text !== null && text !== undefined) return text;
  for (const alias of parameter.aliases ?? []) {
    const aliased = raw(alias);
    if (aliased !== null && aliased !== undefined) return aliased;
  }
  return text;
}

/**
 * Renames former names (aliases) in a name → value map to the current names, so that an
 * old link overrides a page's attributes like a new one; the current name wins over an alias.
 */
export function withCurrentNames<Value>(
  parameters: readonly Parameter[],
  entries: ReadonlyMap<string, Value>,
): Map<string, Value> {
  const renamed = new Map(entries);
  for (const parameter of parameters) {
    for (const alias of parameter.aliases ?? []) {
      const value = renamed.get(alias);
      if (value === undefined) continue;
      renamed.delete(alias);
      if (!renamed.has(parameter.name)) renamed.set(parameter.name, value);
    }
  }
  return renamed;
}

/** Serializes values that differ from their defaults, for the URL hash. */
export function encodeParameters(
  parameters: readonly Parameter[],
  values: ParameterValues,
): string {
  const search = new URLSearchParams();
  for (const parameter of parameters) {
    const value = values[parameter.name];
    if (value === undefined || value === parameter.default) continue;
    search.set(parameter.name, typeof value === 'number' ? formatValue(value) : value);
  }
  return search.toString();
}
