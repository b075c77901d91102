"""goniolight for Python: real luminaire files (EULUMDAT ``.ldt``, IES ``.ies``), their
interpolation and its check, the sun's position, and illuminance at points of a scene.

The numbers come from the same library code as the ``goniolight`` command line: ``info``
equals ``goniolight ldt info --json``, ``sample`` equals ``goniolight ldt sample``,
``sun_position`` equals ``goniolight sun --json`` and ``illuminance`` equals
``goniolight illuminance``.

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

__all__ = ["Luminaire", "read", "sun_position", "illuminance", "INTERPOLATIONS"]

#: The interpolation methods, as the command line names them.
INTERPOLATIONS = ("nearest", "bilinear", "catmull-rom", "monotone")

PathLike = Union[str, "os.PathLike[str]"]


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

    def write(self, path: PathLike) -> None:
        """Writes the file as EULUMDAT or IES, chosen by the extension (.ldt or .ies)."""
        path = os.fspath(path)
        ext = os.path.splitext(path)[1].lower().lstrip(".")
        if ext not in ("ldt", "ies"):
            raise ValueError(f"{path}: the extension must be .ldt or .ies")
        text = self._native.to_text(ext)
        tmp = f"{path}.tmp{os.getpid()}"
        with open(tmp, "w", encoding="utf-8", newline="") as f:
            f.write(text)
        os.replace(tmp, path)

    def __repr__(self) -> str:
        i = self.info
        return (f"Luminaire({self.path!r}, {i.get('luminaire_name')!r}, "
                f"{i.get('flux_lm', 0):.0f} lm)")


def read(path: PathLike) -> Luminaire:
    """Reads an ``.ldt`` or ``.ies`` file (ValueError naming file and line when malformed)."""
    return Luminaire(_native.read(os.fspath(path)))


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


def illuminance(scene: PathLike, points, *, interp: str = "catmull-rom",
                shadows: Optional[str] = None, cpu: bool = False,
                return_device: bool = False):
    """Direct illuminance (lux) at points of a scene file.

    ``points``: an N × 6 array of ``x y z nx ny nz`` (metres, world frame). Computed on the
    GPU with the renderer's lighting code; without a GPU adapter (or with ``cpu=True``) by
    the CPU reference, with a RuntimeWarning. ``shadows``: none, paraboloid or volumes
    (default: the scene's). With ``return_device=True`` also returns ``"gpu"`` or ``"cpu"``.
    """
    pts = np.ascontiguousarray(np.atleast_2d(np.asarray(points, dtype=float)))
    lux, on_gpu = _native.illuminance(os.fspath(scene), pts, interp, shadows, bool(cpu))
    if return_device:
        return lux, ("gpu" if on_gpu else "cpu")
    return lux
