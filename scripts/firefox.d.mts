import type { LaunchOptions } from 'puppeteer-core';

export declare const FIREFOX_PATH: string;
export declare const LAVAPIPE_ICD: string;
export declare const WEBGPU_PREFS: Record<string, boolean>;
export declare function firefoxLaunchOptions(): LaunchOptions;
