export declare const CHROMIUM_PATH: string;
export declare const WEBGPU_ARGS: string[];
export declare const NO_WEBGPU_ARGS: string[];
