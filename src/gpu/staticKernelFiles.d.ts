// The module the static-kernels plugin generates (src/book/build/staticKernels.ts).
declare module 'virtual:static-kernels' {
  /** variantKey(kernel, conditions) → path of the linked WGSL file under the site root. */
  export const KERNEL_FILES: Readonly<Record<string, string>>;
}
