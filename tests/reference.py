"""Slow, obviously-correct reference implementations (stumpy's ``naive.py`` idea).

``ReferenceModel`` writes the equations of motion of docs/model.md (1.3)-(1.5) again in plain
numpy from the equations of that page and the parameter objects alone: the Hertz constants
from 3.1-3.3 (the ellipticity solved from (3.1) with scipy's elliptic integrals), the central
film of Hamrock and Dowson (4.1)-(4.2) with the load floor of 4.1, the squeeze-film damping
(4.5), the entrainment speed and the frequencies of section 2, the waviness of section 5 from
the ``Waviness`` objects (only the random per-ball phases of ball waviness, drawn by
``prepare``, are read from its table, after checking the table's orders and amplitudes
against the objects). Both integrations start from ``prepare``'s static state (a shared initial
condition); that it is an equilibrium is checked against this model's own equations
(``frozen_accelerations``). Nothing of ``generators.contact``,
``generators.kinematics`` or the kernel is used, so a wrong constant, film, damping or cage
speed in the package makes the two disagree. ``reference_solution`` integrates it with
``solve_ivp`` (DOP853, tight tolerances).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import integrate, optimize, special

from generators import Waviness

SURF_OUTER, SURF_INNER, SURF_BALL = 0, 1, 2  # the kernel table's surface codes (ball rows)
GRAVITY = 9.81  # docs/model.md 1.1 [m/s^2]


def _radii(geometry, which):
    """R_x, R_y of the inner or outer contact [m] (docs/model.md 3.1)."""
    d, dm = geometry.ball_diameter, geometry.pitch_diameter
    c = d * math.cos(geometry.contact_angle)
    if which == "inner":
        f = geometry.inner_groove_curvature
        return d * (dm - c) / (2 * dm), f * d / (2 * f - 1)
    f = geometry.outer_groove_curvature
    return d * (dm + c) / (2 * dm), f * d / (2 * f - 1)


def _effective_modulus(geometry):
    """E' [Pa] (docs/model.md 3.1)."""
    a, b = geometry.ball_material, geometry.ring_material
    return 2.0 / (
        (1 - a.poisson_ratio**2) / a.youngs_modulus + (1 - b.poisson_ratio**2) / b.youngs_modulus
    )


def hertz_constant(geometry, which):
    """K [N/m^1.5] from (3.1) solved for kappa and (3.3)."""
    rx, ry = _radii(geometry, which)
    r = 1.0 / (1.0 / rx + 1.0 / ry)
    big_f = (ry - rx) / (ry + rx)

    def residual(kappa):
        m = 1.0 - 1.0 / kappa**2
        e, k = special.ellipe(m), special.ellipk(m)
        return ((kappa**2 + 1) * e - 2 * k) / ((kappa**2 - 1) * e) - big_f

    kappa = optimize.brentq(residual, 1.0 + 1e-9, 100.0, xtol=1e-14)
    m = 1.0 - 1.0 / kappa**2
    e, k = special.ellipe(m), special.ellipk(m)
    return math.pi * kappa * _effective_modulus(geometry) * math.sqrt(r * e / (4.5 * k**3))


def central_film(geometry, which, lubricant, speed, load):
    """h_c [m] of (4.1)-(4.2) (times the lubricant's film factor), at ``load`` [N]."""
    rx, ry = _radii(geometry, which)
    e = _effective_modulus(geometry)
    u = lubricant.viscosity * speed / (e * rx)
    g = lubricant.pressure_viscosity_coefficient * e
    w = load / (e * rx**2)
    ke = 1.03 * (ry / rx) ** 0.64
    h = 2.69 * rx * u**0.67 * g**0.53 * w**-0.067 * (1 - 0.61 * math.exp(-0.73 * ke))
    return lubricant.film_factor * h


def squeeze_damping(geometry, which, lubricant, film):
    """c_sq [N s/m] of (4.5) for a film ``film`` [m]."""
    rx, ry = _radii(geometry, which)
    eps = min(rx / ry, 1.0)
    shape = 2.0 - eps**0.75
    return 6 * math.pi * lubricant.viscosity * rx**1.5 * ry**0.5 * shape / film


class ReferenceModel:
    """Equations of motion of one prepared run (``generators.model.prepare``)."""

    def __init__(self, prep):
        g, op, rig = prep.geometry, prep.operating, prep.rig
        self.geometry = g
        self.level, self.ehl = prep.scene_name, prep.ehl
        self.z = g.ball_count
        self.ki, self.ko = hertz_constant(g, "inner"), hertz_constant(g, "outer")
        self.kt = (self.ki ** (-2 / 3) + self.ko ** (-2 / 3)) ** -1.5  # (3.4)
        self.gap = g.radial_internal_clearance / 2  # c_r = P_d / 2 (1.1)
        density = g.ball_material.density
        self.ms, self.mh = rig.shaft_mass, rig.housing_mass
        self.mb = density * math.pi * g.ball_diameter**3 / 6
        self.kh, self.ch, self.cs = rig.pedestal_stiffness, rig.pedestal_damping, rig.shaft_damping
        self.tau = rig.contact_damping_time
        self.grav = GRAVITY if rig.gravity else 0.0
        self.load = op.radial_load * np.array([math.cos(op.load_angle), math.sin(op.load_angle)])
        self.kl = rig.loading_stiffness
        # section 2: cage, ball spin (rolling on the standing outer race), entrainment
        gamma = g.ball_diameter * math.cos(g.contact_angle) / g.pitch_diameter
        self.ws = 2 * math.pi * op.shaft_frequency
        self.wc = 0.5 * self.ws * (1 - gamma) * (1 - op.cage_slip)
        self.wb = (g.pitch_diameter / g.ball_diameter) * (1 + gamma) * self.wc
        self.u = self.ws * (g.pitch_diameter**2 - g.ball_diameter**2) / (4 * g.pitch_diameter)
        self.theta0 = prep.settings.cage_angle
        self.radius = g.pitch_diameter / 2
        self.lub = rig.lubricant
        self.floor = max(1.0, self.mb * self.wc**2 * self.radius)  # Q_floor (4.1)
        self.film_factor = rig.film_damping_factor
        self.nd = 4 + self.z if self.level == "full" else 4
        self.rows = self._waviness_rows(prep)
        self.anchor = prep.y0[:2].copy()  # the loading spring's rest point: the start

    def _waviness_rows(self, prep):
        """(surface, ball, order, amplitude, phase) from the Waviness objects (section 5)."""
        rows, table = [], prep.wav[prep.wav[:, 0] == SURF_BALL]
        used = 0
        for w in prep.defects:
            assert isinstance(w, Waviness), "the reference models waviness only"
            if w.amplitude == 0.0:
                continue
            if w.surface in ("outer", "inner"):
                assert w.phase is not None, "give race waviness an explicit phase"
                code = SURF_OUTER if w.surface == "outer" else SURF_INNER
                rows.append((code, -1, w.order, w.amplitude, w.phase))
                continue
            balls = range(self.z) if w.ball is None else (w.ball,)
            for j in balls:
                # the drawn phase (waviness phase plus order x initial spin angle) is the one
                # thing taken from prepare's table; its order and amplitude must be the object's
                surf, ball, order, amplitude, phase = table[used, :5]
                assert (int(ball), order, amplitude) == (j, w.order, w.amplitude)
                rows.append((SURF_BALL, j, w.order, w.amplitude, phase))
                used += 1
        return rows

    def frozen_accelerations(self, y):
        """Accelerations at ``y`` with the cage frozen at t = 0 and no damping (the static
        problem of docs/model.md 7.3; the full scene keeps its centrifugal ball term)."""
        saved = (self.ws, self.wc, self.wb, self.tau, self.film_factor, self.cs, self.ch)
        self.ws = self.wb = self.tau = self.film_factor = self.cs = self.ch = 0.0
        if self.level != "full":
            self.wc = 0.0
        try:
            return self.rhs(0.0, np.r_[y[: self.nd], np.zeros(self.nd)])[self.nd :]
        finally:
            self.ws, self.wc, self.wb, self.tau, self.film_factor, self.cs, self.ch = saved

    # waviness -------------------------------------------------------------------------
    def waviness(self, t):
        z = self.z
        theta = self.theta0 + self.wc * t + 2 * np.pi * np.arange(z) / z
        phi_s = self.ws * t
        w = np.zeros((8, z))
        for surf, ball, k, a, ph in self.rows:
            if surf == SURF_OUTER:
                w[0] += a * np.cos(k * theta + ph)
                w[1] += -a * k * self.wc * np.sin(k * theta + ph)
            elif surf == SURF_INNER:
                arg = k * (theta - phi_s) + ph
                w[2] += a * np.cos(arg)
                w[3] += -a * k * (self.wc - self.ws) * np.sin(arg)
            else:
                j = int(ball)
                chi = self.wb * t
                w[4, j] += a * math.cos(k * chi + ph)
                w[5, j] += -a * k * self.wb * math.sin(k * chi + ph)
                w[6, j] += a * math.cos(k * (chi + math.pi) + ph)
                w[7, j] += -a * k * self.wb * math.sin(k * (chi + math.pi) + ph)
        return theta, w

    # contact laws ---------------------------------------------------------------------
    def _film(self, which, q):
        # the load floor of docs/model.md 4.1: h(Q + Q_floor)
        return central_film(self.geometry, which, self.lub, self.u, q + self.floor)

    def contact(self, delta, rate, which):
        if which == "series":
            kc = self.kt
        else:
            kc = self.ki if which == "inner" else self.ko
        if not self.ehl:
            if delta <= 0:
                return 0.0
            q = kc * delta**1.5 + self.tau * 1.5 * kc * math.sqrt(delta) * rate  # (1.2)
            return max(q, 0.0)

        def film(q):
            if which == "series":
                return self._film("inner", q) + self._film("outer", q)
            return self._film(which, q)

        if delta + film(0.0) <= 0:
            if which == "series" or rate <= 0:
                return 0.0
            # apart (scene full): Reynolds' squeeze film (4.5) at the separation -delta as
            # they approach; Guembel's condition (no pressure under ambient) leaves none as
            # they separate; weighted to zero at onset over the Hertz approach at the load
            # floor (docs/model.md 4.4)
            gap = -(delta + film(0.0))
            gap_floor = (self.floor / kc) ** (2 / 3)
            c_sq = squeeze_damping(self.geometry, which, self.lub, -delta) * self.film_factor
            return c_sq * gap / (gap + gap_floor) * rate
        # exact solution of Q = K (delta + h(Q))^1.5 (docs/model.md 4.3)
        q_hi = kc * (delta + film(0.0)) ** 1.5
        q = (
            optimize.brentq(
                lambda q: q - kc * max(delta + film(q), 0.0) ** 1.5,
                0.0,
                q_hi,
                xtol=1e-14,
                rtol=1e-13,
            )
            if q_hi > 0
            else 0.0
        )
        d_el = delta + film(q)
        blend = q / (q + self.floor)  # docs/model.md 4.4: continuous at onset
        if which == "series":
            g = self.geometry
            c_i = squeeze_damping(g, "inner", self.lub, self._film("inner", q))
            c_o = squeeze_damping(g, "outer", self.lub, self._film("outer", q))
            # two contacts in series (docs/model.md 1.4), k_i : k_o = K_i^(2/3) : K_o^(2/3)
            kri, kro = self.ki ** (2 / 3), self.ko ** (2 / 3)
            k_i, k_o = kri / (kri + kro), kro / (kri + kro)
            c_sq = (c_i * k_o**2 + c_o * k_i**2) * self.film_factor
        else:
            c_sq = squeeze_damping(self.geometry, which, self.lub, self._film(which, q))
            c_sq *= self.film_factor
        c = self.tau * 1.5 * kc * math.sqrt(d_el) + blend * c_sq
        return max(q + c * rate, 0.0)

    # equations of motion ----------------------------------------------------------------
    def rhs(self, t, y):
        nd, z = self.nd, self.z
        xs, vs = y[0:2], y[nd : nd + 2]
        xh, vh = y[2:4], y[nd + 2 : nd + 4]
        theta, w = self.waviness(t)
        e = np.stack([np.cos(theta), np.sin(theta)])  # (2, z)
        et = np.stack([-np.sin(theta), np.cos(theta)])
        us = xs @ e
        dus = vs @ e + self.wc * (xs @ et)
        uh = xh @ e
        duh = vh @ e + self.wc * (xh @ et)
        dydt = np.zeros_like(y)
        dydt[:nd] = y[nd:]
        if self.level == "full":
            rho, drho = y[4 : 4 + z], y[nd + 4 : nd + 4 + z]
            di = us - rho - self.gap / 2 + w[2] + w[6]
            ddi = dus - drho + w[3] + w[7]
            do = rho - uh - self.gap / 2 + w[0] + w[4]
            ddo = drho - duh + w[1] + w[5]
            qi = np.array([self.contact(di[j], ddi[j], "inner") for j in range(z)])
            qo = np.array([self.contact(do[j], ddo[j], "outer") for j in range(z)])
            dydt[nd + 4 : nd + 4 + z] = (
                (qi - qo) / self.mb + self.wc**2 * (self.radius + rho) - self.grav * e[1]
            )
        else:
            coupled = self.level == "shaft+housing"
            d = us - (uh if coupled else 0.0) - self.gap + w[0] + w[2] + w[4] + w[6]
            dd = dus - (duh if coupled else 0.0) + w[1] + w[3] + w[5] + w[7]
            qi = np.array([self.contact(d[j], dd[j], "series") for j in range(z)])
            qo = qi
        f_shaft = -(e @ qi) + self.load - self.kl * (xs - self.anchor) - self.cs * vs
        f_shaft[1] -= self.ms * self.grav
        f_house = e @ qo - self.kh * xh - self.ch * vh
        f_house[1] -= self.mh * self.grav
        dydt[nd : nd + 2] = f_shaft / self.ms
        dydt[nd + 2 : nd + 4] = f_house / self.mh
        return dydt


def reference_solution(prep, t_eval: np.ndarray) -> np.ndarray:
    """States at ``t_eval`` [s] from solve_ivp (DOP853, rtol 1e-11), shape (len(t_eval), n)."""
    model = ReferenceModel(prep)
    nd = model.nd
    atol = np.r_[np.full(nd, 1e-15), np.full(nd, 1e-12)]
    sol = integrate.solve_ivp(
        model.rhs,
        (0.0, float(t_eval[-1])),
        prep.y0,
        method="DOP853",
        t_eval=t_eval,
        rtol=1e-11,
        atol=atol,
    )
    assert sol.success, sol.message
    return sol.y.T


def rk4_records(prep, record_dt, n_record, substeps, *, y0=None, ehl=None):
    """Kernel RK4 records (states, accelerations) every ``record_dt`` from t = 0, with
    ``substeps`` steps per record; raises if the kernel reports divergence."""
    from generators import _integrators
    from generators import _kernels as K

    y0 = prep.y0 if y0 is None else y0
    ehl = prep.ehl if ehl is None else ehl
    dt = record_dt / substeps
    st = np.zeros((n_record, K.N_OUT_STATE))
    ac = np.zeros((n_record, K.N_OUT_ACCEL))
    ld = np.zeros((1, 2, prep.geometry.ball_count))
    status, _, _ = _integrators._rk4(
        prep.scene_code,
        int(ehl),
        y0,
        prep.p,
        prep.wav,
        0.0,
        dt,
        (n_record - 1) * substeps + 1,
        0.0,
        record_dt,
        n_record,
        st,
        ac,
        ld,
        False,
        1,  # uniform steps
        np.ones(K.N_OUT_STATE + K.N_OUT_ACCEL, dtype=np.int64),  # every record column
    )
    assert status == K.STATUS_OK, status
    return st, ac
