"""Slow, obviously-correct reference implementations (stumpy's ``naive.py`` idea).

``reference_rhs`` writes the equations of motion of docs/model.md (1.3)-(1.5) again in plain numpy,
from the parameter objects (not from the kernel's packed vector), with the EHL film solved
exactly (``scipy.optimize.brentq`` on Q = K (delta + h(Q))^1.5 with the Hamrock-Dowson film of
``generators.contact``). ``reference_solution`` integrates it with ``solve_ivp`` (DOP853, tight
tolerances).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import integrate, optimize

from generators.contact import (
    entrainment_speed,
    film_thickness,
    hertz_contact,
    squeeze_film_damping,
)

SURF_OUTER, SURF_INNER, SURF_BALL = 0, 1, 2


class ReferenceModel:
    """Equations of motion of one prepared run (``generators.model.prepare``)."""

    def __init__(self, prep):
        g, op, rig = prep.geometry, prep.operating, prep.rig
        self.level, self.ehl = prep.level, prep.ehl
        self.z = g.ball_count
        self.ci, self.co = hertz_contact(g, "inner"), hertz_contact(g, "outer")
        self.ki, self.ko = self.ci.stiffness_constant, self.co.stiffness_constant
        self.kt = (self.ki ** (-2 / 3) + self.ko ** (-2 / 3)) ** -1.5
        self.gap = g.radial_internal_clearance / 2
        self.ms, self.mh, self.mb = rig.shaft_mass, rig.housing_mass, g.ball_mass
        self.kh, self.ch, self.cs = rig.pedestal_stiffness, rig.pedestal_damping, rig.shaft_damping
        self.tau = rig.contact_damping_time
        self.grav = 9.81 if rig.gravity else 0.0
        self.load = op.radial_load * np.array([math.cos(op.load_angle), math.sin(op.load_angle)])
        self.kl = rig.loading_stiffness
        self.anchor = prep.y0[:2].copy()
        f = prep.freqs
        self.ws = 2 * math.pi * op.shaft_frequency
        self.wc = 2 * math.pi * f.ftf
        self.wb = 2 * math.pi * f.bsf
        self.theta0 = prep.settings.cage_angle
        self.radius = g.pitch_diameter / 2
        self.wav = prep.wav
        self.lub = rig.lubricant
        self.u = entrainment_speed(g, op.shaft_frequency)
        self.floor = max(1.0, self.mb * self.wc**2 * self.radius)
        self.film_factor = rig.film_damping_factor
        self.nd = 4 + self.z if self.level == "full" else 4

    # waviness -------------------------------------------------------------------------
    def waviness(self, t):
        z = self.z
        theta = self.theta0 + self.wc * t + 2 * np.pi * np.arange(z) / z
        phi_s = self.ws * t
        w = np.zeros((8, z))
        for surf, ball, k, a, ph in self.wav[:, :5]:
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
    def _film(self, contact, q):
        # the kernel's smooth load floor: h(Q + Q_floor)
        return film_thickness(contact, self.lub, self.u, q + self.floor, load_floor=1e-30)

    def contact(self, delta, rate, which):
        if which == "series":
            kc = self.kt
        else:
            kc = self.ki if which == "inner" else self.ko
        if not self.ehl:
            if delta <= 0:
                return 0.0
            q = kc * delta**1.5 + self.tau * 1.5 * kc * math.sqrt(delta) * rate
            return max(q, 0.0)

        def film(q):
            if which == "series":
                return self._film(self.ci, q) + self._film(self.co, q)
            return self._film(self.ci if which == "inner" else self.co, q)

        if delta + film(0.0) <= 0:
            return 0.0
        # exact solution of Q = K (delta + h(Q))^1.5
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
        blend = q / (q + self.floor)
        if which == "series":
            hi, ho = self._film(self.ci, q), self._film(self.co, q)
            c_i = squeeze_film_damping(self.ci, self.lub, hi) * self.film_factor
            c_o = squeeze_film_damping(self.co, self.lub, ho) * self.film_factor
            kri, kro = self.ki ** (2 / 3), self.ko ** (2 / 3)
            ri, ro = kri / (kri + kro), kro / (kri + kro)
            c_sq = c_i * ro**2 + c_o * ri**2
        else:
            con = self.ci if which == "inner" else self.co
            c_sq = squeeze_film_damping(con, self.lub, self._film(con, q)) * self.film_factor
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
    from generators import _kernels as K

    y0 = prep.y0 if y0 is None else y0
    ehl = prep.ehl if ehl is None else ehl
    dt = record_dt / substeps
    st = np.zeros((n_record, K.N_OUT_STATE))
    ac = np.zeros((n_record, K.N_OUT_ACCEL))
    ld = np.zeros((1, 2, prep.geometry.ball_count))
    status, _, _ = K._rk4(
        prep.code,
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
    )
    assert status == K.STATUS_OK, status
    return st, ac
