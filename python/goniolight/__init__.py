"""goniolight for Python: real luminaire files (EULUMDAT ``.ldt``, IES ``.ies``), their
interpolation and its check, the sun's position, illuminance at points of a scene,
its radiosity solution (the interreflected light), its calculation surfaces, and sun studies
of a model (hours of sun or shadow on the ground, facades and windows).

The numbers come from the same library code as the ``goniolight`` command line: ``info``
equals ``goniolight ldt info --json``, ``sample`` equals ``goniolight ldt sample``,
``sun_position`` equals ``goniolight sun --json``, ``illuminance`` equals
``goniolight illuminance``, ``radiosity(...).lux`` equals ``goniolight radiosity
--points``, ``calc`` equals ``goniolight calc``'s ``calc.json``, ``render`` draws what
``goniolight render`` draws and ``sun_study`` equals
``goniolight profile``'s ``study.json`` and ``hours.csv``.

Run from the repository's root (the tests run these examples):

>>> import goniolight, numpy as np
>>> lum = goniolight.read("luminaires/eulumdat-analysis/sample_18.ldt")
>>> round(lum.info["flux_lm"], 1)
2445.4
>>> lum.sample([0, 90], [0, 30], interp="catmull-rom").round(1)
array([442.8, 346.2])
>>> sun = goniolight.sun_position(48.21, 16.37, "2026-06-21T12:00", tz="Europe/Vienna")
>>> round(float(sun["elevation_deg"][0]), 2)
62.83
>>> goniolight.illuminance("assets/scenes/box_room.toml", [[1, 1, 0.8, 0, 0, 1]], cpu=True).round(1)
array([33.])
"""

from __future__ import annotations

import json
import os
from typing import Iterable, Optional, Sequence, Union

import numpy as np

from . import _native

__all__ = ["Scene", "Luminaire", "read", "ugr_table", "luminance_table", "datasheet", "sun_position",
           "illuminance", "radiosity", "Radiosity", "calc", "sunlight", "sun_study", "SunStudy", "render", "Rendering",
           "INTERPOLATIONS"]

#: The interpolation methods, as the command line names them.
INTERPOLATIONS = ("nearest", "bilinear", "catmull-rom", "monotone")

PathLike = Union[str, "os.PathLike[str]"]


class Scene:
    """A scene: loaded once from its file (``Scene.load``) or built from a dict with the
    scene file's keys (``Scene.from_dict``), and passed to ``render``, ``illuminance``,
    ``radiosity`` and ``calc`` in place of a path (each also takes the path itself).

    >>> import goniolight
    >>> room = goniolight.Scene.load("assets/scenes/box_room_calc.toml")
    >>> room.luminaires, room.grids[0]
    (1, 'work plane')
    >>> lamp = {"file": "../../luminaires/eulumdat-plot/sample_06_isym1.ldt",
    ...         "position": [3.0, 2.0, 2.95]}
    >>> same = goniolight.Scene.from_dict(
    ...     {"model": [{"path": "box_room.obj", "up": "z"}], "luminaire": [lamp]},
    ...     base="assets/scenes")
    >>> same.luminaires, same.triangles == room.triangles
    (1, True)
    """

    def __init__(self, native: "_native.NativeScene"):
        self._native = native

    @classmethod
    def load(cls, path: PathLike) -> "Scene":
        """The scene file at ``path`` (TOML) and everything it refers to. What loading works
        around (a missing MTL file, triangles without area) is raised as ``UserWarning``;
        a bad file raises ValueError naming the file, line and key."""
        return cls(_native.NativeScene.load(os.fspath(path)))

    @classmethod
    def from_dict(cls, scene: dict, base: PathLike = ".", name: str = "scene.toml") -> "Scene":
        """The scene of ``scene``, a dict with the scene file's keys (as ``tomllib.load``
        reads a scene file: ``{"model": [{"path": ...}], "luminaire": [...], "grid":
        [...]}``). Relative paths resolve against the folder ``base``; ``name`` names the
        scene in messages. A key the scene file does not know raises ValueError."""
        path = os.path.join(os.fspath(base), name)
        return cls(_native.NativeScene.from_json(json.dumps(scene), path))

    @property
    def path(self) -> str:
        """The scene file (or ``base/name`` of a scene from a dict)."""
        return self._native.path

    @property
    def triangles(self) -> int:
        """Triangles of the model."""
        return self._native.triangles

    @property
    def area(self) -> float:
        """The area of the model's triangles, m² (one side each)."""
        return self._native.area

    @property
    def luminaires(self) -> int:
        """Placed luminaires."""
        return self._native.luminaires

    @property
    def grids(self) -> list:
        """The calculation grids' names."""
        return list(self._native.grids)

    @property
    def observers(self) -> int:
        """The glare observers."""
        return self._native.observers

    @property
    def warnings(self) -> list:
        """What loading worked around."""
        return list(self._native.warnings)

    def __repr__(self) -> str:
        return (f"Scene({self.path!r}, {self.triangles} triangles, {self.luminaires} luminaires, "
                f"{len(self.grids)} grids)")


def _scene_arg(scene):
    """A loaded scene's native object, or the path of a scene file."""
    return scene._native if isinstance(scene, Scene) else os.fspath(scene)


class Luminaire:
    """A luminaire file read into goniolight's full-sphere distribution (cd/klm).

    ``info`` is the dict that ``goniolight ldt info --json`` prints for the file. Made by
    :func:`read`.
    """

    def __init__(self, native: "_native.NativeLuminaire"):
        self._native = native
        self.info: dict = json.loads(native.info_json())
        """What ``goniolight ldt info --json`` prints for the file."""

    @property
    def path(self) -> str:
        """The file's path, as given to :func:`read`."""
        return str(self._native.path())

    @property
    def warnings(self) -> list:
        """What the reader noticed and repaired (decimal commas, missing optional values, …)."""
        return list(self._native.warnings())

    @property
    def c_angles(self) -> np.ndarray:
        """C planes of the full circle, degrees."""
        return np.asarray(self.info["c_angles"], dtype=float)

    @property
    def gamma_angles(self) -> np.ndarray:
        """γ angles, degrees."""
        return np.asarray(self.info["gamma_angles"], dtype=float)

    @property
    def intensities(self) -> np.ndarray:
        """The table, one row per C plane, one column per γ angle, cd/klm."""
        return self._native.intensities()

    def sample(self, c_deg, gamma_deg, interp: str = "catmull-rom") -> np.ndarray:
        """Intensity (cd/klm) at C and γ angles (degrees, broadcast together)."""
        c, g = np.broadcast_arrays(np.asarray(c_deg, dtype=float), np.asarray(gamma_deg, dtype=float))
        flat = self._native.sample(np.ascontiguousarray(c.ravel()), np.ascontiguousarray(g.ravel()), interp)
        return flat.reshape(c.shape)

    def check(self, leave_out: str = "both", downsample: Optional[Sequence[float]] = None,
              reference: Optional[PathLike] = None) -> dict:
        """The interpolation check (as ``goniolight ldt check --json``)."""
        ds = None if downsample is None else (float(downsample[0]), float(downsample[1]))
        ref = None if reference is None else os.fspath(reference)
        return json.loads(self._native.check_json(leave_out, ds, ref))

    def ugr_table(self, shr: float = 0.25, lamp_set: Optional[int] = None) -> dict:
        """The UGR table (CIE 117 formula, CIE 190 tabular method) at spacing ``shr`` × H:
        the dict that ``goniolight ldt ugr --json`` prints (``shr``, ``rooms``,
        ``reflectances``, ``crosswise``, ``endwise`` with ``None`` where a room is not
        tabulated, ``observer_variation``, ``flux_lm``). ``lamp_set`` counts from 1."""
        return json.loads(self._native.ugr_table_json(float(shr), lamp_set))

    def luminance_table(self, lamp_set: Optional[int] = None, gamma_from: int = 65,
                        interp: str = "bilinear") -> dict:
        """The luminance table (cd/m² of the luminous area by C plane 0–345° every 15° and
        γ from ``gamma_from`` every 5° below 90°): the dict that ``goniolight ldt
        luminance --json`` prints, with ``cd_m2`` as a NumPy array (C × γ)."""
        t = json.loads(self._native.luminance_table_json(lamp_set, int(gamma_from), interp))
        t["cd_m2"] = np.asarray(t["cd_m2"], dtype=float)
        return t

    def write(self, path: PathLike) -> None:
        """Writes the file as EULUMDAT, IES, TM-33-23 XML or ATLA S001 JSON, chosen by the
        extension (.ldt, .ies, .xml, .json), as ``goniolight ldt convert`` does."""
        path = os.fspath(path)
        ext = os.path.splitext(path)[1].lower().lstrip(".")
        if ext not in ("ldt", "ies", "xml", "json"):
            raise ValueError(f"{path}: the extension must be .ldt, .ies, .xml or .json")
        _write_text(path, self._native.to_text(ext))

    def losses(self, format: str) -> list:
        """What writing the file as ``format`` (``"ldt"``, ``"ies"``, ``"xml"`` for
        TM-33-23, ``"json"`` for ATLA S001) loses, in words (the notes ``ldt convert``
        prints)."""
        return self._native.losses(format)

    def datasheet(self, out: PathLike, lamp_set: int = 1) -> None:
        """Writes the one-page datasheet (``goniolight ldt report``: summary, polar,
        cartesian and isocandela diagrams, UGR and luminance tables, warnings) as one
        self-contained HTML or SVG file, chosen by the extension."""
        out = os.fspath(out)
        ext = os.path.splitext(out)[1].lower().lstrip(".")
        if ext not in ("html", "htm", "svg"):
            raise ValueError(f"{out}: the extension must be .html or .svg")
        _write_text(out, self._native.datasheet_page(ext == "svg", int(lamp_set)))

    def __repr__(self) -> str:
        i = self.info
        return (f"Luminaire({self.path!r}, {i.get('luminaire_name')!r}, "
                f"{i.get('flux_lm', 0):.0f} lm)")


def read(path: PathLike) -> Luminaire:
    """Reads an ``.ldt``, ``.ies`` or TM-33 / ATLA (``.xml``, ``.json``) file (ValueError
    naming file and line when malformed)."""
    return Luminaire(_native.read(os.fspath(path)))


def _write_text(path: str, text: str) -> None:
    """Writes ``text`` to ``path`` whole or not at all (a temporary file moved into place)."""
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8", newline="") as f:
        f.write(text)
    os.replace(tmp, path)


def datasheet(path: PathLike, out: PathLike, lamp_set: int = 1) -> None:
    """Writes a luminaire file's one-page datasheet (``goniolight ldt report FILE --out
    OUT``): :meth:`Luminaire.datasheet` of :func:`read`."""
    read(path).datasheet(out, lamp_set=lamp_set)


def ugr_table(path: PathLike, shr: float = 0.25, lamp_set: Optional[int] = None) -> dict:
    """The UGR table of a luminaire file (``goniolight ldt ugr --json``):
    :meth:`Luminaire.ugr_table` of :func:`read`."""
    return read(path).ugr_table(shr=shr, lamp_set=lamp_set)


def luminance_table(path: PathLike, lamp_set: Optional[int] = None, gamma_from: int = 65,
                    interp: str = "bilinear") -> dict:
    """The luminance table of a luminaire file (``goniolight ldt luminance --json``):
    :meth:`Luminaire.luminance_table` of :func:`read`."""
    return read(path).luminance_table(lamp_set=lamp_set, gamma_from=gamma_from, interp=interp)


def _iso(t) -> str:
    if isinstance(t, str):
        return t
    if isinstance(t, np.datetime64):
        return str(np.datetime_as_string(t, unit="ms")) + "Z"
    if hasattr(t, "isoformat"):
        return t.isoformat()
    raise TypeError(f"not a time: {t!r}")


def sun_position(lat: float, lon: float, times: Union[str, Iterable], tz: Optional[str] = None,
                 *, elevation: float = 0.0, delta_t: Optional[float] = None,
                 pressure: float = 1013.25, temperature: float = 12.0,
                 north_offset: float = 0.0) -> dict:
    """The sun's position (NREL SPA) at one or many instants.

    ``times``: ISO 8601 strings (with an offset, or local time with ``tz``), ``datetime``
    objects or ``numpy.datetime64`` values (UTC). Returns a dict of NumPy arrays with the
    keys of ``goniolight sun --json``: ``zenith_deg``, ``apparent_zenith_deg``,
    ``elevation_deg``, ``azimuth_deg``, ``direction`` (N × 3), ``delta_t_s``, and ``utc``
    (strings).
    """
    single = isinstance(times, (str, np.datetime64)) or hasattr(times, "isoformat")
    seq = [times] if single else list(np.asarray(times).ravel()) if isinstance(times, np.ndarray) else list(times)
    rows = json.loads(_native.sun_positions_json(
        float(lat), float(lon), [_iso(t) for t in seq], tz, float(elevation), delta_t,
        float(pressure), float(temperature), float(north_offset)))
    out = {k: np.asarray([r[k] for r in rows], dtype=float)
           for k in ("zenith_deg", "apparent_zenith_deg", "elevation_deg", "azimuth_deg",
                     "direction", "delta_t_s")}
    out["utc"] = np.asarray([r["utc"] for r in rows])
    return out


def illuminance(scene: Union[PathLike, Scene], points, *, interp: str = "catmull-rom",
                shadows: Optional[str] = None, cpu: bool = False,
                sky: Optional[str] = None, time: Optional[str] = None,
                return_device: bool = False):
    """Direct illuminance (lux) at points of a scene file.

    ``points``: an N × 6 array of ``x y z nx ny nz`` (metres, world frame). Computed on the
    GPU with the renderer's lighting code; without a GPU adapter (or with ``cpu=True``) by
    the CPU reference, with a RuntimeWarning. ``shadows``: none, paraboloid or volumes
    (default: the scene's). The scene's ``[sky]`` adds daylight (sky, ground and sun through
    the model's openings and glazing, on the CPU); ``sky`` (``"cie-overcast"``,
    ``"cie-clear"``, ``"cie:1"`` … ``"cie:15"``, ``"uniform"``) and ``time`` (local time at
    its ``[site]``) replace its model and time, as ``illuminance --sky --time`` do. With
    ``return_device=True`` also returns ``"gpu"`` or ``"cpu"``.
    """
    pts = np.ascontiguousarray(np.atleast_2d(np.asarray(points, dtype=float)))
    lux, on_gpu = _native.illuminance(_scene_arg(scene), pts, interp, shadows, bool(cpu),
                                      sky, time)
    if return_device:
        return lux, ("gpu" if on_gpu else "cpu")
    return lux


class Radiosity:
    """A radiosity solution of a scene: what ``goniolight radiosity`` solves. Made by
    :func:`radiosity`.

    ``convergence`` is the fraction of the luminaires' first-bounce power that was shot
    when the solver stopped, ``stop_reason`` why it stopped (``"converged"``, ``"shot
    limit reached"``, ``"time budget spent"``, ``"interrupted"``, …).
    """

    def __init__(self, native: "_native.NativeRadiosity"):
        self._native = native

    @property
    def convergence(self) -> float:
        """The converged fraction (0..1) when the solver stopped."""
        return float(self._native.convergence())

    @property
    def stop_reason(self) -> str:
        """Why the solver stopped."""
        return str(self._native.stop_reason())

    @property
    def elements(self) -> int:
        """Elements (light-map texels) of the solution."""
        return int(self._native.sizes()[0])

    @property
    def log(self) -> dict:
        """The convergence log (``convergence.csv`` of ``goniolight radiosity``) as a dict
        of arrays: ``shot``, ``seconds``, ``unshot_lm``, ``convergence``."""
        rows = [line.split(",") for line in self._native.convergence_csv().splitlines()[1:]]
        cols = {"shot": 0, "seconds": 1, "unshot_lm": 3, "convergence": 4}
        return {k: np.asarray([float(r[i]) for r in rows]) for k, i in cols.items()}

    def lux(self, points) -> np.ndarray:
        """Total illuminance (lux: the luminaires' direct light with its shadows, what
        mirrors and clear glass pass on, and the interreflected light) at an N × 6 array
        of ``x y z nx ny nz``: what ``goniolight radiosity SCENE --points`` prints."""
        return self._native.lux(_points(points))

    def interreflected_lux(self, points) -> np.ndarray:
        """The interreflected illuminance alone (lux) at an N × 6 array of points."""
        return self._native.interreflected_lux(_points(points))

    def export(self, path: PathLike, bake: str = "auto", bake_budget: Optional[int] = None) -> None:
        """Writes the solved scene as glTF 2.0 binary (``radiosity --export``): each
        surface light-mapped or vertex-lit as ``bake`` (auto, map or vertex) chooses."""
        self._native.export(os.fspath(path), bake, bake_budget)

    def __repr__(self) -> str:
        return (f"Radiosity({self.elements} elements, {100 * self.convergence:.2f} % "
                f"converged, {self.stop_reason})")


def _points(points) -> np.ndarray:
    return np.ascontiguousarray(np.atleast_2d(np.asarray(points, dtype=float)))


def radiosity(scene: Union[PathLike, Scene], *, converge: float = 0.99, max_shots: Optional[int] = None,
              time_limit: Optional[float] = None, texel_density: float = 10.0, level: int = 2,
              adaptive: int = 0, adaptive_share: Sequence[float] = (0.0, 1.0),
              visibility: str = "hemicube", map_size: int = 256, raster: str = "auto",
              hierarchy: str = "clusters", cell_power: float = 1e-3, link_error: float = 0.05,
              form_factor: str = "polygon", ambient: str = "display", drive: str = "global",
              fov_margin: float = 10.0, interp: Optional[str] = None,
              shadows: Optional[str] = None, progress=None) -> Radiosity:
    """Solves a scene file's interreflected light on the GPU, as ``goniolight radiosity``
    does: every keyword is the command's flag of that name, with its default.

    ``interp`` and ``shadows`` default to the scene's ``[display]``. ``progress``, if
    given, is called as ``progress(shot, convergence)`` before each shot. Ctrl-C (or
    Jupyter's interrupt) during the preparation raises KeyboardInterrupt; during the
    shooting it stops the solver and returns the solution so far (``stop_reason`` is
    ``"interrupted"``). Bad options and scenes raise ValueError naming the option or the
    file.

    >>> import goniolight
    >>> sol = goniolight.radiosity("assets/scenes/box_room.toml", converge=0.9, texel_density=4)
    >>> sol.stop_reason, sol.convergence >= 0.9
    ('converged', True)
    >>> bool(sol.lux([[1, 1, 0.8, 0, 0, 1]])[0] > 33.0)
    True
    """
    options = {
        "converge": converge, "max_shots": max_shots, "time_limit": time_limit,
        "texel_density": texel_density, "level": level, "adaptive": adaptive,
        "adaptive_share": [float(v) for v in adaptive_share], "visibility": visibility,
        "map_size": map_size, "raster": raster, "hierarchy": hierarchy,
        "cell_power": cell_power, "link_error": link_error, "form_factor": form_factor,
        "ambient": ambient, "drive": drive, "fov_margin": fov_margin,
    }
    native = _native.radiosity(_scene_arg(scene), json.dumps(options), interp, shadows, progress)
    return Radiosity(native)


def calc(scene: Union[PathLike, Scene], *, maintenance_factor: Optional[float] = None, cpu: bool = False,
         interp: str = "catmull-rom", shadows: str = "volumes", indirect: Optional[str] = None,
         max_points: Optional[int] = None, solver: Optional[dict] = None,
         progress=None, emergency: bool = False) -> dict:
    """The scene's calculation surfaces and observers, as ``goniolight calc`` computes
    them: the dict of its ``calc.json`` (``grids`` with ``em``, ``emin``, ``emax``,
    ``u0``, ``g2``, …; ``observers`` with ``ugr``; ``requirements``, the verdicts of the
    scene's EN 12464-1 areas; ``method``; ``indirect``, ``convergence``), each
    grid also with ``values`` (the maintained lux at its points, a NumPy array in the
    order of its CSV). Keywords are the command's flags: ``maintenance_factor`` (default
    the scene's), ``cpu``, ``interp``, ``shadows``, ``indirect`` (``"none"`` or
    ``"radiosity"``; default the scene's), ``max_points``, ``emergency`` (EN 1838: the
    luminaires at their emergency output, direct light, the ``[[emergency]]`` areas
    judged); ``solver`` is a dict of :func:`radiosity`'s options for the interreflected
    light; ``progress(shot, convergence)`` sees its solve.

    >>> import goniolight
    >>> doc = goniolight.calc("assets/scenes/box_room_calc.toml",
    ...                       solver={"converge": 0.9, "texel_density": 4})
    >>> [g["name"] for g in doc["grids"]][:2]
    ['work plane', 'cylindrical 1.2 m']
    >>> bool(doc["grids"][0]["values"].min() == doc["grids"][0]["emin"])
    True
    """
    text, values = _native.calc_json(
        _scene_arg(scene), maintenance_factor, bool(cpu), interp, shadows, indirect,
        max_points, json.dumps(solver or {}), progress, bool(emergency))
    doc = json.loads(text)
    for grid, v in zip(doc["grids"], values):
        grid["values"] = np.asarray(v, dtype=float)
    return doc


def sunlight(scene: Union[PathLike, Scene], *, baseline: Union[PathLike, Scene, None] = None,
             weather: Optional[PathLike] = None, date=None, en17037_date=None,
             year: Optional[int] = None, step: float = 5.0, min_elevation: float = 0.0,
             points: Optional[PathLike] = None, areas: Optional[PathLike] = None,
             area_spacing: float = 0.25) -> dict:
    """The planning tests of the scene's ``[[window]]`` and ``[[open_space]]`` tables, as
    ``goniolight sunlight`` runs them: the dict of its ``sunlight.json`` (``windows``
    with ``vsc``, ``apsh``, ``wpsh``, ``en17037_hours``, ``en17037_rating``, ``baseline``
    and ``pass``; ``areas`` with ``sunlit_fraction_2h`` and ``pass``; ``method``), each
    area also with ``hours`` (its points' hours of sun on the day, a NumPy array in the
    order of its CSV). Keywords are the command's flags: ``baseline`` (the existing
    situation's scene), ``weather`` (an EPW file, for APSH and WPSH), ``date`` and
    ``en17037_date`` (``"2026-03-21"`` or a ``datetime.date``), ``year``, ``step``
    (minutes), ``min_elevation`` (degrees), ``points`` (a ``profile --points`` file of
    more windows), ``areas`` (a GeoJSON file of more open spaces, as ``profile --areas``)
    and ``area_spacing`` (metres between their points). Bad input raises ValueError naming the keyword or the scene key.

    >>> import goniolight
    >>> doc = goniolight.sunlight("assets/scenes/sunlight_site.toml",
    ...                           baseline="assets/scenes/sunlight_site_existing.toml",
    ...                           year=2026)
    >>> w = doc["windows"][0]
    >>> w["name"], w["vsc"], w["baseline"]["vsc"], w["pass"]["vsc"]
    ('flat A ground floor', 26.5, 39.62, False)
    >>> doc["areas"][0]["hours"].shape
    (4800,)
    """
    def day(d):
        return None if d is None else (d if isinstance(d, str) else d.isoformat())

    text, hours = _native.sunlight_json(
        _scene_arg(scene), None if baseline is None else _scene_arg(baseline),
        None if weather is None else os.fspath(weather), day(date), day(en17037_date), year,
        float(step), float(min_elevation), None if points is None else os.fspath(points),
        None if areas is None else os.fspath(areas), float(area_spacing))
    doc = json.loads(text)
    for area, h in zip(doc["areas"], hours):
        area["hours"] = np.asarray(h, dtype=float)
    return doc


def _hhmm(t) -> str:
    return t if isinstance(t, str) else t.strftime("%H:%M")


def _site(site):
    """(latitude, longitude, timezone, north_offset_deg) of a ``[site]``-style dict or a
    (latitude, longitude) pair."""
    if isinstance(site, dict):
        unknown = set(site) - {"latitude", "longitude", "timezone", "north_offset_deg"}
        if unknown:
            raise ValueError(f"site: unknown key(s) {sorted(unknown)}; expected latitude, "
                             "longitude, timezone, north_offset_deg")
        try:
            return (float(site["latitude"]), float(site["longitude"]), site.get("timezone"),
                    float(site.get("north_offset_deg", 0.0)))
        except KeyError as e:
            raise ValueError(f"site: {e.args[0]} is missing") from None
    lat, lon = site
    return float(lat), float(lon), None, 0.0


class SunStudy:
    """A sun study of a model over one or more dates (what ``goniolight profile``
    computes): per date the hours of sun or shadow on the plan, its ``study.json``
    numbers (passing fractions, facades, window points), and every file the command
    writes."""

    def __init__(self, native: "_native.NativeSunStudy"):
        self._native = native

    @property
    def dates(self) -> list:
        """The dates, ``YYYY-MM-DD``, in order."""
        return self._native.dates()

    @property
    def studies(self) -> list:
        """Each date's ``study.json`` as a dict (the command's keys)."""
        return [json.loads(self._native.study_json(k)) for k in range(len(self.dates))]

    @property
    def warnings(self) -> list:
        """What the study warned about (also raised as UserWarnings)."""
        return self._native.warnings()

    def hours(self, date: int = 0) -> np.ndarray:
        """Hours per plan cell of date number ``date`` (a resolution × resolution array,
        row 0 at the plan's +y edge; NaN where the plan sees neither ground nor model)."""
        return self._native.hours(date)

    def cells(self, date: int = 0) -> np.ndarray:
        """The rows of ``hours.csv`` of date number ``date``: an N × 3 array of x, y (the
        model file's plan coordinates, metres) and hours."""
        return self._native.cells(date)

    def plan(self, date: int = 0) -> dict:
        """The plan's corner at row 0, column 0 (``x``, ``y`` of its outer corner, metres),
        its side ``extent_m`` and ``resolution`` (pixels per side)."""
        (x, y), extent, resolution = self._native.plan(date)
        return {"x": x, "y": y, "extent_m": extent, "resolution": resolution}

    def write(self, out: PathLike, step_images: bool = False) -> None:
        """Writes what ``goniolight profile --out OUT`` writes (plans, rasters, tables,
        ``study.json``, sun-path diagrams; a folder per date and ``dates.csv`` when there
        are several): complete or nothing."""
        self._native.write(os.fspath(out), bool(step_images))

    def __repr__(self) -> str:
        return f"SunStudy({len(self.dates)} date(s): {', '.join(self.dates)})"


def sun_study(model: PathLike, site, dates, *, start="08:00", end="16:00", step: int = 60,
              north_offset: Optional[float] = None, extent: Optional[float] = None,
              resolution: int = 1024, up: str = "y", silhouettes: str = "hextree",
              metric: str = "shadow", threshold: Optional[float] = None,
              areas: Optional[PathLike] = None, casters: Sequence[str] = (),
              facades: bool = False, facade_cell: float = 0.5, min_facade_area: float = 1.0,
              points: Optional[PathLike] = None, min_elevation: float = 0.0,
              model_view: bool = False, view_from: Optional[Sequence[float]] = None,
              view_at: Optional[Sequence[float]] = None,
              view_size: Sequence[int] = (1200, 900), progress=None) -> SunStudy:
    """A sun study of an OBJ or glTF model, as ``goniolight profile`` runs it: the keywords are
    its flags (``start``/``end`` are ``--from``/``--to``, ``step`` minutes).

    ``site`` is a dict with the scene file's ``[site]`` keys (``latitude``,
    ``longitude``, ``timezone``, ``north_offset_deg``) or a ``(latitude, longitude)``
    pair (then the times are UTC); ``north_offset`` overrides the site's.
    ``dates`` is a date (``"2026-03-21"`` or a ``datetime.date``) or several.
    ``progress(done, total)`` is called after each step; Ctrl-C (Jupyter's interrupt)
    raises KeyboardInterrupt. Bad options raise ValueError naming the option.

    >>> import goniolight
    >>> s = goniolight.sun_study("assets/models/box.obj",
    ...                          {"latitude": 48.21, "longitude": 16.37,
    ...                           "timezone": "Europe/Vienna"},
    ...                          "2026-03-21", up="z", resolution=64, metric="sun")
    >>> s.dates, s.hours().shape
    (['2026-03-21'], (64, 64))
    >>> round(s.studies[0]["period_h"], 1)
    8.0
    """
    lat, lon, tz, site_north = _site(site)
    if isinstance(dates, (str, bytes)) or not isinstance(dates, Iterable):
        dates = [dates]
    dates = [d if isinstance(d, str) else d.isoformat() for d in dates]
    view = None
    if model_view:
        view = (None if view_from is None else [float(v) for v in view_from],
                None if view_at is None else [float(v) for v in view_at],
                tuple(int(v) for v in view_size))
    native = _native.sun_study(
        os.fspath(model), lat, lon, dates, _hhmm(start), _hhmm(end), int(step), tz,
        site_north if north_offset is None else float(north_offset), extent, int(resolution),
        up, silhouettes, metric, threshold, None if areas is None else os.fspath(areas),
        list(casters), (float(facade_cell), float(min_facade_area)) if facades else None,
        None if points is None else os.fspath(points), float(min_elevation), view, progress)
    return SunStudy(native)


class Rendering:
    """One image of a scene (what ``goniolight render`` draws): the picture and, per
    pixel, the linear RGB (cd/m²) and the illuminance (lux)."""

    def __init__(self, native: "_native.NativeRendering"):
        self._native = native

    @property
    def image(self) -> np.ndarray:
        """The picture as ``render --out`` writes it: rows × columns × RGBA, uint8 (in
        false-colour lux with the legend panel beside the view)."""
        return self._native.image()

    @property
    def rgb(self) -> np.ndarray:
        """Per pixel of the view: the linear RGB of the surface seen, cd/m² (rows ×
        columns × 3)."""
        return self._native.rgb()

    @property
    def lux(self) -> np.ndarray:
        """Per pixel of the view: the illuminance on the surface seen, lux (NaN where no
        surface shows)."""
        return self._native.lux()

    @property
    def stats(self) -> dict:
        """What ``render`` reports: ``log_average_luminance``, ``max_luminance``, ``lux``
        (mean, median, percentiles, max over the surfaces in view) and ``lux_max_shown``
        (the top of the false-colour scale)."""
        return json.loads(self._native.stats_json())

    def save(self, png: PathLike, exr: Optional[PathLike] = None) -> None:
        """Writes the picture as PNG and, with ``exr``, the HDR values as ``render --exr``
        does."""
        self._native.save(os.fspath(png), None if exr is None else os.fspath(exr))


def render(scene: Union[PathLike, Scene], *, width: Optional[int] = None, height: Optional[int] = None,
           mode: Optional[str] = None, tonemap: Optional[str] = None,
           exposure: Optional[float] = None, lux_max: Optional[float] = None,
           palette: Optional[str] = None, steps: Optional[int] = None,
           interp: Optional[str] = None, shadows: Optional[str] = None,
           supersample: int = 3, solution: Optional[Radiosity] = None) -> Rendering:
    """Renders a scene file from its camera, as ``goniolight render`` does: the keywords
    are its flags (each absent one takes the scene's ``[display]`` value, then the
    default); ``mode="illuminance"`` draws false-colour lux. With ``solution`` (from
    :func:`radiosity`) the image shows its interreflected light, as ``render --indirect
    radiosity``. A value out of range raises ValueError naming the ``[display]`` key.

    >>> import goniolight
    >>> r = goniolight.render("assets/scenes/box_room.toml", width=64, height=48,
    ...                       mode="illuminance", supersample=1)
    >>> r.lux.shape, r.image.shape[2]
    ((48, 64), 4)
    >>> bool(r.stats["lux"]["max"] > 30)
    True
    """
    over = {k: v for k, v in {
        "width": width, "height": height, "mode": mode, "tonemap": tonemap,
        "exposure": exposure, "lux_max": lux_max, "palette": palette, "steps": steps,
        "interp": interp, "shadows": shadows}.items() if v is not None}
    native = _native.render(_scene_arg(scene), json.dumps(over), int(supersample),
                            None if solution is None else solution._native)
    return Rendering(native)
