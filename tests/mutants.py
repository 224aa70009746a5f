"""Pytest plugin that plants one physics error in the package (``-p mutants``).

``CMTOOL_MUTANT`` names the mutation; each changes one quantity of docs/model.md by 2 % (or a
waviness phase by 2 % of a cycle) where the package computes it, before any test runs.
``benchmarks/mutation_table.py`` runs the suite once per mutation and reports which test
caught it: a suite that passes under a mutation cannot tell that physics from its neighbour.
"""

from __future__ import annotations

import functools
import math
import os

MUTANTS = {
    "contact_constant": "Hertz constants K_i, K_o, K_tot x 1.02 (docs/model.md 3.3)",
    "waviness_phase": "every waviness phase + 2 % of a cycle (docs/model.md 5)",
    "film_thickness": "EHL central film h_c x 1.02 (docs/model.md 4.2)",
    "contact_damping": "dry contact damping time tau x 1.02 (docs/model.md 1.2, 4.4)",
    "squeeze_damping": "squeeze-film damping c_sq x 1.02 (docs/model.md 4.5)",
    "cage_speed": "cage speed omega_c x 1.02 in the kernel (docs/model.md 2)",
}


def _scaled(fn, factor):
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        return fn(*args, **kwargs) * factor

    return wrapper


def pytest_configure(config):
    name = os.environ.get("CMTOOL_MUTANT", "")
    if not name:
        return
    if name not in MUTANTS:
        raise ValueError(f"CMTOOL_MUTANT = {name!r} is not one of {', '.join(MUTANTS)}")
    import generators.contact as contact
    import generators.packing as packing
    import generators.prepared as prepared
    import generators.static as static
    from generators import _kernels as K

    if name == "contact_constant":
        original = contact.load_deflection_constants

        @functools.wraps(original)
        def constants(geometry):
            return tuple(1.02 * k for k in original(geometry))

        for module in (contact, packing, static):
            module.load_deflection_constants = constants
        packing.contact_geometries.cache_clear()
    elif name == "waviness_phase":
        original = prepared.waviness_table

        @functools.wraps(original)
        def table(*args, **kwargs):
            wav = original(*args, **kwargs).copy()
            rows = wav[:, K.W_SURFACE] <= K.SURF_BALL
            wav[rows, K.W_PHASE] += 0.02 * 2 * math.pi
            return wav

        prepared.waviness_table = table
    elif name == "film_thickness":
        packing.film_thickness = _scaled(packing.film_thickness, 1.02)
    elif name == "squeeze_damping":
        packing.squeeze_film_damping = _scaled(packing.squeeze_film_damping, 1.02)
    else:
        index = {"contact_damping": K.P_CONTACT_DAMPING_TIME, "cage_speed": K.P_CAGE_SPEED}[name]
        original = prepared.pack_parameters

        @functools.wraps(original)
        def pack(*args, **kwargs):
            p = original(*args, **kwargs)
            p[index] *= 1.02
            return p

        prepared.pack_parameters = pack
    config.stash_mutant = name  # noqa: B010 - a marker for the report header


def pytest_report_header(config):
    name = os.environ.get("CMTOOL_MUTANT", "")
    return f"mutant: {name} ({MUTANTS[name]})" if name else None
