#!/usr/bin/env python3
"""goniolight's radiosity against Radiance in a bundled validation room.

Builds the same room (its OBJ's polygons, Kd from its MTL, `[[material]]` overrides from
its scene file; a translucent material becomes Radiance's two-sided `trans`) lit by the
same luminaire (the LDT converted to IES by `goniolight ldt convert`, then to Radiance by
`ies2rad`) in Radiance and in goniolight, and compares the illuminance on a work plane at
0.8 m. `--scene box_room` (default): the 6 x 4 x 3 m box room, reflectances 0.2 floor /
0.5 walls / 0.7 ceiling. `--scene luminous_ceiling`: a 4 x 4 x 3 m room under a
translucent panel (reflectance 0.4, diffuse transmittance 0.3) lit from the plenum, where
every lux on the work plane has come through the panel. `--scene mirror_room`: the box
room with its back wall a mirror (specular reflectance 0.9, Radiance's `mirror`).
`--scene glass_partition`: a 6 x 4 x 3 m room split by clear glass (specular
transmittance 0.85, Radiance's `trans` with all its transmission specular) with the
luminaire on one side. `--scene side_lit_room`: the box room lit only by its `[sky]` (the
CIE overcast sky, `gensky -c` with the same diffuse horizontal illuminance and ground
reflectance) through a window glazed with Radiance's `glass` of the same normal
transmittance (goniolight's daylight glazing is that model; Radiance's pane also reflects,
goniolight's does not):

  direct: Radiance `rtrace -I -ab 0`  vs  `goniolight illuminance`
          (daylight: `-ab 1`, the sky and ground seen through the window)
  total:  a converged Radiance run    vs  `goniolight radiosity --points`

and, with --bench, the time each needs to come within 2 % (mean absolute difference) of
the converged Radiance work plane, measured side by side on this machine.

Radiance comes from pyradiance (pip install pyradiance), which ships rtrace, oconv and
ies2rad. Writes radiance_SCENE.csv (x y z and every column; the last, Radiance's total
averaged over each point's mirror images where the luminaire is centred along x or y and
the room is symmetric about that mid-plane, is what the total is checked against) into
--out.

Usage: python3 scripts/compare_radiance.py [--scene NAME] [--goniolight BIN] [--out DIR]
       [--bench]
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENES = ROOT / "assets/scenes"
# Set by main() from --scene: the scene file and the room's extent (the OBJ's bounds).
SCENE = SCENES / "box_room.toml"
ROOM = (6.0, 4.0, 3.0)
WORK_PLANE_Z = 0.8
# Radiance's luminous efficacy of its white light, lm/W.
WHITE_EFFICACY = 179.0
# A converged Radiance run: eight bounces, dense hemisphere sampling, fine ambient cache.
RADIANCE_CONVERGED = "-ab 8 -ad 2048 -as 1024 -aa 0.05 -ar 256 -lw 1e-5"
RADIANCE_COMMON = "-h -I -dt 0 -dc 1 -ds 0.01 -dj 0"


def radiance_bin():
    try:
        import pyradiance
    except ImportError:
        sys.exit("error: Radiance is missing: pip install pyradiance")
    base = Path(pyradiance.__file__).parent
    return base / "bin", base / "lib"


def work_plane(step=0.5):
    """Points on a grid at 0.8 m, half a step from the walls, facing up."""
    nx, ny = round(ROOM[0] / step), round(ROOM[1] / step)
    return [
        (step * (i + 0.5), step * (j + 0.5), WORK_PLANE_Z)
        for j in range(ny)
        for i in range(nx)
    ]


def obj_polygons(obj):
    """The OBJ's faces as (material, [corner, ...]) and its file's `mtllib`."""
    vertices, faces, material, mtllib = [], [], None, None
    for line in obj.read_text().splitlines():
        words = line.split()
        if words[:1] == ["v"]:
            vertices.append(tuple(float(w) for w in words[1:4]))
        elif words[:1] == ["usemtl"]:
            material = words[1]
        elif words[:1] == ["mtllib"]:
            mtllib = words[1]
        elif words[:1] == ["f"]:
            faces.append((material, [vertices[int(w.split("/")[0]) - 1] for w in words[1:]]))
    return faces, mtllib


def grey(value):
    """A scene-file colour (one number or three) as three numbers."""
    return value if isinstance(value, list) else [value] * 3


def specular_of(overrides):
    """Per material name its (specular reflectance, specular transmittance)."""
    return {o["name"]: (grey(o.get("specular_reflectance", 0.0)),
                        grey(o.get("specular_transmittance", 0.0))) for o in overrides}


def materials(mtl, overrides):
    """Per material name (Kd, diffuse transmittance) from the MTL and the scene's
    `[[material]]` overrides."""
    kd, name = {}, None
    for line in mtl.read_text().splitlines():
        words = line.split()
        if words[:1] == ["newmtl"]:
            name = words[1]
        elif words[:1] == ["Kd"] and name:
            kd[name] = [float(w) for w in words[1:4]]
    out = {name: (rgb, [0.0, 0.0, 0.0]) for name, rgb in kd.items()}
    for o in overrides:
        rho, tau = out[o["name"]]
        t = o.get("diffuse_transmittance", 0.0)
        out[o["name"]] = (rho, t if isinstance(t, list) else [t] * 3)
    return out


def glass_transmissivity(tn):
    """Radiance's `glass` transmissivity for a normal transmittance (its documented
    closed form for n = 1.52)."""
    return ((0.8402528435 + 0.0072522239 * tn * tn) ** 0.5 - 0.9166530661) / 0.0036261119 / tn


def sky_rad(sky):
    """The scene's CIE overcast `[sky]` as Radiance's `gensky -c` with the same diffuse
    horizontal illuminance (W/m² at Radiance's 179 lm/W) and ground reflectance, its sky
    and ground hemispheres as `glow` sources."""
    if sky["model"] != "cie-overcast" or sky.get("direct_horizontal_lux") or sky.get("direct_normal_lux"):
        sys.exit("error: only the CIE overcast sky without sun is compared")
    watts = sky["diffuse_horizontal_lux"] / WHITE_EFFICACY
    rho = sky.get("ground_reflectance", 0.2)
    return (f"!gensky 3 21 12 -c -B {watts} -g {rho}\n"
            "skyfunc glow sky_glow\n0\n0\n4 1 1 1 0\n"
            "sky_glow source sky\n0\n0\n4 0 0 1 180\n"
            "skyfunc glow ground_glow\n0\n0\n4 1 1 1 0\n"
            "ground_glow source ground\n0\n0\n4 0 0 -1 180\n")


def room_rad(scene, lum_rad, position):
    """The scene's model in Radiance's scene language: `plastic` for opaque materials,
    `trans` (two-sided; C (1 - t) reflected, C t transmitted diffusely) for translucent,
    `mirror` for a mirror, and `trans` with C = the transmittance, t = 1 and all of it
    specular for clear glass (no diffuse part: goniolight's constant, Fresnel-free
    glass)."""
    model = scene["model"][0]
    faces, mtllib = obj_polygons(SCENE.parent / model["path"])
    mats = materials(SCENE.parent / mtllib, scene.get("material", []))
    specular = specular_of(scene.get("material", []))
    out = []
    for name, (rho, tau) in mats.items():
        mirror, glass = specular.get(name, ([0.0] * 3, [0.0] * 3))
        if max(mirror) > 0 or max(glass) > 0:
            if max(rho) > 0 or max(tau) > 0 or (max(mirror) > 0 and max(glass) > 0):
                sys.exit(f"error: material {name}: only a pure mirror or pure glass is compared")
            if max(mirror) > 0:
                out.append(f"void mirror {name}\n0\n0\n3 {mirror[0]} {mirror[1]} {mirror[2]}\n")
            elif "sky" in scene:
                t = glass_transmissivity(sum(glass) / 3)
                out.append(f"void glass {name}\n0\n0\n3 {t} {t} {t}\n")
            else:
                out.append(f"void trans {name}\n0\n0\n7 {glass[0]} {glass[1]} {glass[2]} 0 0 1 1\n")
        elif max(tau) > 0:
            c = [r + t for r, t in zip(rho, tau)]
            t = sum(tau) / sum(c)
            out.append(f"void trans {name}\n0\n0\n7 {c[0]} {c[1]} {c[2]} 0 0 {t} 0\n")
        else:
            out.append(f"void plastic {name}\n0\n0\n5 {rho[0]} {rho[1]} {rho[2]} 0 0\n")
    for k, (name, poly) in enumerate(faces):
        coords = " ".join(f"{a} {b} {c}" for a, b, c in poly)
        out.append(f"{name} polygon face.{k}\n0\n0\n{3 * len(poly)} {coords}\n")
    if lum_rad is None:
        out.append(sky_rad(scene["sky"]))
    else:
        px, py, pz = position
        out.append(f"!xform -t {px} {py} {pz} {lum_rad}\n")
    return "".join(out)


def lux_of(line):
    r, g, b = (float(v) for v in line.split()[:3])
    return WHITE_EFFICACY * (0.265 * r + 0.670 * g + 0.065 * b)


def rtrace(env, octree, options, points):
    rays = "".join(f"{x} {y} {z} 0 0 1\n" for x, y, z in points)
    start = time.perf_counter()
    run = subprocess.run(
        ["rtrace", *RADIANCE_COMMON.split(), *options.split(), str(octree)],
        input=rays, capture_output=True, text=True, env=env, cwd=octree.parent,
    )
    seconds = time.perf_counter() - start
    if run.returncode != 0:
        sys.exit(f"error: rtrace {options} failed:\n{run.stderr}")
    out = run.stdout
    return [lux_of(l) for l in out.splitlines() if l.strip()], seconds


def goniolight(binary, args, points):
    rays = "".join(f"{x} {y} {z} 0 0 1\n" for x, y, z in points)
    start = time.perf_counter()
    out = subprocess.run(
        [str(binary), *args, str(SCENE)], input=rays, capture_output=True, text=True,
    )
    seconds = time.perf_counter() - start
    if out.returncode != 0:
        sys.exit(f"error: goniolight {' '.join(args)} failed:\n{out.stderr}")
    return [float(v) for v in out.stdout.split()], seconds


def mad(values, reference):
    """Mean absolute difference relative to the reference's mean (absolute, in lux,
    where the reference is dark: nothing reaches the luminous ceiling's work plane
    directly)."""
    diff = sum(abs(a - b) for a, b in zip(values, reference)) / len(reference)
    mean = sum(reference) / len(reference)
    return diff / mean if mean > 1e-9 else diff


def worst(values, reference):
    """The worst relative difference (absolute, in lux, at dark reference points)."""
    return max(abs(a / b - 1.0) if b > 1e-9 else abs(a) for a, b in zip(values, reference))


def mirror_averaged(points, values, position):
    """`values` averaged over each point's mirror images about the room's mid-planes
    along which the luminaire at `position` is centred; None when it is centred along
    neither."""
    flips = [k for k in (0, 1) if abs(position[k] - ROOM[k] / 2) < 1e-9]
    if not flips:
        return None
    index = {(round(p[0], 6), round(p[1], 6)): k for k, p in enumerate(points)}
    out = []
    for x, y, _ in points:
        xs = (x, ROOM[0] - x) if 0 in flips else (x,)
        ys = (y, ROOM[1] - y) if 1 in flips else (y,)
        images = {(round(u, 6), round(v, 6)) for u in xs for v in ys}
        out.append(sum(values[index[i]] for i in images) / len(images))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", default="box_room",
                    choices=["box_room", "luminous_ceiling", "mirror_room", "glass_partition",
                             "side_lit_room"])
    ap.add_argument("--goniolight", type=Path, default=ROOT / "target/release/goniolight")
    ap.add_argument("--out", type=Path, default=Path("radiance-compare"))
    ap.add_argument("--radiance-csv", type=Path,
                    help="reuse Radiance's direct and converged columns from an earlier "
                         "run's CSV (the converged run takes minutes)")
    ap.add_argument("--bench", action="store_true",
                    help="also time both to within 2 %% of their converged work plane")
    a = ap.parse_args()
    global SCENE, ROOM
    SCENE = SCENES / f"{a.scene}.toml"
    faces, _ = obj_polygons(SCENES / f"{a.scene}.obj")
    ROOM = tuple(max(p[k] for _, poly in faces for p in poly) for k in range(3))
    if not a.goniolight.exists():
        subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=ROOT, check=True)
    work = Path(tempfile.mkdtemp(prefix="goniolight-radiance-"))
    try:
        return compare(a, work)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def compare(a, work):
    bindir, libdir = radiance_bin()
    env = dict(os.environ, PATH=f"{bindir}{os.pathsep}{os.environ['PATH']}",
               RAYPATH=f"{work}{os.pathsep}{libdir}")
    scene = tomllib.loads(SCENE.read_text())
    points = work_plane()
    daylight = "sky" in scene
    if daylight:
        lum = {"position": (-1.0, -1.0, -1.0)}
        source = f"the {scene['sky']['model']} sky of {scene['sky']['diffuse_horizontal_lux']} lx"
        (work / "room.rad").write_text(room_rad(scene, None, None))
    else:
        lum = scene["luminaire"][0]
        ldt = (SCENE.parent / lum["file"]).resolve()
        source = f"luminaire {ldt.name} at {lum['position']}"
        subprocess.run([str(a.goniolight), "ldt", "convert", str(ldt), "--out",
                        str(work / "lum.ies")], check=True, capture_output=True)
        # -i: a point-like sphere (1 cm) as goniolight's point source; -t default: white.
        subprocess.run(["ies2rad", "-dm", "-t", "default", "-i", "0.01", "-o", "lum",
                        "lum.ies"], cwd=work, env=env, check=True)
        (work / "room.rad").write_text(room_rad(scene, "lum.rad", lum["position"]))
    octree = work / "room.oct"
    with open(octree, "wb") as f:
        subprocess.run(["oconv", "room.rad"], cwd=work, env=env, check=True, stdout=f)
    # The sky is a glow source: only ambient rays see it, so its direct part is `-ab 1`.
    rad_direct, t_rad_direct = rtrace(
        env, octree, "-ab 1 -ad 65536 -as 0 -aa 0 -lw 1e-7" if daylight else "-ab 0", points)
    if a.radiance_csv:
        rows = [l.split(",") for l in a.radiance_csv.read_text().splitlines()[1:]]
        if [tuple(float(v) for v in r[:3]) for r in rows] != points:
            sys.exit(f"error: {a.radiance_csv}: not the points of this comparison")
        rad_total, t_rad_total = [float(r[5]) for r in rows], float("nan")
    else:
        rad_total, t_rad_total = rtrace(env, octree, RADIANCE_CONVERGED, points)
    gl_direct, t_gl_direct = goniolight(a.goniolight, ["illuminance"], points)
    gl_total, t_gl_total = goniolight(
        a.goniolight, ["radiosity", "--points", "--converge", "0.999"], points)
    a.out.mkdir(parents=True, exist_ok=True)
    reference = mirror_averaged(points, rad_total, lum["position"]) or rad_total
    with open(a.out / f"radiance_{a.scene}.csv", "w") as f:
        f.write("x,y,z,radiance_direct_lx,goniolight_direct_lx,"
                "radiance_total_lx,goniolight_total_lx,radiance_total_averaged_lx\n")
        for p, rd, gd, rt, gt, ra in zip(points, rad_direct, gl_direct, rad_total, gl_total,
                                         reference):
            f.write(f"{p[0]},{p[1]},{p[2]},{rd:.4f},{gd:.4f},{rt:.4f},{gt:.4f},{ra:.4f}\n")
    mean = lambda v: sum(v) / len(v)
    print(f"{a.scene} {ROOM[0]:g} x {ROOM[1]:g} x {ROOM[2]:g} m, {len(points)} work-plane points at {WORK_PLANE_Z} m, "
          f"{source}")
    print("| quantity | Radiance mean lx | goniolight mean lx | mean abs. diff. | worst point |")
    print("|---|---|---|---|---|")
    direct_name = "direct (`-ab 1`: sky and ground)" if daylight else "direct (`-ab 0`)"
    for name, r, g in [(direct_name, rad_direct, gl_direct),
                       ("total (converged)", rad_total, gl_total),
                       ("interreflected (total − direct)",
                        [t - d for t, d in zip(rad_total, rad_direct)],
                        [t - d for t, d in zip(gl_total, gl_direct)])]:
        print(f"| {name} | {mean(r):.2f} | {mean(g):.2f} | {100 * mad(g, r):.2f} % "
              f"| {100 * worst(g, r):.2f} % |")
    # Where the luminaire is centred along x or y, the bundled rooms are symmetric about
    # that mid-plane: averaging Radiance over the mirror images of each point takes out
    # much of its sampling noise.
    averaged = mirror_averaged(points, rad_total, lum["position"])
    if averaged is not None:
        print(f"| total, Radiance averaged over the mirror images | {mean(averaged):.2f} "
              f"| {mean(gl_total):.2f} | {100 * mad(gl_total, averaged):.2f} % "
              f"| {100 * worst(gl_total, averaged):.2f} % |")
    print(f"times: rtrace direct {t_rad_direct:.2f} s, converged {t_rad_total:.2f} s; "
          f"goniolight illuminance {t_gl_direct:.2f} s, radiosity {t_gl_total:.2f} s")
    # Radiance samples the sky through the window with its ambient rays (-ad 65536): its
    # direct part is itself a few per cent noisy point by point.
    direct_limit = 0.05 if daylight else 0.01
    ok = worst(gl_direct, rad_direct) <= direct_limit and mad(gl_total, reference) <= 0.03
    print("PASS" if ok else f"FAIL: direct must agree within {100 * direct_limit:g} % at every point, "
          "total within 3 % mean absolute difference (of Radiance averaged over the "
          "mirror images where the room has them)")
    if a.bench:
        bench(a.goniolight, env, octree, points, rad_total, gl_total)
    return 0 if ok else 1


# Cheaper Radiance settings, coarse to fine (the last is the converged run).
RADIANCE_LADDER = [
    "-ab 1 -ad 256 -as 128 -aa 0.2 -ar 64 -lw 1e-3",
    "-ab 2 -ad 256 -as 128 -aa 0.2 -ar 64 -lw 1e-3",
    "-ab 3 -ad 512 -as 256 -aa 0.15 -ar 128 -lw 1e-4",
    "-ab 4 -ad 512 -as 256 -aa 0.1 -ar 128 -lw 1e-4",
    "-ab 6 -ad 1024 -as 512 -aa 0.1 -ar 256 -lw 1e-5",
    "-ab 8 -ad 1024 -as 512 -aa 0.05 -ar 256 -lw 1e-5",
]
# The solver stops at the first shot whose convergence reaches the setting, so 0.1 is one
# shot (the luminaires' direct light, then the brightest surface's): the cheapest run.
GONIOLIGHT_LADDER = ["0.1", "0.5", "0.7", "0.8", "0.9", "0.95", "0.98", "0.99"]


def bench(binary, env, octree, points, rad_converged, gl_converged):
    """Per tool the cheapest setting within 2 % (mean absolute difference) of its own
    converged work plane, and its wall-clock time (the whole process: start-up, scene,
    GPU or CPU work; the median of three runs under 10 s), side by side on this machine."""
    print("\ntime to within 2 % of the converged work plane (wall clock, this machine):")
    print("| tool | setting | MAD to own converged | MAD to Radiance converged | seconds |")
    print("|---|---|---|---|---|")
    found = {}
    runs = [("Radiance rtrace", o, lambda o=o: rtrace(env, octree, o, points), rad_converged)
            for o in RADIANCE_LADDER]
    runs += [("goniolight radiosity", f"--converge {c}",
              lambda c=c: goniolight(binary, ["radiosity", "--points", "--converge", c], points),
              gl_converged) for c in GONIOLIGHT_LADDER]
    for tool, setting, run, own in runs:
        if tool in found:
            continue
        lux, seconds = run()
        if seconds < 10:
            # Short runs vary by a third from run to run (process and GPU start-up): the
            # median of three.
            seconds = sorted([seconds] + [run()[1] for _ in range(2)])[1]
        d_own, d_rad = mad(lux, own), mad(lux, rad_converged)
        print(f"| {tool} | `{setting}` | {100 * d_own:.2f} % | {100 * d_rad:.2f} % | {seconds:.2f} |")
        if d_own <= 0.02:
            found[tool] = seconds
    g = found.get("goniolight radiosity")
    r = found.get("Radiance rtrace")
    if g and r:
        print(f"\nRadiance / goniolight time to 2 %: {r / g:.1f}×")
    elif g:
        print(f"\nRadiance did not come within 2 % of its converged run with any cheaper "
              f"setting: its time to 2 % is more than the last rung's; goniolight {g:.2f} s")


if __name__ == "__main__":
    sys.exit(main())
