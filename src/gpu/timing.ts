// GPU timing: timestamp queries around a pass when the device was created with
// the 'timestamp-query' feature; otherwise `read()` returns null and callers show
// wall time instead (and say so).

export class GpuTimer {
  private readonly querySet: GPUQuerySet | null;
  private readonly resolveBuffer: GPUBuffer | null;
  private readonly resultBuffer: GPUBuffer | null;

  constructor(device: GPUDevice) {
    if (device.features.has('timestamp-query')) {
      this.querySet = device.createQuerySet({ type: 'timestamp', count: 2 });
      this.resolveBuffer = device.createBuffer({
        size: 16,
        usage: GPUBufferUsage.QUERY_RESOLVE | GPUBufferUsage.COPY_SRC,
      });
      this.resultBuffer = device.createBuffer({
        size: 16,
        usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST,
      });
    } else {
      this.querySet = null;
      this.resolveBuffer = null;
      this.resultBuffer = null;
    }
  }

  get available(): boolean {
    return this.querySet !== null;
  }

  /** Spread into a pass descriptor: `encoder.beginComputePass(timer.passDescriptor())`. */
  passDescriptor(): { timestampWrites?: GPUComputePassTimestampWrites } {
    if (!this.querySet) return {};
    return {
      timestampWrites: {
        querySet: this.querySet,
        beginningOfPassWriteIndex: 0,
        endOfPassWriteIndex: 1,
      },
    };
  }

  /**
   * Spread into a render pass descriptor. To time several passes as one span, give
   * the first pass `begin` only and the last `end` only.
   */
  renderPassTimestamps(begin = true, end = true): GPURenderPassTimestampWrites | undefined {
    if (!this.querySet || !(begin || end)) return undefined;
    return {
      querySet: this.querySet,
      ...(begin ? { beginningOfPassWriteIndex: 0 } : {}),
      ...(end ? { endOfPassWriteIndex: 1 } : {}),
    };
  }

  resolve(encoder: GPUCommandEncoder): void {
    if (!this.querySet || !this.resolveBuffer || !this.resultBuffer) return;
    encoder.resolveQuerySet(this.querySet, 0, 2, this.resolveBuffer, 0);
    encoder.copyBufferToBuffer(this.resolveBuffer, 0, this.resultBuffer, 0, 16);
  }

  /** Elapsed GPU time in ms, or null without timestamp queries. */
  async read(): Promise<number | null> {
    if (!this.resultBuffer) return null;
    await this.resultBuffer.mapAsync(GPUMapMode.READ);
    const [begin, end] = new BigUint64Array(this.resultBuffer.getMappedRange());
    const elapsed =
      begin !== undefined && end !== undefined && end >= begin ? Number(end - begin) / 1e6 : null;
    this.resultBuffer.unmap();
    return elapsed;
  }

  destroy(): void {
    this.querySet?.destroy();
    this.resolveBuffer?.destroy();
    this.resultBuffer?.destroy();
  }
}
