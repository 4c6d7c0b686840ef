// inverse-render's set-up preview (issue 23): while the first render of the fit is under
// way the frame carries a refinement, and the readouts and the cost line say set-up is in
// progress instead of printing the not-yet-known training numbers (NaN).
import { describe, expect, it } from 'vitest';
import { widget, type InverseRenderFrame } from '../../src/widgets/inverse-render/widget.ts';

const frame: InverseRenderFrame = {
  model: 'grid',
  parameters: 4 * 32 ** 3,
  tableSize: 4096,
  trainSeconds: 0,
  comparison: null,
  iteration: 0,
  budget: 1000,
  lastLoss: null,
  trainMse: 0.027,
  initialTrainMse: 0.027,
  tenfoldAt: null,
  novelMse: 0.03,
  rate: Number.NaN,
  iterationMs: null,
  timing: '',
  dropped: 0,
  cost: { milliseconds: 120, timing: 'gpu-wall' },
  setupMs: 450,
  lastBatch: null,
  resolution: 32,
  trainViews: 8,
  size: 32,
  steps: 64,
  rays: 1024,
  learningRate: 0.05,
  regularizer: 'no regularizer',
};
const settingUp: InverseRenderFrame = {
  ...frame,
  trainMse: Number.NaN,
  initialTrainMse: Number.NaN,
  setupMs: Number.NaN,
  novelMse: null,
  refinement: { label: 'Setting up: target views drawn', pending: 'job' },
};
const backend = { kind: 'gpu' as const, adapterDescription: 'test' };

function row(key: string, shown: InverseRenderFrame): string {
  const found = widget.readouts!.rows.find((r) => r.key === key);
  const value = found!.format!(shown, backend);
  return typeof value === 'string' ? value : value.text;
}

describe('inverse-render set-up preview', () => {
  it('says set-up is in progress instead of printing unknown numbers', () => {
    for (const key of ['train-mse', 'reduction']) {
      expect(row(key, settingUp)).toMatch(/setting up/);
      expect(row(key, settingUp)).not.toMatch(/NaN/);
    }
    const line = widget.readouts!.costLine!(settingUp, 'GPU wall time', backend);
    expect(line).toMatch(/set-up in progress: the targets of every view drawn in 120\.0 ms/);
    expect(line).not.toMatch(/NaN/);
  });

  it('prints the training numbers once set up', () => {
    expect(row('train-mse', frame)).toBe('0.027 (at the last redraw)');
    expect(row('reduction', frame)).toBe('start: 0.027');
    expect(widget.readouts!.costLine!(frame, 'GPU wall time', backend)).toMatch(
      /Render of every view in 120\.0 ms \(GPU wall time\); set-up \(targets and the first render of every view\) 450\.0 ms wall time\./,
    );
  });
});
