"""Tables for renderers: directional albedo E(μ, p) and its cosine-weighted average E_avg(p), certified.

Renderers ship precomputed albedo tables: the directional albedo E(μ) = a(θ), μ = cos θ, for
energy compensation (Kulla & Conty 2017: f_ms = (1 − E(μ_L))(1 − E(μ_V)) / (π (1 − E_avg))) and
for directional-albedo lookups, with

    E_avg = 2 ∫₀¹ E(μ) μ dμ

(the mean albedo, eq. 1.20 / 3.37).  Such tables are usually made by Monte Carlo with errors
around 1e-3; here every cell is the albedo engine's, with its error bound
(:func:`brdfs.albedo_table`), and E_avg is a nested adaptive integration over μ of engine values
(:func:`brdfs.numerics.quantities.mean_albedo_nested`), not a sum over the table's own cells.

The grid: ``p`` from START to STOP inclusive (``numpy.linspace``), μ at the centres of ``n_mu``
equal cells of [0, 1], μ_j = (j + ½)/n_mu, where a texture with linear filtering puts its texels.
The model is built by the front door :func:`brdfs.model` with the other parameters at their
defaults (GGX and Beckmann: F = 1, no index of refraction, as energy compensation assumes).

Formats (:func:`write`): ``npy`` — a NumPy archive (``numpy.load`` reads it whatever the file's
name: ``E``, ``E_error``, ``E_status``, ``E_avg``, ``E_avg_error``, ``mu``, ``param_values`` and
``metadata``, a JSON string); ``csv`` — tidy rows ``quantity, <param>, mu, value, error, status``
after ``#`` lines with the metadata; ``exr`` — E and its error as two channels of an OpenEXR image
(rows: the parameter, columns: μ) with the metadata as header attributes, through Mitsuba's
``Bitmap`` (the optional ``render`` extra).
"""
from __future__ import annotations

import csv
import io
import json
import math
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

FORMATS = ("npy", "csv", "exr")
#: Albedo cells per parameter value (μ) by default: 32, as renderers' compensation tables use.
DEFAULT_MU = 32
#: Relative tolerance of every cell and of E_avg by default.
DEFAULT_RTOL = 1e-10


def parse_sweep(text: str, default_count: int = 32):
    """``"alpha=0.01:1:32"`` -> ``("alpha", array of 32 values from 0.01 to 1)``; ``alpha=0.01:1``
    takes ``default_count`` values.  A ``ValueError`` names the text."""
    key, sep, spec = text.partition("=")
    parts = spec.split(":")
    try:
        if not sep or not key.strip() or len(parts) not in (2, 3):
            raise ValueError
        start, stop = float(parts[0]), float(parts[1])
        count = int(parts[2]) if len(parts) == 3 else default_count
        if not (math.isfinite(start) and math.isfinite(stop)) or count < 1 or (count > 1 and stop <= start) \
                or (len(parts) == 3 and str(count) != parts[2].strip()):
            raise ValueError
    except ValueError:
        raise ValueError(f"--param {text!r}: expected NAME=START:STOP:N (START < STOP, N a positive integer)") from None
    return key.strip(), np.linspace(start, stop, count)


def mu_grid(n_mu: int) -> np.ndarray:
    """μ_j = (j + ½)/n_mu, j = 0 … n_mu − 1: the centres of equal cells of [0, 1]."""
    if int(n_mu) != n_mu or n_mu < 1:
        raise ValueError(f"--mu {n_mu!r}: expected a positive integer")
    return (np.arange(int(n_mu)) + 0.5) / int(n_mu)


def theta_of_mu(mu) -> np.ndarray:
    """θ in degrees with cos θ = μ, to the rounding of μ (arctan2, not arccos)."""
    mu = np.asarray(mu, float)
    return np.degrees(np.arctan2(np.sqrt((1.0 - mu) * (1.0 + mu)), mu))


@dataclass(frozen=True)
class AlbedoLUT:
    """E(μ, p) (shape (len(param_values), len(mu))) and E_avg(p), each with its error bound."""

    model: str
    param: str
    param_values: np.ndarray
    mu: np.ndarray
    E: np.ndarray
    E_error: np.ndarray
    E_status: np.ndarray
    E_avg: np.ndarray
    E_avg_error: np.ndarray
    E_avg_status: np.ndarray
    rtol: float
    fixed: dict = field(default_factory=dict)

    @property
    def converged(self) -> bool:
        return bool(np.all(self.E_status == "converged") and np.all(self.E_avg_status == "converged"))

    def metadata(self) -> dict:
        import brdfs
        return {"generator": "brdfs lut", "version": brdfs.__version__, "model": self.model,
                "param": self.param, "fixed_params": {k: v for k, v in self.fixed.items()},
                "param_values": [float(v) for v in self.param_values], "n_mu": int(self.mu.size),
                "mu": "(j + 0.5) / n_mu", "rtol": self.rtol,
                "E": "directional albedo a(theta), mu = cos theta, rows: param, columns: mu",
                "E_avg": "2 * integral_0^1 E(mu) mu dmu (nested adaptive integration, not the table's cells)",
                "max_E_error": float(np.max(self.E_error)), "max_E_avg_error": float(np.max(self.E_avg_error)),
                "converged": self.converged}


def albedo_lut(model_name: str, param: str, values, n_mu: int = DEFAULT_MU, rtol: float = DEFAULT_RTOL,
               fixed: dict | None = None) -> AlbedoLUT:
    """The table of model ``model_name`` over ``param`` = ``values`` (other parameters ``fixed``)."""
    import brdfs
    from brdfs.numerics.quantities import mean_albedo_nested

    fixed = dict(fixed or {})
    if param in fixed:
        raise ValueError(f"--param {param}: given as the swept parameter and as a fixed one")
    values = np.asarray(values, float)
    mu = mu_grid(n_mu)
    models = [brdfs.model(model_name, **fixed, **{param: float(v)}) for v in values]
    table = brdfs.albedo_table(models, theta_of_mu(mu), rtol=rtol)
    average = mean_albedo_nested(models, rtol=rtol)
    avg_status = np.asarray(getattr(average, "status", np.full(values.shape, "converged")), str)
    return AlbedoLUT(model_name, param, values, mu, np.asarray(table.value), np.asarray(table.error),
                     np.asarray(table.status, str), np.asarray(average.value), np.asarray(average.error),
                     np.broadcast_to(avg_status, values.shape).copy(), float(rtol), fixed)


def write(lut: AlbedoLUT, path, fmt: str | None = None) -> Path:
    """Write ``lut`` to ``path`` in ``fmt`` (default: from the suffix, else ``npy``)."""
    path = Path(path)
    fmt = fmt or (path.suffix.lstrip(".").lower() if path.suffix.lstrip(".").lower() in FORMATS else "npy")
    if fmt not in FORMATS:
        raise ValueError(f"--format {fmt!r}: choose one of {', '.join(FORMATS)}")
    {"npy": _write_npy, "csv": _write_csv, "exr": _write_exr}[fmt](lut, path)
    return path


def _write_npy(lut, path):
    arrays = {"E": lut.E, "E_error": lut.E_error, "E_status": lut.E_status, "E_avg": lut.E_avg,
              "E_avg_error": lut.E_avg_error, "mu": lut.mu, "param_values": lut.param_values,
              "metadata": np.array(json.dumps(lut.metadata()))}
    buffer = io.BytesIO()
    np.savez(buffer, **arrays)                 # to a buffer: np.savez would append .npz to a name
    path.write_bytes(buffer.getvalue())


def _write_csv(lut, path):
    with path.open("w", newline="") as f:
        for key, value in lut.metadata().items():
            f.write(f"# {key}: {json.dumps(value)}\n")
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(["quantity", lut.param, "mu", "value", "error", "status"])
        for i, p in enumerate(lut.param_values):
            for j, mu in enumerate(lut.mu):
                writer.writerow(["E", repr(float(p)), repr(float(mu)), repr(float(lut.E[i, j])),
                                 repr(float(lut.E_error[i, j])), lut.E_status[i, j]])
            writer.writerow(["E_avg", repr(float(p)), "", repr(float(lut.E_avg[i])), repr(float(lut.E_avg_error[i])),
                             lut.E_avg_status[i]])


def _write_exr(lut, path):
    try:
        import mitsuba as mi
    except ImportError:
        raise ValueError("--format exr: needs Mitsuba 3 (the optional extra: pip install 'brdfs[render]')") from None
    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    pixels = np.ascontiguousarray(np.stack([lut.E, lut.E_error], -1), dtype=np.float32)
    bitmap = mi.Bitmap(pixels, mi.Bitmap.PixelFormat.MultiChannel, ["E", "E_error"])
    meta = bitmap.metadata()
    for key, value in lut.metadata().items():
        meta[f"brdfs_{key}"] = value if isinstance(value, str) else json.dumps(value)
    meta["brdfs_E_avg"] = json.dumps([float(v) for v in lut.E_avg])
    meta["brdfs_E_avg_error"] = json.dumps([float(v) for v in lut.E_avg_error])
    bitmap.write(str(path), mi.Bitmap.FileFormat.OpenEXR)


def read(path) -> dict:
    """A table :func:`write` wrote in ``npy`` or ``csv``: the arrays and ``metadata`` (a dict)."""
    path = Path(path)
    if zipfile.is_zipfile(path):
        with np.load(path) as archive:
            out = {k: archive[k] for k in archive.files}
        out["metadata"] = json.loads(str(out["metadata"]))
        return out
    lines = path.read_text().splitlines()
    meta = {}
    for line in lines:
        if not line.startswith("# "):
            break
        key, _, value = line[2:].partition(": ")
        meta[key] = json.loads(value)
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    param, n_mu = meta["param"], meta["n_mu"]
    cells = [r for r in rows if r["quantity"] == "E"]
    averages = [r for r in rows if r["quantity"] == "E_avg"]
    shape = (len(averages), n_mu)
    return {"E": np.array([float(r["value"]) for r in cells]).reshape(shape),
            "E_error": np.array([float(r["error"]) for r in cells]).reshape(shape),
            "E_avg": np.array([float(r["value"]) for r in averages]),
            "E_avg_error": np.array([float(r["error"]) for r in averages]),
            "mu": np.array([float(r["mu"]) for r in cells[:n_mu]]),
            "param_values": np.array([float(r[param]) for r in averages]), "metadata": meta}


__all__ = ["AlbedoLUT", "albedo_lut", "parse_sweep", "mu_grid", "write", "read", "FORMATS"]
