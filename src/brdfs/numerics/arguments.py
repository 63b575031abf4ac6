"""Argument checks of the front doors :func:`brdfs.albedo` and :func:`brdfs.model`: before any work,
each bad argument is refused with one line naming the argument and its value.

(Scaffold: issue 25 fills these in.)
"""
from __future__ import annotations


def check_albedo_call(model, theta_deg, method, rtol, atol, options) -> None:
    """Refuse a bad :func:`brdfs.albedo` call (``options``: the method's keyword options)."""


def check_model_call(name, params) -> None:
    """Refuse a bad :func:`brdfs.model` call before any table is computed."""
