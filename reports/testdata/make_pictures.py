#!/usr/bin/python3
"""Writes the test fixture's pictures (sample/pictures/): small stand-ins for what
`subdivbench pictures` renders (interfaces: pictures.json schema 1), so the report's tests do not
need a Vulkan device. Run once; the output is committed."""
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sample", "pictures")
SIZE = 96


def sphere(seed):
    y, x = np.mgrid[-1:1:SIZE * 1j, -1:1:SIZE * 1j]
    r2 = x * x + y * y
    z = np.sqrt(np.clip(1 - r2, 0, 1))
    light = np.clip(0.3 * x + 0.5 * y + 0.8 * z, 0, 1)
    bumps = 0.5 + 0.5 * np.sin(6 * x + seed) * np.cos(6 * y - seed)
    return r2 <= 1, light, bumps


def write(name, rgb):
    plt.imsave(os.path.join(HERE, name), rgb)


def main():
    os.makedirs(HERE, exist_ok=True)
    pictures = []
    for k, (mesh, scheme, level, tris) in enumerate([("torus-8x8", "cpatch-2pass", 9, 8192), ("torus-8x8", "geometry-image", 3, 8192),
                                                     ("quadsphere", "cpatch-2pass", 9, 12288), ("quadsphere", "geometry-image", 3, 12288)]):
        inside, light, bumps = sphere(k)
        shaded = np.zeros((SIZE, SIZE, 3))
        shaded[inside] = (light[inside] * 0.85)[:, None] * np.array([0.9, 0.75 + 0.05 * k, 1.0 - 0.1 * k])
        dev = np.zeros((SIZE, SIZE, 3))
        dev[inside] = plt.get_cmap("viridis")(bumps[inside])[:, :3]
        base = f"{scheme}-{mesh}"
        write(base + "-shaded.png", shaded)
        write(base + "-deviation.png", dev)
        common = {"scheme": scheme, "mesh": mesh, "level": level, "backend": "vulkan", "triangles": tris}
        pictures.append(dict(common, kind="shaded", file=base + "-shaded.png"))
        pictures.append(dict(common, kind="deviation", file=base + "-deviation.png", deviation_range=[0.0, 1e-5 * (k + 1)]))
    # A picture the renderer could not make is an entry with its error and no file (interfaces B).
    for kind in ("shaded", "deviation"):
        pictures.append({"scheme": "fragments-cc", "mesh": "quadsphere", "level": 3, "backend": "vulkan",
                         "triangles": 12288, "kind": kind, "error": "vkQueueSubmit: VK_ERROR_DEVICE_LOST (planted in the fixture)"})
    bar = plt.get_cmap("viridis")(np.tile(np.linspace(0, 1, 256), (16, 1)))[:, :, :3]
    write("colour-bar.png", bar)
    manifest = {"schema": 1, "available": True, "reason": "", "device": "llvmpipe (LLVM 15.0.6, 256 bits)",
                "colour_bar": "colour-bar.png", "pictures": pictures}
    with open(os.path.join(HERE, "pictures.json"), "w") as f:
        json.dump(manifest, f, indent=1)


if __name__ == "__main__":
    main()
