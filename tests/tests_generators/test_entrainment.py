"""The film's load at light load (``Rig.film_entrainment_factor``, docs/model.md 4.6)."""

import math

import numpy as np
import pytest

import generators._kernels as K
import generators._static_kernels as SK
from generators import (
    LUBRICANTS,
    OperatingCondition,
    ParameterError,
    Rig,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
    form_waviness,
    simulate,
)
from generators.batches import lanes_supported, simulate_lanes
from generators.contact import (
    entrainment_speed,
    film_thickness,
    hertz_contact,
    rigid_isoviscous_coefficient,
)
from generators.packing import ENTRAINED_GAP_NODES, ENTRAINED_PASSES, FILM_TABLE_NODES
from generators.prepared import prepare

CHANNEL = "housing_acceleration_y"


def _packed(factor: float = 1.0, rpm: float = 1800.0) -> np.ndarray:
    """The 6205's parameter vector at 500 N as packed for the kernels (massless balls)."""
    return prepare(
        bearing("6205"),
        OperatingCondition.from_rpm(rpm, 500.0),
        rig=Rig(film_entrainment_factor=factor),
        settings=SimulationSettings(fs=12000.0, duration=0.01),
    ).p


def _film_parameters(factor: float = 1.0, rpm: float = 1800.0):
    """The 6205's series-contact film parameters as packed for the kernels (massless balls)."""
    p = _packed(factor, rpm)
    return (
        p[K.P_K_SERIES],
        p[K.P_CONTACT_DAMPING_TIME],
        p[K.P_FILM_INNER] + p[K.P_FILM_OUTER],
        p[K.P_SQUEEZE_SERIES],
        p[K.P_FILM_LOAD_FLOOR],
        p[K.P_FILM_INNER_REF] + p[K.P_FILM_OUTER_REF],
        p[K.P_FILM_INNER_MAX] + p[K.P_FILM_OUTER_MAX],
        p[K.P_ENTRAINMENT_SERIES],
    )


def test_rigid_isoviscous_load_is_the_ehl_films_order_at_light_load():
    """At 5 N the rigid-isoviscous film (C / Q)^2 lies under Hamrock-Dowson's EHL film (which
    piezoviscosity thickens) but within a factor of three of it, at both races of a 6205 at
    1800 rpm in VG 68; C grows with the entrainment speed as u and C^2 with the film factor."""
    g = bearing("6205")
    u = entrainment_speed(g, 30.0)
    for race in ("inner", "outer"):
        contact = hertz_contact(g, race)
        c = rigid_isoviscous_coefficient(contact, LUBRICANTS["VG68"], u)
        rigid = (c / 5.0) ** 2
        ehl = film_thickness(contact, LUBRICANTS["VG68"], u, 5.0)
        assert ehl / 3.0 < rigid < ehl, (race, rigid, ehl)
        twice = rigid_isoviscous_coefficient(contact, LUBRICANTS["VG68"], 2.0 * u)
        assert twice == pytest.approx(2.0 * c, rel=1e-12)
    grease = LUBRICANTS["grease"]
    contact = hertz_contact(g, "inner")
    ratio = rigid_isoviscous_coefficient(contact, grease, u) ** 2 / (
        (grease.viscosity * u) ** 2 * contact.geometry.rx**3
    )
    plain = rigid_isoviscous_coefficient(contact, LUBRICANTS["VG68"], u) ** 2 / (
        (LUBRICANTS["VG68"].viscosity * u) ** 2 * contact.geometry.rx**3
    )
    assert ratio == pytest.approx(plain * grease.film_factor, rel=1e-12)


def test_the_entrained_film_has_no_onset_and_meets_both_regimes():
    """Apart, the series contact carries C / sqrt(g) at a gap g far beyond the EHL film; under
    load it is the EHL contact of docs/model.md 4.3; in between it rises smoothly, where the
    film law without entrainment is zero up to its onset at -h_max."""
    k, tau, film, squeeze, floor, h_ref, h_max, c2 = _film_parameters()
    assert c2 > 0.0
    gap = 100e-6
    q = K._entrained_film(-gap, 0.0, k, tau, film, squeeze, floor, c2)
    assert q == pytest.approx(math.sqrt(c2 / gap), rel=0.01)  # h_max (0.9 um) is 1 % of g
    for delta in (5e-6, 10e-6):  # 60 N and 400 N through the series contact
        q = K._entrained_film(delta, 0.0, k, tau, film, squeeze, floor, c2)
        plain = K._hertz_ehl(delta, 0.0, k, tau, film, squeeze, floor, h_ref, h_max)
        exact = K._entrained_film(delta, 0.0, k, tau, film, squeeze, floor, 1e-300)
        assert q == pytest.approx(exact, rel=1e-3) and exact == pytest.approx(plain, rel=1e-4)
    deltas = np.linspace(-10e-6, 2e-6, 601)
    loads = np.array([K._entrained_film(d, 0.0, k, tau, film, squeeze, floor, c2) for d in deltas])
    plain = np.array(
        [K._hertz_ehl(d, 0.0, k, tau, film, squeeze, floor, h_ref, h_max) for d in deltas]
    )
    assert np.all(loads > 0.0) and np.all(np.diff(loads) > 0.0)
    assert np.all(plain[deltas < -h_max] == 0.0)  # the onset the entrainment removes
    # smooth: the second difference of the load stays bounded across the old onset
    curvature = np.abs(np.diff(loads, 2))
    assert curvature.max() < 10.0 * np.median(curvature[-50:])
    # each load solves the composite film equation
    for d, q in zip(deltas[::60], loads[::60], strict=True):
        h = film * (q + floor) ** K.FILM_EXPONENT + c2 / q**2
        assert (q / k) ** (2.0 / 3.0) - h == pytest.approx(d, abs=1e-15)


def test_entrainment_needs_the_film_and_massless_balls_and_runs_its_own_film_mode():
    """Refused, by name, in scene full and without the film; its runs take the kernels' own
    film mode, in the lanes too in scene shaft+housing."""
    g = bearing("6205")
    op = OperatingCondition.from_rpm(1800.0, 500.0)
    rig = Rig(film_entrainment_factor=0.5)
    settings = SimulationSettings(fs=12000.0, duration=0.01)
    for scene in (Scene(level="full", ehl=True), Scene(level="shaft+housing", ehl=False)):
        with pytest.raises(ParameterError, match="film_entrainment_factor = 0.5"):
            prepare(g, op, scene=scene, rig=rig, settings=settings)
    entrained = prepare(g, op, rig=rig, settings=settings)
    plain = prepare(g, op, settings=settings)
    assert lanes_supported(entrained) and lanes_supported(plain)
    # scene shaft with it runs one signal at a time (its lane kernel is not compiled)
    shaft = Scene(level="shaft")
    assert not lanes_supported(prepare(g, op, scene=shaft, rig=rig, settings=settings))
    assert lanes_supported(prepare(g, op, scene=shaft, settings=settings))
    assert (entrained.film_mode, plain.film_mode) == (K.FILM_ENTRAINED, K.FILM_EHL)
    with pytest.raises(ParameterError, match="film_entrainment_factor"):
        Rig(film_entrainment_factor=1.5)


def test_the_entrained_table_reads_the_law_newton_solves():
    """The kernels read the composite law from a table (``packing._entrained_film_table``):
    across the gap (to 0.1 mm), the onset region and the Hertz regime (to 30 um of approach),
    the force with and without a rate is within 1e-8 of the Newton solution (or of 1 N, for
    the light loads); beyond the table's reach into the gap the kernel is the Newton solution
    itself."""
    for factor, rpm in ((1.0, 1800.0), (0.3, 900.0)):
        p = _packed(factor, rpm)
        k, tau, film, squeeze, floor, _, h_max, c2 = _film_parameters(factor, rpm)
        rng = np.random.default_rng(4)
        deltas = np.concatenate(
            [
                -(10.0 ** rng.uniform(-9.0, -4.0, 400)),
                rng.uniform(-3.0 * h_max, h_max, 400),
                10.0 ** rng.uniform(-9.0, -4.5, 400),
            ]
        )
        for delta in deltas:
            for rate in (0.0, 2e-3, -2e-3):
                law = K._entrained_film(delta, rate, k, tau, film, squeeze, floor, c2)
                read = K._entrained_table(delta, rate, k, tau, film, squeeze, floor, c2, h_max, p)
                assert abs(read - law) <= 1e-8 * max(law, 1.0), (delta, rate, read, law)
        reach = (p[K.P_ENTRAINED_ORIGIN] * p[K.P_ENTRAINED_STEP]) ** 2  # [m] into the gap
        assert 5e-5 < reach < 1e-3
        far = -h_max - 1.01 * reach
        law = K._entrained_film(far, 1e-3, k, tau, film, squeeze, floor, c2)
        assert K._entrained_table(far, 1e-3, k, tau, film, squeeze, floor, c2, h_max, p) == law


def _entrained_residual(log_q, delta, k, film, floor, c2):
    """(Q / K)^(2/3) - film (Q + floor)^e - C^2 / Q^2 - delta [m], as the table's law in numpy."""
    q = np.exp(log_q)
    return (q / k) ** (2 / 3) - film * (q + floor) ** K.FILM_EXPONENT - c2 / q**2 - delta


def _numpy_is_libm(k, floor):
    """Whether numpy's array exp and pow give the C library's bits (numba's) on this host."""
    v = np.linspace(-40.0, 50.0, 1001)
    q = np.exp(v)
    elastic, ehl = (q / k) ** (2 / 3), (q + floor) ** K.FILM_EXPONENT
    libm = [math.exp(x) for x in v]
    return (
        q.tolist() == libm
        and elastic.tolist() == [(x / k) ** (2 / 3) for x in libm]
        and ehl.tolist() == [(x + floor) ** K.FILM_EXPONENT for x in libm]
    )


def test_the_entrained_tables_bisection_is_the_laws_to_the_bit():
    """The entrained table's loads (``_static_kernels._entrained_bisection``: its halvings far
    from the root decided by the root's side) are the bisection by the law alone, halving by
    halving, from the gap's far end through the Hertz regime, at film factors 0.01-1 and
    300-12,000 rpm and with 64 and 20 halvings: the same bits where numpy's exp and pow are the
    C library's (this project's hosts), within 1e-13 elsewhere."""
    e = K.FILM_EXPONENT
    for factor, rpm in ((1.0, 1800.0), (0.3, 900.0), (0.01, 300.0), (1.0, 12000.0)):
        p = _packed(factor, rpm)
        k, _, film, _, floor, _, h_max, c2 = _film_parameters(factor, rpm)
        step = p[K.P_ENTRAINED_STEP]
        s = step * (np.arange(ENTRAINED_GAP_NODES + FILM_TABLE_NODES) - ENTRAINED_GAP_NODES)
        delta = np.sign(s) * s**2 - h_max
        exact = _numpy_is_libm(k, floor)
        for passes in (ENTRAINED_PASSES, 20):
            log_q = np.empty(delta.size)
            SK._entrained_bisection(delta, k, film, floor, c2, e, passes, log_q)
            lo, hi = np.full(delta.size, -40.0), np.full(delta.size, 50.0)
            for _ in range(passes):
                mid = 0.5 * (lo + hi)
                above = _entrained_residual(mid, delta, k, film, floor, c2) > 0.0
                hi, lo = np.where(above, mid, hi), np.where(above, lo, mid)
            reference = 0.5 * (lo + hi)
            if exact:
                assert np.array_equal(log_q, reference), (factor, rpm, passes)
            else:
                assert np.allclose(np.exp(log_q), np.exp(reference), rtol=1e-13, atol=0.0)


def test_entrained_runs_in_lanes_are_simulates_and_do_not_depend_on_their_block():
    """Wavy 6205s with the film's entrainment (three speeds and loads, 5 um clearance) in
    scene shaft+housing: the lanes give what :func:`simulate` gives (to 1e-9 of the peak, as
    the plain film's lanes), and a run's bytes do not depend on its place in a block."""
    g = bearing("6205", radial_internal_clearance=5e-6)
    rig = Rig(film_entrainment_factor=1.0)
    scene = Scene(level="shaft+housing", ehl=True)
    settings = SimulationSettings(fs=6400.0, duration=0.05, settle_time=0.02, channels=(CHANNEL,))
    cases = [
        (
            OperatingCondition.from_rpm(900 + 450 * i, 100 + 200 * i),
            Waviness(surface="inner", order=9, amplitude=5e-7),
        )
        for i in range(3)
    ]
    preps = [
        prepare(g, op, wavy, scene=scene, rig=rig, settings=settings, random_state=i)
        for i, (op, wavy) in enumerate(cases)
    ]
    lanes = simulate_lanes(preps, CHANNEL)
    for i, (op, wavy) in enumerate(cases):
        ref = simulate(g, op, wavy, scene=scene, rig=rig, settings=settings, random_state=i)
        ref = ref[CHANNEL]
        scale = np.max(np.abs(ref))
        assert scale > 0 and np.max(np.abs(lanes[i] - ref)) <= 1e-9 * scale, i
    for position in range(3):
        block = [preps[0], preps[2]]
        block.insert(position, preps[1])
        assert np.array_equal(simulate_lanes(block, CHANNEL)[position], lanes[1]), position


def test_the_entry_kink_is_what_a_perfect_bearing_rings_with():
    """A perfect 6205 with 5 um of clearance at 100 N, 1797 rpm: the housing's acceleration
    with a flooded film's entrainment is under a tenth of its RMS without (60 times less when
    measured, stop 73): without it, the contacts' onset at the load zone's edges is a kink of
    the force, whose broadband content the structure rings with."""
    g = bearing("6205", radial_internal_clearance=5e-6)
    op = OperatingCondition.from_rpm(1797, 100.0)
    settings = SimulationSettings(fs=12000.0, duration=0.5, channels=(CHANNEL,))
    rms = [
        np.std(simulate(g, op, rig=Rig(film_entrainment_factor=f), settings=settings)[CHANNEL])
        for f in (0.0, 1.0)
    ]
    assert rms[1] < 0.1 * rms[0], rms


def test_with_entrainment_form_errors_and_slow_waviness_are_no_local_fault():
    """The two strict xfails' cases (tests_cmtool/test_diagnosis.py) with a flooded film's
    entrainment: the balls' 0.1 um form errors (100 N, 5 um clearance, 1797 rpm, 5 % noise)
    and the 9-lobe inner race at 900 rpm (1 um, 500 N, 25.6 kHz, 5 % noise) are healthy to
    the rule, "outer race" without it (docs/diagnosis.md: the entry events)."""
    from cmtool.diagnose import diagnose_signal

    cases = [
        (
            bearing("6205", radial_internal_clearance=5e-6),
            OperatingCondition.from_rpm(1797, 100.0),
            form_waviness(9, 0.0, 0.0, 1e-7),
            12000.0,
            2,
        ),
        (
            bearing("6205"),
            OperatingCondition.from_rpm(900, 500.0),
            Waviness(surface="inner", order=9, amplitude=1e-6),
            25600.0,
            3,
        ),
    ]
    for g, op, defects, fs, seed in cases:
        settings = SimulationSettings(fs=fs, duration=1.0, channels=(CHANNEL,))
        verdicts = []
        for factor in (0.0, 1.0):
            rig = Rig(film_entrainment_factor=factor)
            x = simulate(g, op, defects, rig=rig, settings=settings, random_state=seed)[CHANNEL]
            x = x + np.random.default_rng(1).normal(0.0, 0.05 * np.std(x), x.size)
            verdicts.append(diagnose_signal(x, fs, op.rpm, g, waviness=False).verdict)
        assert verdicts == ["outer race", "healthy"], (op.rpm, verdicts)


ENTRAINED_RECIPE = """
name = "entrained"
seed = 6
bearings = ["6205"]
[operating]
rpm = 1797
load_n = 100
clearance_m = 5e-6
[model]
{model}
[sensor]
fs_hz = 12000
duration_s = 0.3
settle_s = 0.1
[[conditions]]
label = "healthy"
count = 1
"""


def test_a_recipe_gives_every_case_the_films_entrainment():
    """``[model] film_entrainment_factor`` gives every case's rig the option (the entrained
    film mode; the perfect bearing of the test above then rings under a tenth as much); absent,
    the validated recipe (and its digest) has no such key; refused, by name, out of 0-1, in
    scene full and without the film."""
    import tomllib

    from generators.cases import expand_cases
    from generators.recipe import validate_recipe
    from generators.synthesis import _setup, generate_cases

    rms = []
    for model in ("", "film_entrainment_factor = 1.0"):
        recipe = validate_recipe(tomllib.loads(ENTRAINED_RECIPE.format(model=model)))
        assert ("film_entrainment_factor" in recipe["model"]) == bool(model)
        cases = expand_cases(recipe)
        run = _setup(recipe, cases[0], CHANNEL, {}).run
        assert run.film_mode == (K.FILM_ENTRAINED if model else K.FILM_EHL)
        assert (run.p[K.P_ENTRAINMENT_SERIES] > 0.0) == bool(model)
        rms.append(np.std(generate_cases(recipe, cases)[0]["signal"]))
    assert rms[1] < 0.1 * rms[0], rms
    for model in (
        "film_entrainment_factor = 1.5",
        'scene = "full"\nfilm_entrainment_factor = 0.5',
        "ehl = false\nfilm_entrainment_factor = 0.5",
    ):
        with pytest.raises(ParameterError, match="model.film_entrainment_factor"):
            validate_recipe(tomllib.loads(ENTRAINED_RECIPE.format(model=model)))


DRAWN_RECIPE = """
name = "drawn"
seed = 81
bearings = ["6205"]
[operating]
rpm = [1797, 1730]
load_n = { min = 50, max = 500 }
clearance_m = { min = -10e-6, max = 15e-6 }
random_slip = { min = 0.005, max = 0.02 }
cage_slip = { min = 0.0, max = 0.01 }
[model]
scene = "shaft+housing"
housing_mass_kg = { min = 1, max = 20 }
shaft_damping_ratio = { min = 0.02, max = 0.05 }
{model}
[sensor]
fs_hz = 12000
duration_s = 0.3
settle_s = 0.1
background_db = { min = 0, max = 30 }
[[conditions]]
label = "healthy"
count = 6
[[conditions]]
label = "outer"
surface = "outer"
defect = "localized"
length_m = 0.3e-3
depth_m = 0.1e-3
count = 2
"""


def test_a_recipe_draws_the_films_entrainment_per_case_after_everything_else():
    """``[model] film_entrainment_factor = { min, max }`` draws each case its own factor, which
    its rig carries (and the ``film_entrainment_factor`` column). It is drawn after every
    other value, so the cases are those of the recipe without the key (a paired comparison,
    docs/realism.md 5); a single value draws nothing, and gives every case that value."""
    import dataclasses
    import tomllib

    from generators.cases import expand_cases
    from generators.recipe import validate_recipe
    from generators.synthesis import case_rig, generate_cases

    def cases(model: str) -> list:
        return expand_cases(validate_recipe(tomllib.loads(DRAWN_RECIPE.replace("{model}", model))))

    without = cases("")
    drawn = cases("film_entrainment_factor = { min = 0.2, max = 0.9 }")
    single = cases("film_entrainment_factor = 0.6")
    factors = [c.film_entrainment_factor for c in drawn]
    assert all(0.2 <= e <= 0.9 for e in factors) and len(set(factors)) == len(factors)
    assert all(math.isnan(c.film_entrainment_factor) for c in without)
    assert [c.film_entrainment_factor for c in single] == [0.6] * len(single)
    for other in (drawn, single):
        assert [dataclasses.replace(c, film_entrainment_factor=math.nan) for c in other] == [
            dataclasses.replace(c, film_entrainment_factor=math.nan) for c in without
        ]
    g = bearing("6205")
    assert [case_rig(c, g).film_entrainment_factor for c in drawn] == factors
    assert {case_rig(c, g).film_entrainment_factor for c in without} == {0.0}
    recipe = validate_recipe(
        tomllib.loads(
            DRAWN_RECIPE.replace("{model}", "film_entrainment_factor = { min = 0.2, max = 0.9 }")
        )
    )
    rows = generate_cases(recipe, drawn[:2])
    assert [row["film_entrainment_factor"] for row in rows] == factors[:2]
    refused = "film_entrainment_factor = { min = 0, max = 0.5 }\nehl = false"
    with pytest.raises(ParameterError, match=r"model.film_entrainment_factor = \{'min': 0.0"):
        validate_recipe(tomllib.loads(DRAWN_RECIPE.replace("{model}", refused)))
    with pytest.raises(ParameterError, match="model.film_entrainment_factor"):
        cases("film_entrainment_factor = { min = 0.5, max = 1.5 }")


def test_entrained_runs_hold_at_the_extremes_and_beyond_the_tables_reach(monkeypatch):
    """Preload (-10 um), a 6308 at 20 kN and 300 rpm, a 6002 at 9000 rpm and 48 kHz, in both
    scenes: finite records. With 0.5 mm of clearance the unloaded balls stand beyond the
    table's reach into the gap, where the kernels solve the law by Newton: the same record as
    a run with no table at all (every contact by Newton), to 1e-9 of its peak."""
    import generators.prepared as prepared_module

    cases = [
        (bearing("6205", radial_internal_clearance=-10e-6), 1800.0, 500.0, 12000.0),
        (bearing("6308"), 300.0, 20000.0, 12000.0),
        (bearing("6002"), 9000.0, 50.0, 48000.0),
    ]
    rig = Rig(film_entrainment_factor=1.0)
    for g, rpm, load, fs in cases:
        settings = SimulationSettings(fs=fs, duration=0.05, settle_time=0.02, channels=(CHANNEL,))
        for level in ("shaft", "shaft+housing"):
            x = simulate(
                g,
                OperatingCondition.from_rpm(rpm, load),
                scene=Scene(level=level),
                rig=rig,
                settings=settings,
            )[CHANNEL]
            assert np.all(np.isfinite(x)) and np.std(x) > 0.0, (rpm, level)
    wide = bearing("6205", radial_internal_clearance=5e-4)
    op = OperatingCondition.from_rpm(1800.0, 200.0)
    settings = SimulationSettings(fs=12000.0, duration=0.05, settle_time=0.02, channels=(CHANNEL,))
    prep = prepare(wide, op, rig=rig, settings=settings)
    reach = (prep.p[K.P_ENTRAINED_ORIGIN] * prep.p[K.P_ENTRAINED_STEP]) ** 2
    assert 2.0 * prep.p[K.P_GAP] > 1.5 * reach  # the balls opposite the load stand beyond it
    tabled = simulate(wide, op, rig=rig, settings=settings)[CHANNEL]
    with_tables = prepared_module.with_film_tables

    def no_entrained_table(p):
        out = with_tables(p)
        out[K.P_ENTRAINED_NODES] = 0.0  # every read outside the table: Newton
        return out

    monkeypatch.setattr(prepared_module, "with_film_tables", no_entrained_table)
    newton = simulate(wide, op, rig=rig, settings=settings)[CHANNEL]
    assert np.max(np.abs(tabled - newton)) <= 1e-9 * np.max(np.abs(newton))
