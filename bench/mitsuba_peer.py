"""Mitsuba 3 as a performance peer (bench/peers.ts runs this in its venv).

Reads a JSON job from argv[1]: {"variant", "scenes": [{"name", "dict", "spp", "repeats",
"warmup_spp"}]}, where each "dict" is a Mitsuba scene dict that bench/peers.ts exported from
our scene JSON (plain JSON: transforms as {"look_at": ...} / {"matrix": ...}, grids as
{"grid": {"shape": [z, y, x], "values": [...]}}). For each scene it renders once to warm the
JIT, then `repeats` independent images (seeds 1..repeats) of `spp` samples, and prints one
JSON line: the wall time of each timed render (s), the mean image (RGB per pixel, row 0 at
the top) and the per-sample variance per pixel and channel (spp times the variance of the
independent images), so that the caller can compare variance per sample and time per path.
With --once it renders a single image of `spp` samples and exits (the whole-process time).
"""
import json
import sys
import time


def build(node, mi):
    """Turns the exported JSON dict into what mi.load_dict takes."""
    if isinstance(node, list):
        return [build(v, mi) for v in node]
    if not isinstance(node, dict):
        return node
    if "look_at" in node:
        a = node["look_at"]
        t = mi.ScalarTransform4f().look_at(origin=a["origin"], target=a["target"], up=a["up"])
        if "scale" in node:
            t = t @ mi.ScalarTransform4f().scale(node["scale"])
        return t
    if "translate_scale" in node:
        a = node["translate_scale"]
        return mi.ScalarTransform4f().translate(a["translate"]) @ mi.ScalarTransform4f().scale(a["scale"])
    if "grid" in node:
        import numpy as np

        g = node["grid"]
        data = np.array(g["values"], dtype=np.float32).reshape(g["shape"] + [1])
        return mi.TensorXf(data)
    return {k: build(v, mi) for k, v in node.items()}


def main():
    job = json.load(open(sys.argv[1]))
    once = "--once" in sys.argv
    import mitsuba as mi
    import numpy as np

    mi.set_variant(job.get("variant", "llvm_ad_rgb"))
    for entry in job["scenes"]:
        scene = mi.load_dict(build(entry["dict"], mi))
        spp = entry["spp"]
        if once:
            image = np.array(mi.render(scene, spp=spp, seed=1))
            print(json.dumps({"name": entry["name"], "mean": float(image.mean())}), flush=True)
            continue
        np.array(mi.render(scene, spp=entry.get("warmup_spp", 4), seed=0))
        images, seconds = [], []
        for seed in range(1, entry["repeats"] + 1):
            start = time.perf_counter()
            image = np.array(mi.render(scene, spp=spp, seed=seed))
            seconds.append(time.perf_counter() - start)
            images.append(image[:, :, :3].astype(np.float64))
        stack = np.stack(images)
        mean = stack.mean(axis=0)
        variance = stack.var(axis=0, ddof=1) * spp
        print(
            json.dumps(
                {
                    "name": entry["name"],
                    "seconds": seconds,
                    "width": int(mean.shape[1]),
                    "height": int(mean.shape[0]),
                    "mean": mean.reshape(-1).tolist(),
                    "sampleVariance": variance.reshape(-1).tolist(),
                }
            ),
            flush=True,
        )


if __name__ == "__main__":
    main()
