"""Hertz contact and EHL film against docs/model.md's published/verified values.

Sources and tolerances:
* docs/model.md 3.5 table (6205, exact Hertz, 4 significant digits) -> TABLE_RTOL = 1e-3.
* docs/model.md 7.6 T1: Hamrock-Brewe vs exact within 2 % in K and kappa.
* Harris's chart form K = 2.15e5 (sum rho)^-1/2 (delta*)^-3/2 N/mm^1.5 (E = 2.075e11, nu = 0.3):
  its constant has 3 significant digits -> HARRIS_RTOL = 5e-3.
* docs/model.md 4.2 EHL table (3 significant digits) -> T12 says +/- 0.5 %: EHL_RTOL = 5e-3.
* An independent solution of (3.1) with the elliptic integrals by quadrature -> 1e-9.
"""

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy import integrate, optimize

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))  # tests/reference.py

from generators import (
    LUBRICANTS,
    Material,
    ParameterError,
    bearing,
    contact_geometry,
    contact_static_capacity,
    entrainment_speed,
    film_stiffness,
    film_thickness,
    hertz_contact,
    load_deflection_constants,
    sagitta,
    series_constant,
    squeeze_film_damping,
)

TABLE_RTOL = 1e-3
HB_RTOL = 0.02
HARRIS_RTOL = 5e-3
EHL_RTOL = 5e-3
QUADRATURE_RTOL = 1e-9

# docs/model.md 3.5 (6205: d = 7.94 mm, D = 39.04 mm, f = 0.52, E = 2.08e11, nu = 0.3)
TABLE = {
    "inner": {
        "rx": 3.1626e-3,
        "ry": 103.22e-3,
        "kappa": 9.341,
        "E": 1.0179,
        "K": 3.6283,
        "Kc": 2.557e10,
    },
    "outer": {
        "rx": 4.7774e-3,
        "ry": 103.22e-3,
        "kappa": 7.265,
        "E": 1.0273,
        "K": 3.3807,
        "Kc": 2.710e10,
    },
}


@pytest.mark.parametrize("race", ["inner", "outer"])
def test_6205_hertz_table(race):
    c = hertz_contact(bearing("6205"), race)
    t = TABLE[race]
    assert c.geometry.rx == pytest.approx(t["rx"], rel=TABLE_RTOL)
    assert c.geometry.ry == pytest.approx(t["ry"], rel=TABLE_RTOL)
    assert c.kappa == pytest.approx(t["kappa"], rel=TABLE_RTOL)
    assert c.elliptic_e == pytest.approx(t["E"], rel=TABLE_RTOL)
    assert c.elliptic_k == pytest.approx(t["K"], rel=TABLE_RTOL)
    assert c.stiffness_constant == pytest.approx(t["Kc"], rel=TABLE_RTOL)


def test_series_constant_6205():
    ki, ko, kt = load_deflection_constants(bearing("6205"))
    assert kt == pytest.approx(9.30e9, rel=TABLE_RTOL)
    # against (3.1)-(3.4) written independently (tests/reference.py)
    from reference import hertz_constant

    ri, ro = hertz_constant(bearing("6205"), "inner"), hertz_constant(bearing("6205"), "outer")
    assert (ki, ko) == (pytest.approx(ri, rel=1e-9), pytest.approx(ro, rel=1e-9))
    assert kt == pytest.approx((ri ** (-2 / 3) + ro ** (-2 / 3)) ** -1.5, rel=1e-9)
    # a ball between two equal contacts: K_tot = K / 2^1.5
    assert series_constant(1e10, 1e10) == pytest.approx(1e10 / 2**1.5, rel=1e-12)


@pytest.mark.parametrize("race", ["inner", "outer"])
def test_hamrock_brewe_within_two_percent(race):
    # docs/model.md 7.6 T1
    g = bearing("6205")
    exact = hertz_contact(g, race)
    hb = hertz_contact(g, race, method="hamrock-brewe")
    assert hb.stiffness_constant == pytest.approx(exact.stiffness_constant, rel=HB_RTOL)
    assert hb.kappa == pytest.approx(exact.kappa, rel=HB_RTOL)


def _ellipk_quad(m):
    return integrate.quad(
        lambda p: 1 / math.sqrt(1 - m * math.sin(p) ** 2), 0, math.pi / 2, epsabs=0, epsrel=1e-13
    )[0]


def _ellipe_quad(m):
    return integrate.quad(
        lambda p: math.sqrt(1 - m * math.sin(p) ** 2), 0, math.pi / 2, epsabs=0, epsrel=1e-13
    )[0]


@pytest.mark.parametrize("name", ["6205", "6203", "6305", "6002", "6308", "mfpt"])
@pytest.mark.parametrize("race", ["inner", "outer"])
def test_exact_ellipticity_against_quadrature(name, race):
    c = hertz_contact(bearing(name), race)
    target = c.geometry.curvature_difference

    def eq(kappa):
        m = 1 - 1 / kappa**2
        e, k = _ellipe_quad(m), _ellipk_quad(m)
        return ((kappa**2 + 1) * e - 2 * k) / ((kappa**2 - 1) * e) - target

    kappa = optimize.brentq(eq, 1.001, 100, xtol=1e-13)
    assert c.kappa == pytest.approx(kappa, rel=QUADRATURE_RTOL)
    assert c.elliptic_k == pytest.approx(_ellipk_quad(1 - 1 / kappa**2), rel=QUADRATURE_RTOL)


def test_harris_chart_form():
    # docs/model.md 3.3: Harris's K = 2.15e5 (sum rho)^-1/2 (delta*)^-3/2 N/mm^1.5 for E = 2.075e11
    steel = Material(name="Harris steel", youngs_modulus=2.075e11, poisson_ratio=0.3, density=7850)
    g = dataclasses.replace(bearing("6205"), ball_material=steel, ring_material=steel)
    c = hertz_contact(g, "inner")
    sum_rho_mm = c.geometry.curvature_sum / 1e3
    dstar = (2 * c.elliptic_k / math.pi) * (math.pi / (2 * c.kappa**2 * c.elliptic_e)) ** (1 / 3)
    k_harris = 2.15e5 * sum_rho_mm**-0.5 * dstar**-1.5 * 1e3**1.5
    assert c.stiffness_constant == pytest.approx(k_harris, rel=HARRIS_RTOL)


def test_load_deflection_roundtrip():
    c = hertz_contact(bearing("6205"), "outer")
    q = np.array([0.0, 1.0, 100.0, 1000.0])
    assert c.load(c.deflection(q)) == pytest.approx(q, rel=1e-12)
    assert c.load(-1e-6) == 0.0
    # tangent stiffness equals the numerical derivative
    d = 5e-6
    num = (c.load(d * (1 + 1e-6)) - c.load(d * (1 - 1e-6))) / (2e-6 * d)
    assert c.linear_stiffness(c.load(d)) == pytest.approx(num, rel=1e-8)


def test_static_capacity_estimate_matches_catalogue():
    # ISO 76: 4200 MPa at the most loaded contact, Q_max = 5 F_r / Z -> C_0r ~ Z Q / 5. The
    # catalogue 6205 value is 7.85 kN (NSK); the estimate must be within 5 %.
    g = bearing("6205")
    c0 = contact_static_capacity(g) * g.ball_count / 5
    assert c0 == pytest.approx(g.static_load_rating, rel=0.05)


def test_bad_geometry_for_contact():
    with pytest.raises(ParameterError, match="race = 'middle'"):
        contact_geometry(bearing("6205"), "middle")  # type: ignore[arg-type]


# docs/model.md 4.2: 6205, VG 68 at 40 C (rpm, ball load) -> h_c inner/outer, h_min inner/outer [um]
EHL_TABLE = [
    (600, 50, 0.186, 0.224, 0.150, 0.181),
    (1800, 5, 0.452, 0.546, 0.375, 0.452),
    (1800, 500, 0.332, 0.401, 0.268, 0.323),
    (3600, 500, 0.529, 0.639, 0.430, 0.518),
]


@pytest.mark.parametrize(("rpm", "load", "hci", "hco", "hmi", "hmo"), EHL_TABLE)
def test_film_thickness_table(rpm, load, hci, hco, hmi, hmo):
    g, lub = bearing("6205"), LUBRICANTS["VG68"]
    u = entrainment_speed(g, rpm / 60)
    ci, co = hertz_contact(g, "inner"), hertz_contact(g, "outer")
    assert film_thickness(ci, lub, u, load) == pytest.approx(hci * 1e-6, rel=EHL_RTOL)
    assert film_thickness(co, lub, u, load) == pytest.approx(hco * 1e-6, rel=EHL_RTOL)
    assert film_thickness(ci, lub, u, load, kind="minimum") == pytest.approx(
        hmi * 1e-6, rel=EHL_RTOL
    )
    assert film_thickness(co, lub, u, load, kind="minimum") == pytest.approx(
        hmo * 1e-6, rel=EHL_RTOL
    )


def test_entrainment_speed():
    # docs/model.md section 2: 1.764 m/s for a 6205 at 1800 rpm
    assert entrainment_speed(bearing("6205"), 30.0) == pytest.approx(1.764, abs=5e-4)


def test_film_load_floor_and_monotonicity():
    g, lub = bearing("6205"), LUBRICANTS["VG68"]
    c = hertz_contact(g, "inner")
    u = entrainment_speed(g, 30.0)
    h = film_thickness(c, lub, u, np.array([0.0, 0.5, 1.0, 10.0, 100.0]))
    assert h[0] == h[1] == h[2]  # floored at 1 N
    assert np.all(np.diff(h[2:]) < 0)  # thinner under more load, h ~ Q^-0.067
    assert h[3] / h[4] == pytest.approx(10**0.067, rel=1e-12)


@pytest.mark.parametrize(
    ("rpm", "race", "expected"),
    [(1800, "inner", 0.88), (1800, "outer", 0.86), (3600, "outer", 0.79)],
)
def test_film_series_stiffness_at_light_load(rpm, race, expected):
    # docs/model.md 4.3: k_series / k_H = 0.88 (inner), 0.86 (outer) at 5 N, 1800 rpm; 0.79 at
    # 3600 rpm (two significant digits -> abs 0.01)
    g, lub = bearing("6205"), LUBRICANTS["VG68"]
    u = entrainment_speed(g, rpm / 60)
    c = hertz_contact(g, race)
    kf = film_stiffness(5.0, film_thickness(c, lub, u, 5.0))
    kh = c.linear_stiffness(5.0)
    assert 1 / (1 + kh / kf) == pytest.approx(expected, abs=0.01)


def test_film_negligible_at_heavy_load():
    # docs/model.md 4.3: at 500 N the film is two orders stiffer than the Hertz contact
    g, lub = bearing("6205"), LUBRICANTS["VG68"]
    u = entrainment_speed(g, 30.0)
    for race in ("inner", "outer"):
        c = hertz_contact(g, race)
        assert film_stiffness(500.0, film_thickness(c, lub, u, 500.0)) > 100 * c.linear_stiffness(
            500.0
        )


def test_squeeze_film_damping_values():
    # docs/model.md 4.4 D2: c_i ~ 370, c_o ~ 560 N s/m (6205, VG 68, 1800 rpm, 500 N)
    g, lub = bearing("6205"), LUBRICANTS["VG68"]
    u = entrainment_speed(g, 30.0)
    ci, co = hertz_contact(g, "inner"), hertz_contact(g, "outer")
    assert squeeze_film_damping(ci, lub, film_thickness(ci, lub, u, 500.0)) == pytest.approx(
        370, rel=0.01
    )
    assert squeeze_film_damping(co, lub, film_thickness(co, lub, u, 500.0)) == pytest.approx(
        560, rel=0.01
    )


def test_the_film_between_a_ball_and_a_race_apart_resists_their_approach_only():
    """Scene full's balls apart from a race meet the film between them (docs/model.md 4.4):
    Reynolds' squeeze force (4.5) at their separation as they approach, weighted to zero at
    onset over the Hertz approach at the load floor, nothing as they separate (Guembel). Checked
    against squeeze_film_damping at the separation, each race, 6205 at 1800 rpm; at onset
    continuous with the film contact's force (1e-15 m either side, both under 1e-6 of the
    unweighted squeeze force there)."""
    from generators import OperatingCondition, Scene, SimulationSettings
    from generators import _kernels as K
    from generators.model import prepare

    g = bearing("6205")
    prep = prepare(
        g,
        OperatingCondition.from_rpm(1800, 500.0),
        scene=Scene(level="full", ehl=True),
        settings=SimulationSettings(fs=12000.0, duration=0.01),
    )
    p, rate = prep.p, 1e-3  # approach speed [m/s]
    floor = p[K.P_FILM_LOAD_FLOOR]
    for table, race in ((K.TABLE_INNER, "inner"), (K.TABLE_OUTER, "outer")):
        film, h_max = p[K.P_FILM_INNER + table], p[K.P_FILM_INNER_MAX + table]
        squeeze, k = p[K.P_SQUEEZE_INNER + table], p[K.P_K_INNER + table]
        contact = hertz_contact(g, race)
        gap_floor = (floor / k) ** (2 / 3)
        packed_floor = p[K.P_GAP_FLOOR_INNER + table]
        assert packed_floor == pytest.approx(gap_floor, rel=1e-12)
        for separation in (1e-6, 5e-6, 40e-6):
            delta = -separation
            gap = separation - h_max
            expected = squeeze_film_damping(contact, LUBRICANTS["VG68"], separation) * rate
            expected *= gap / (gap + gap_floor)
            force = K._gap_squeeze(delta, rate, film, squeeze, h_max, packed_floor)
            assert force == pytest.approx(expected, rel=1e-9)
            assert K._gap_squeeze(delta, -rate, film, squeeze, h_max, packed_floor) == 0.0
        onset, full = -h_max, squeeze * film / h_max * rate  # the unweighted force there
        assert (
            0.0
            < K._gap_squeeze(onset - 1e-15, rate, film, squeeze, h_max, packed_floor)
            < 1e-6 * full
        )
        assert 0.0 < _film_contact_exact(p, table, onset + 1e-15, rate) < 1e-6 * full
        assert K._gap_squeeze(onset + 1e-9, rate, film, squeeze, h_max, packed_floor) == 0.0


def test_film_bad_input():
    g, lub = bearing("6205"), LUBRICANTS["VG68"]
    c = hertz_contact(g, "inner")
    with pytest.raises(ParameterError, match="entrainment_speed_m_s = -1"):
        film_thickness(c, lub, -1.0, 100.0)
    with pytest.raises(ParameterError, match="kind = 'max'"):
        film_thickness(c, lub, 1.0, 100.0, kind="max")  # type: ignore[arg-type]


def _film_contact_exact(p, table, delta, rate):
    """Q + C delta' of a film contact by bisection of d = delta + h(K d^1.5) to the last bit."""
    from generators import _kernels as K

    if table == K.TABLE_SERIES:
        film = p[K.P_FILM_INNER] + p[K.P_FILM_OUTER]
        h_max = p[K.P_FILM_INNER_MAX] + p[K.P_FILM_OUTER_MAX]
        squeeze, k = p[K.P_SQUEEZE_SERIES], p[K.P_K_SERIES]
    else:
        film, h_max = p[K.P_FILM_INNER + table], p[K.P_FILM_INNER_MAX + table]
        squeeze, k = p[K.P_SQUEEZE_INNER + table], p[K.P_K_INNER + table]
    floor, tau = p[K.P_FILM_LOAD_FLOOR], p[K.P_CONTACT_DAMPING_TIME]
    if delta + h_max <= 0.0:
        return 0.0
    lo, hi = 0.0, delta + h_max
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid - delta - film * (k * mid**1.5 + floor) ** K.FILM_EXPONENT > 0.0:
            hi = mid
        else:
            lo = mid
    d = 0.5 * (lo + hi)
    q = k * d**1.5
    h = film * (q + floor) ** K.FILM_EXPONENT
    c = 1.5 * tau * k * math.sqrt(d) + q / (q + floor) * squeeze * film / h
    return max(q + c * rate, 0.0)


@pytest.mark.parametrize("load", [5.0, 500.0, 5000.0])
def test_film_tables_give_the_film_contact_force(load):
    """The kernels read Q + C delta' of the film contacts from tables (cubic Hermite in
    s = sqrt(delta + h_max), 2048 nodes up to 100 times the load plus 100 N,
    packing._film_tables); against the film equation solved by bisection: within 5e-8 of the
    force above 1 N and 5e-8 N below it (observed 1e-9 at 5 and 500 N, 1.4e-8 near the onset
    at 5000 N, where the nodes are ten times as far apart; RK4's own error at the default step
    is 1e-4 or more), exactly zero out of contact, and the lanes' series contact reads the same
    bits as the one-signal kernel's."""
    from generators import OperatingCondition, Scene, SimulationSettings
    from generators import _kernels as K
    from generators import _lanes as L
    from generators.model import prepare

    prep = prepare(
        bearing("6205"),
        OperatingCondition.from_rpm(1800, load),
        scene=Scene(level="shaft+housing", ehl=True),
        settings=SimulationSettings(fs=12000.0, duration=0.01),
    )
    p = prep.p
    rng = np.random.default_rng(7)
    for table in (K.TABLE_INNER, K.TABLE_OUTER, K.TABLE_SERIES):
        if table == K.TABLE_SERIES:
            args = (
                p[K.P_K_SERIES],
                p[K.P_CONTACT_DAMPING_TIME],
                p[K.P_FILM_INNER] + p[K.P_FILM_OUTER],
                p[K.P_SQUEEZE_SERIES],
                p[K.P_FILM_LOAD_FLOOR],
                p[K.P_FILM_INNER_REF] + p[K.P_FILM_OUTER_REF],
                p[K.P_FILM_INNER_MAX] + p[K.P_FILM_OUTER_MAX],
            )
        else:
            args = (
                p[K.P_K_INNER + table],
                p[K.P_CONTACT_DAMPING_TIME],
                p[K.P_FILM_INNER + table],
                p[K.P_SQUEEZE_INNER + table],
                p[K.P_FILM_LOAD_FLOOR],
                p[K.P_FILM_INNER_REF + table],
                p[K.P_FILM_INNER_MAX + table],
            )
        k, h_max = args[0], args[-1]
        top = (20.0 * (load + 100.0) / k) ** (2.0 / 3.0)  # up to 20 times the load
        deltas = np.concatenate(
            [
                rng.uniform(-2.0 * h_max, top, 400),
                -h_max + rng.uniform(0.0, 1e-2, 100) * h_max,  # the onset
            ]
        )
        for delta in deltas:
            rate = rng.normal(0.0, 1e-3)  # m/s
            q = K._hertz_ehl_table(delta, rate, *args, p, table)
            exact = _film_contact_exact(p, table, delta, rate)
            if delta + h_max <= 0.0:
                assert q == 0.0
            elif exact > 1.0:
                assert abs(q - exact) <= 5e-8 * exact, (table, delta, q, exact)
            else:
                assert abs(q - exact) <= 5e-8, (table, delta, q, exact)
    # the lanes' series contact: the same function of the same table row
    lanes_p = np.repeat(p[:, None], 2, axis=1)
    c = np.zeros((L.C_SIZE, 2))
    L._constants(lanes_p, c, 2)
    nodes = int(p[K.P_TABLE_NODES])
    first = K.P_SIZE + 4 * K.TABLE_SERIES * nodes
    tab = np.ascontiguousarray(np.repeat(p[None, first : first + 4 * nodes], 2, axis=0))
    for delta in rng.uniform(-2.0 * args[-1], top, 50):
        expected = K._hertz_ehl_table(delta, 1e-3, *args, p, K.TABLE_SERIES)
        assert L._series_film(delta, 1e-3, c, 1, tab, nodes) == expected


def _contact():
    return hertz_contact(bearing("6205"), "inner")


@pytest.mark.parametrize(
    ("call", "said"),
    [
        (lambda: _contact().load([1e-6, float("nan")]), r"deflection\[1\] = nan is not finite"),
        (lambda: _contact().deflection(-1.0), r"load = -1 N is outside the allowed range \[0, "),
        (lambda: _contact().linear_stiffness([[5.0, -2.0]]), r"load\[0, 1\] = -2 N is outside"),
        (lambda: _contact().semi_axes(-1.0), r"load = -1 N is outside the allowed range"),
        (lambda: _contact().max_pressure(float("inf")), r"load = inf is not finite"),
        (lambda: series_constant(0.0, 1e10), r"k_inner = 0 N/m\^1\.5 is outside .*\(0, inf\)"),
        (lambda: sagitta(4e-3, float("nan")), r"distance = nan is not finite"),
        (
            lambda: squeeze_film_damping(_contact(), LUBRICANTS["VG68"], 0.0),
            r"central_film_thickness = 0 m is outside the allowed range \(0, inf\) m",
        ),
        (
            lambda: film_thickness(_contact(), LUBRICANTS["VG68"], 5.0, float("nan")),
            r"load = nan is not finite",
        ),
    ],
)
def test_the_contact_laws_refuse_input_that_is_no_load_or_approach(call, said):
    """Bad input is refused by name, value and range, where before it gave NaN, complex
    semi-axes (a negative load), a ZeroDivisionError (no film) or numpy's power warning."""
    with pytest.raises(ParameterError, match=said):
        call()


def test_the_contact_laws_keep_their_values_for_valid_input():
    """The checks change nothing the laws return: the same values as the formulas."""
    c = _contact()
    approach = np.array([-1e-6, 0.0, 5e-6])
    np.testing.assert_array_equal(
        c.load(approach), c.stiffness_constant * np.maximum(approach, 0) ** 1.5
    )
    assert c.deflection(500.0) == (500.0 / c.stiffness_constant) ** (2.0 / 3.0)
    assert c.max_pressure(0.0) == 0.0 and c.semi_axes(0.0) == (0.0, 0.0)
