"""Alternative readings of Table 1.2's inputs, each evaluated with eq. 1.40.

For every metal: the inputs as printed; every transposition of two adjacent
digits of ``n`` and of ``k`` (the decimal point kept in place); and the four
corners ``n +- h_n``, ``k +- h_k`` of the printed rounding intervals (``h`` half
a unit of the last printed digit). The readings use no printed output: the
comparison ``metal_a0`` picks the one, if any, that reproduces a print.
"""

from __future__ import annotations

from decimal import Decimal

import pandas as pd

from brdfs.pipeline import plotting
from brdfs.pipeline.registry import table
from brdfs.artifacts.table_1_2_metal_reflectance import a0_percent


def adjacent_transpositions(printed: str) -> list[str]:
    """Distinct numbers obtained by swapping two adjacent digits of ``printed``.

    Examples
    --------
    >>> adjacent_transpositions("4.58"), adjacent_transpositions("0.331")
    (['5.48', '4.85'], ['3.031', '0.313'])
    """
    digits = [i for i, c in enumerate(printed) if c.isdigit()]
    swapped = []
    for i, j in zip(digits, digits[1:]):
        chars = list(printed)
        chars[i], chars[j] = chars[j], chars[i]
        text = "".join(chars)
        if text != printed and text not in swapped:
            swapped.append(text)
    return swapped


def rounding_corners(printed_re: str, printed_im: str) -> list[tuple[str, str]]:
    """The corners of the rounding intervals of two printed decimals.

    Examples
    --------
    >>> rounding_corners("2.06", "4.26")[0]
    ('2.055', '4.255')
    """

    def ends(printed: str) -> tuple[str, str]:
        value = Decimal(printed)
        half = Decimal((0, (5,), value.as_tuple().exponent - 1))
        return str(value - half), str(value + half)

    return [(re, im) for re in ends(printed_re) for im in ends(printed_im)]


def _readings(ior_re: float, ior_im: float) -> list[tuple[str, str, str]]:
    """``(reading, n, k)`` for the printed inputs (their shortest decimal reprs)."""
    n, k = str(float(ior_re)), str(float(ior_im))
    return [
        ("printed", n, k),
        *(("transposed_ior_re", t, k) for t in adjacent_transpositions(n)),
        *(("transposed_ior_im", n, t) for t in adjacent_transpositions(k)),
        *(("rounding_corner", re, im) for re, im in rounding_corners(n, k)),
    ]


@table("extra_metal_a0_readings", config=("metal_reflectance",), chapter=1)
def compute(cfg: dict, deps: dict[str, pd.DataFrame]) -> pd.DataFrame:
    """Eq. 1.40 under each reading of each metal's inputs.

    Returns
    -------
    pandas.DataFrame
        Columns ``metal, reading, ior_re, ior_im, a0_percent, a0_percent_err``;
        ``reading`` is ``printed``, ``transposed_ior_re``, ``transposed_ior_im``
        or ``rounding_corner``.
    """
    records = [
        {"metal": metal["name"], "reading": reading, "ior_re": float(n), "ior_im": float(k)}
        for metal in cfg["metal_reflectance"]["metals"]
        for reading, n, k in _readings(metal["ior_re"], metal["ior_im"])
    ]
    df = pd.DataFrame.from_records(records)
    value, err = a0_percent(df["ior_re"].to_numpy(), df["ior_im"].to_numpy())
    return df.assign(a0_percent=value, a0_percent_err=err)


def plot(df: pd.DataFrame, path) -> None:
    """The readings as a table."""
    shown = df[["metal", "reading", "ior_re", "ior_im"]].astype(str).assign(
        **{"a0 eq. 1.40 [%]": [f"{v:.3f}" for v in df["a0_percent"]]}
    )
    plotting.save_table_png(shown, path, "Readings of Table 1.2's inputs n, k, each through eq. 1.40")
