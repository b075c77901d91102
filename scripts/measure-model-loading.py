#!/usr/bin/env python3
"""Times reading the shared models as scenes: the OBJ interiors and their GLB conversions
(trimesh), and the shared glTF files; prints the table of docs/src/measurements/models.md.
Run with the Python package built by `scripts/test-python.sh --from-build`:

    PYTHONPATH=target/python-from-build target/python-venv/bin/python scripts/measure-model-loading.py
"""
import os
import pathlib
import tempfile
import time

import goniolight
import trimesh

MODELS = pathlib.Path(__file__).resolve().parents[2] / "shared" / "models"


def best_of_three(path, scale, base):
    """The fastest of three reads of `path` as a scene's model, seconds, and its triangles."""
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        scene = goniolight.Scene.from_dict({"model": [{"path": str(path), "scale": scale}]}, base=base)
        best = min(best, time.perf_counter() - start)
    return best, scene.triangles


def main():
    base = pathlib.Path(tempfile.mkdtemp(prefix="goniolight-model-loading-"))
    files = []
    for model, scale in [("conference/conference.obj", 0.01), ("sibenik/sibenik.obj", 1.0)]:
        obj = MODELS / model
        glb = base / (obj.stem + ".glb")
        trimesh.load(str(obj), force="mesh", process=False, maintain_order=True).export(str(glb))
        files += [(obj, scale), (glb, scale)]
    for model in ["CornellBox/CornellBox.glb", "LightsPunctualLamp/LightsPunctualLamp.gltf",
                  "TransmissionTest/TransmissionTest.glb", "GlassVaseFlowers/GlassVaseFlowers.glb"]:
        files.append((MODELS / "gltf" / model, 1.0))
    print("| file | size | triangles read | time |\n|---|---|---|---|")
    for path, scale in files:
        seconds, triangles = best_of_three(path, scale, base)
        print(f"| {path.name} | {os.path.getsize(path) / 1e6:.2f} MB | {triangles:,} | {seconds * 1000:.0f} ms |")


if __name__ == "__main__":
    main()
