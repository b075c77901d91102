"""glTF models against an independent reader (trimesh): the shared glTF files give the
triangle counts and areas trimesh finds, and the shared OBJ interiors converted to GLB by
trimesh give the same direct lux at 100 points as the OBJ files themselves."""

import numpy as np
import pytest

from test_goniolight import ROOT

import goniolight
import trimesh  # noqa: E402  (installed by scripts/test-python.sh)

SHARED = ROOT.parent / "shared" / "models"
GLTF = SHARED / "gltf"


def _trimesh_triangles(path):
    """Every triangle trimesh places through the default scene, as an N × 3 × 3 array."""
    scene = trimesh.load(str(path), force="scene", process=False)
    meshes = scene.dump()
    return np.concatenate([m.triangles for m in meshes])


def _has_area(t):
    """goniolight's rule for a triangle with an area (geometry::has_area)."""
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    scale = np.maximum(((t[:, 1] - t[:, 0]) ** 2).sum(1), ((t[:, 2] - t[:, 0]) ** 2).sum(1))
    return (n ** 2).sum(1) > 1e-24 * scale * scale


@pytest.mark.parametrize("model", [
    "CornellBox/CornellBox.glb",
    "LightsPunctualLamp/LightsPunctualLamp.gltf",
    "TransmissionTest/TransmissionTest.glb",
    "GlassVaseFlowers/GlassVaseFlowers.glb",
])
def test_shared_gltf_models_have_trimesh_counts_and_areas(model, tmp_path):
    path = GLTF / model
    assert path.exists(), f"the shared test data is missing: {path}"
    triangles = _trimesh_triangles(path)
    solid = triangles[_has_area(triangles)]
    area = 0.5 * np.linalg.norm(np.cross(solid[:, 1] - solid[:, 0], solid[:, 2] - solid[:, 0]), axis=1).sum()
    scene = goniolight.Scene.from_dict({"model": [{"path": str(path)}]}, base=tmp_path)
    assert scene.triangles == len(solid), (scene.triangles, len(triangles), len(solid))
    assert scene.area == pytest.approx(area, rel=1e-5)


def _points(lo, hi, count, seed):
    """`count` points facing up on the plane a tenth of the way up the box lo…hi, over
    its middle 60 % in plan."""
    rng = np.random.default_rng(seed)
    xy = lo[:2] + (hi[:2] - lo[:2]) * rng.uniform(0.2, 0.8, size=(count, 2))
    z = np.full((count, 1), lo[2] + 0.1 * (hi[2] - lo[2]))
    return np.hstack([xy, z, np.tile([0.0, 0.0, 1.0], (count, 1))])


@pytest.mark.parametrize("model,scale", [("conference/conference.obj", 0.01), ("sibenik/sibenik.obj", 1.0)])
def test_an_obj_converted_to_glb_by_trimesh_gives_the_same_direct_lux(model, scale, tmp_path):
    obj = SHARED / model
    assert obj.exists(), f"the shared test data is missing: {obj}"
    loaded = trimesh.load(str(obj), force="mesh", process=False, maintain_order=True)
    glb = tmp_path / "converted.glb"
    loaded.export(str(glb))
    luminaire = ROOT / "luminaires" / "eulumdat-analysis" / "sample_18.ldt"

    def scene(path):
        lo, hi = loaded.bounds * scale
        # The file's +Y up is the world's +Z; its z the world's −y.
        centre = [(lo[0] + hi[0]) / 2, -(lo[2] + hi[2]) / 2, lo[1] + 0.5 * (hi[1] - lo[1])]
        return goniolight.Scene.from_dict({
            "model": [{"path": str(path), "scale": scale}],
            "luminaire": [{"file": str(luminaire), "position": centre}],
        }, base=tmp_path)

    obj_scene, glb_scene = scene(obj), scene(glb)
    # Rounding to the GLB's 32-bit floats breaks the exact collinearity of a few of the
    # OBJ's degenerate triangles (3 of Šibenik's 11): slivers of no measurable area.
    assert abs(glb_scene.triangles - obj_scene.triangles) <= 1e-4 * obj_scene.triangles
    lo, hi = loaded.bounds * scale
    world_lo = np.array([lo[0], -hi[2], lo[1]])
    world_hi = np.array([hi[0], -lo[2], hi[1]])
    points = _points(world_lo, world_hi, 100, 7)
    a = goniolight.illuminance(obj_scene, points, cpu=True, shadows="paraboloid")
    b = goniolight.illuminance(glb_scene, points, cpu=True, shadows="paraboloid")
    assert (a > 0).sum() >= 25, "a good share of the points see the luminaire"
    np.testing.assert_allclose(b, a, rtol=1e-6, atol=1e-9)
