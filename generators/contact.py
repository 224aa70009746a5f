"""Hertzian point contact and elastohydrodynamic film of a deep groove ball bearing.

Sources (docs/model.md sections 3-4):

* [1] Hertz point contact in Hamrock's notation: curvature sum 1/R = 1/R_x + 1/R_y, ellipticity
  kappa = a/b from the exact elliptic-integral equation (3.1), load-deflection constant (3.3)
  K = pi kappa E' sqrt(R E / (4.5 K^3)).
* [2] Hamrock & Brewe (1983) closed-form approximations (3.2) of kappa and the elliptic integrals
  (coefficients recalled in docs/model.md; accuracy verified there to 2 % in K).
* [3] Hamrock & Dowson (1977) isothermal central and minimum film thickness (4.2), (4.3).
* [4] Film stiffness k_f = Q / (0.067 h_c) (4.4) and the squeeze-film damping of a flooded
  ellipsoidal gap (4.5), both derived in docs/model.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy import optimize, special

from ._validate import ParameterError, check_choice, check_real, check_real_array
from .params import BearingGeometry, Lubricant

__all__ = [
    "ContactGeometry",
    "HertzContact",
    "contact_geometry",
    "ellipticity_exact",
    "ellipticity_hamrock_brewe",
    "hertz_contact",
    "load_deflection_constants",
    "series_constant",
    "entrainment_speed",
    "film_thickness",
    "film_stiffness",
    "squeeze_film_damping",
    "squeeze_film_shape_factor",
    "contact_static_capacity",
]

Race = Literal["inner", "outer"]
Method = Literal["exact", "hamrock-brewe"]

#: Exponent of the load in the Hamrock-Dowson central film thickness (4.2).
FILM_LOAD_EXPONENT = -0.067


@dataclass(frozen=True, slots=True)
class ContactGeometry:
    """Principal radii of a ball-race contact [m].

    Attributes
    ----------
    rx : float
        Effective radius in the rolling direction R_x [m].
    ry : float
        Effective radius across the rolling direction R_y [m].
    """

    rx: float
    ry: float

    @property
    def curvature_sum(self) -> float:
        """Sum of curvatures 1/R = 1/R_x + 1/R_y [1/m] (Harris's sum rho)."""
        return 1.0 / self.rx + 1.0 / self.ry

    @property
    def effective_radius(self) -> float:
        """R = 1 / (1/R_x + 1/R_y) [m]."""
        return 1.0 / self.curvature_sum

    @property
    def radius_ratio(self) -> float:
        """alpha_r = R_y / R_x [-]."""
        return self.ry / self.rx

    @property
    def curvature_difference(self) -> float:
        """F(rho) = (R_y - R_x) / (R_y + R_x) [-]."""
        return (self.ry - self.rx) / (self.ry + self.rx)


def contact_geometry(geometry: BearingGeometry, race: Race) -> ContactGeometry:
    """Principal radii of the ball-inner or ball-outer groove contact (docs/model.md 3.1).

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry.
    race : {"inner", "outer"}
        Which contact.

    Returns
    -------
    ContactGeometry
        R_x = d (D -/+ d cos alpha) / (2D), R_y = f d / (2f - 1) [m].
    """
    check_choice("race", race, ("inner", "outer"))
    d, pd = geometry.ball_diameter, geometry.pitch_diameter
    c = d * math.cos(geometry.contact_angle)
    if race == "inner":
        rx = d * (pd - c) / (2.0 * pd)
        f = geometry.inner_groove_curvature
    else:
        rx = d * (pd + c) / (2.0 * pd)
        f = geometry.outer_groove_curvature
    ry = f * d / (2.0 * f - 1.0)
    return ContactGeometry(rx=rx, ry=ry)


def _curvature_difference_of_kappa(kappa: float) -> float:
    m = 1.0 - 1.0 / kappa**2
    e = special.ellipe(m)
    k = special.ellipk(m)
    return ((kappa**2 + 1.0) * e - 2.0 * k) / ((kappa**2 - 1.0) * e)


def ellipticity_exact(cg: ContactGeometry) -> tuple[float, float, float]:
    """Ellipticity and elliptic integrals from the exact Hertz equation (docs/model.md 3.1).

    Solves F(rho) = [(kappa^2 + 1) E(m) - 2 K(m)] / [(kappa^2 - 1) E(m)], m = 1 - 1/kappa^2.

    Parameters
    ----------
    cg : ContactGeometry
        Contact radii (R_y > R_x for a groove contact).

    Returns
    -------
    kappa, E, K : float
        Ellipticity a/b [-] and complete elliptic integrals of the 2nd and 1st kind [-].
    """
    target = cg.curvature_difference
    if not 0.0 < target < 1.0:
        raise ParameterError(
            f"curvature_difference = {target:g} is outside (0, 1): the groove must be wider than "
            "the ball curvature in the rolling direction (R_y > R_x)"
        )
    kappa = optimize.brentq(
        lambda k: _curvature_difference_of_kappa(k) - target,
        1.0 + 1e-9,
        1e3,
        xtol=1e-14,
        rtol=1e-14,
    )
    m = 1.0 - 1.0 / kappa**2
    return float(kappa), float(special.ellipe(m)), float(special.ellipk(m))


def ellipticity_hamrock_brewe(cg: ContactGeometry) -> tuple[float, float, float]:
    """Hamrock-Brewe closed-form ellipticity and elliptic integrals (docs/model.md 3.2).

    kappa = 1.0339 alpha_r^0.6360, E = 1.0003 + 0.5968 / alpha_r, K = 1.5277 + 0.6023 ln alpha_r.

    Parameters
    ----------
    cg : ContactGeometry
        Contact radii.

    Returns
    -------
    kappa, E, K : float
        Ellipticity and elliptic integrals [-].
    """
    ar = cg.radius_ratio
    return 1.0339 * ar**0.6360, 1.0003 + 0.5968 / ar, 1.5277 + 0.6023 * math.log(ar)


@dataclass(frozen=True, slots=True)
class HertzContact:
    """Hertz point contact of one ball with one groove.

    Attributes
    ----------
    geometry : ContactGeometry
        Principal radii [m].
    effective_modulus : float
        E' [Pa].
    kappa : float
        Ellipticity a/b [-].
    elliptic_e, elliptic_k : float
        Complete elliptic integrals of the 2nd and 1st kind [-].
    stiffness_constant : float
        K in Q = K delta^1.5 [N/m^1.5].
    """

    geometry: ContactGeometry
    effective_modulus: float
    kappa: float
    elliptic_e: float
    elliptic_k: float
    stiffness_constant: float

    def load(self, deflection: float | np.ndarray) -> float | np.ndarray:
        """Contact load Q = K [delta]_+^1.5 [N] for an approach ``deflection`` [m].

        Parameters
        ----------
        deflection : float or ndarray
            Elastic approach of ball and groove [m]; a negative one (a gap) carries no load.

        Returns
        -------
        float or ndarray
            Contact load [N].
        """
        d = np.maximum(check_real_array("deflection", deflection, unit="m"), 0.0)
        return self.stiffness_constant * d**1.5

    def deflection(self, load: float | np.ndarray) -> float | np.ndarray:
        """Approach delta = (Q / K)^(2/3) [m] for a load ``load`` [N] >= 0.

        Parameters
        ----------
        load : float or ndarray
            Contact load [N], >= 0.

        Returns
        -------
        float or ndarray
            Elastic approach [m].
        """
        q = check_real_array("load", load, low=0.0, unit="N")
        return (q / self.stiffness_constant) ** (2.0 / 3.0)

    def linear_stiffness(self, load: float | np.ndarray) -> float | np.ndarray:
        """Tangent stiffness dQ/d delta = 1.5 K^(2/3) Q^(1/3) [N/m].

        Parameters
        ----------
        load : float or ndarray
            Contact load [N], >= 0.

        Returns
        -------
        float or ndarray
            Tangent stiffness at that load [N/m] (0 unloaded).
        """
        q = check_real_array("load", load, low=0.0, unit="N")
        return 1.5 * self.stiffness_constant ** (2.0 / 3.0) * np.cbrt(q)

    def semi_axes(self, load: float) -> tuple[float, float]:
        """Contact ellipse semi-axes (a across rolling, b along rolling) [m] at ``load`` [N].

        Parameters
        ----------
        load : float
            Contact load [N], >= 0.

        Returns
        -------
        a, b : float
            Semi-axes across and along the rolling direction [m].
        """
        check_real("load", load, low=0.0, unit="N")
        r = self.geometry.effective_radius
        base = 6.0 * self.elliptic_e * load * r / (math.pi * self.effective_modulus)
        return (self.kappa**2 * base) ** (1 / 3), (base / self.kappa) ** (1 / 3)

    def max_pressure(self, load: float) -> float:
        """Maximum Hertz pressure p_max = 3 Q / (2 pi a b) [Pa] at ``load`` [N].

        Parameters
        ----------
        load : float
            Contact load [N].

        Returns
        -------
        float
            Maximum contact pressure [Pa]; 0 for a load <= 0.
        """
        if check_real("load", load, unit="N") <= 0:
            return 0.0
        a, b = self.semi_axes(load)
        return 3.0 * load / (2.0 * math.pi * a * b)


def hertz_contact(
    geometry: BearingGeometry, race: Race, *, method: Method = "exact"
) -> HertzContact:
    """Hertz point contact of the ball with the inner or outer groove (docs/model.md 3.3).

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry and materials.
    race : {"inner", "outer"}
        Which contact.
    method : {"exact", "hamrock-brewe"}
        Ellipticity and elliptic integrals from the exact equation (root of (3.1) with scipy)
        or from the Hamrock-Brewe closed form (3.2).

    Returns
    -------
    HertzContact
        With K = pi kappa E' sqrt(R E / (4.5 K^3)) [N/m^1.5].

    Examples
    --------
    >>> from generators import bearing, hertz_contact
    >>> c = hertz_contact(bearing("6205"), "inner")
    >>> f"{c.stiffness_constant:.3e}"
    '2.557e+10'
    """
    check_choice("method", method, ("exact", "hamrock-brewe"))
    cg = contact_geometry(geometry, race)
    kappa, e, k = ellipticity_exact(cg) if method == "exact" else ellipticity_hamrock_brewe(cg)
    ep = geometry.effective_modulus
    kc = math.pi * kappa * ep * math.sqrt(cg.effective_radius * e / (4.5 * k**3))
    return HertzContact(cg, ep, kappa, e, k, kc)


def series_constant(k_inner: float, k_outer: float) -> float:
    """Load-deflection constant of a ball between both races (docs/model.md 3.4) [N/m^1.5].

    K_tot = (K_i^(-2/3) + K_o^(-2/3))^(-3/2).

    Parameters
    ----------
    k_inner, k_outer : float
        Load-deflection constants of the inner and the outer contact [N/m^1.5].

    Returns
    -------
    float
        The two contacts' series constant [N/m^1.5].
    """
    check_real("k_inner", k_inner, low=0.0, low_inclusive=False, unit="N/m^1.5")
    check_real("k_outer", k_outer, low=0.0, low_inclusive=False, unit="N/m^1.5")
    return (k_inner ** (-2.0 / 3.0) + k_outer ** (-2.0 / 3.0)) ** (-1.5)


def load_deflection_constants(
    geometry: BearingGeometry, *, method: Method = "exact"
) -> tuple[float, float, float]:
    """K_i, K_o and the series constant K_tot of a bearing [N/m^1.5].

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry.
    method : {"exact", "hamrock-brewe"}
        See :func:`hertz_contact`.

    Returns
    -------
    k_inner, k_outer, k_total : float
        Load-deflection constants [N/m^1.5].
    """
    ki = hertz_contact(geometry, "inner", method=method).stiffness_constant
    ko = hertz_contact(geometry, "outer", method=method).stiffness_constant
    return ki, ko, series_constant(ki, ko)


def contact_static_capacity(geometry: BearingGeometry, *, max_pressure: float = 4.2e9) -> float:
    """Ball load at which the more heavily stressed contact reaches ``max_pressure`` [N].

    ISO 76 defines the static load rating of a radial ball bearing as the load that gives a
    4200 MPa maximum contact pressure at the most heavily loaded contact; with Stribeck's
    Q_max = 5 F_r / Z this gives an estimate C_0r ~ Z Q_limit / 5 (compare with catalogue values).

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry.
    max_pressure : float
        Pressure limit [Pa].

    Returns
    -------
    float
        Ball load at the limit [N].
    """
    check_real("max_pressure", max_pressure, low=1e8, high=1e11, unit="Pa")
    # p_max scales as Q^(1/3): p(Q) = p(1 N) * Q^(1/3)
    p_unit = max(hertz_contact(geometry, r).max_pressure(1.0) for r in ("inner", "outer"))
    return (max_pressure / p_unit) ** 3


# ---------------------------------------------------------------------------------------- EHL


def entrainment_speed(geometry: BearingGeometry, shaft_frequency_hz: float) -> float:
    """Mean rolling (entrainment) speed of both contacts, u = omega_s (D^2 - d^2) / (4 D) [m/s].

    For alpha = 0 and a stationary outer ring (docs/model.md section 2).

    Parameters
    ----------
    geometry : BearingGeometry
        Bearing geometry (ball and pitch diameters [m], contact angle [rad]).
    shaft_frequency_hz : float
        Shaft rotation frequency [Hz], 0 .. 2000.

    Returns
    -------
    float
        Entrainment speed [m/s].
    """
    fs = check_real("shaft_frequency_hz", shaft_frequency_hz, low=0.0, high=2000.0, unit="Hz")
    d, pd = geometry.ball_diameter * math.cos(geometry.contact_angle), geometry.pitch_diameter
    return 2.0 * math.pi * fs * (pd**2 - d**2) / (4.0 * pd)


def film_thickness(
    contact: HertzContact,
    lubricant: Lubricant,
    entrainment_speed_m_s: float,
    load: float | np.ndarray,
    *,
    kind: Literal["central", "minimum"] = "central",
    load_floor: float = 1.0,
) -> float | np.ndarray:
    """Hamrock-Dowson isothermal EHL film thickness of a point contact (docs/model.md 4.1) [m].

    h_c = 2.69 R_x U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k_e)),
    h_min = 3.63 R_x U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k_e)),
    U = eta_0 u / (E' R_x), G = alpha_p E', W = Q / (E' R_x^2), k_e = 1.03 (R_y/R_x)^0.64.

    Parameters
    ----------
    contact : HertzContact
        The contact (radii and E').
    lubricant : Lubricant
        Viscosity and pressure-viscosity coefficient; its ``film_factor`` multiplies the result.
    entrainment_speed_m_s : float
        Entrainment speed u [m/s] (see :func:`entrainment_speed`).
    load : float or ndarray
        Contact load Q [N]; evaluated at max(Q, ``load_floor``) because h -> inf as W -> 0.
    kind : {"central", "minimum"}
        Central film h_c (used in the dynamics) or minimum film h_min (film parameter).
    load_floor : float
        Smallest load used [N].

    Returns
    -------
    float or ndarray
        Film thickness [m].
    """
    check_choice("kind", kind, ("central", "minimum"))
    u = check_real("entrainment_speed_m_s", entrainment_speed_m_s, low=0.0, high=1e3, unit="m/s")
    check_real("load_floor", load_floor, low=0.0, low_inclusive=False, unit="N")
    cg, ep = contact.geometry, contact.effective_modulus
    rx, ry = cg.rx, cg.ry
    q = np.maximum(check_real_array("load", load, unit="N"), load_floor)
    big_u = lubricant.viscosity * u / (ep * rx)
    big_g = lubricant.pressure_viscosity_coefficient * ep
    big_w = q / (ep * rx**2)
    ke = 1.03 * (ry / rx) ** 0.64
    if kind == "central":
        h = (
            2.69
            * rx
            * big_u**0.67
            * big_g**0.53
            * big_w**FILM_LOAD_EXPONENT
            * (1 - 0.61 * math.exp(-0.73 * ke))
        )
    else:
        h = 3.63 * rx * big_u**0.68 * big_g**0.49 * big_w**-0.073 * (1 - math.exp(-0.68 * ke))
    h = h * lubricant.film_factor
    return float(h) if np.ndim(h) == 0 else h


def rigid_isoviscous_coefficient(
    contact: HertzContact, lubricant: Lubricant, entrainment_speed_m_s: float
) -> float:
    """Load coefficient C of a flooded rolling point contact at light load [N m^0.5].

    Hamrock and Dowson's rigid-isoviscous regime (no elastic flattening, no piezoviscosity):
    H_min (W / U)^2 = 128 a_r l_b^2 (0.131 atan(a_r / 2) + 1.683)^2, a_r = R_y / R_x,
    l_b = (1 + 2 / (3 a_r))^-1, H = h / R_x, U and W as in :func:`film_thickness`; so a film
    of thickness h carries w = C / sqrt(h), C = eta_0 u R_x^1.5 sqrt(H_min (W / U)^2)
    (docs/model.md 4.6). The lubricant's ``film_factor`` (starvation) scales h, so C^2.

    Parameters
    ----------
    contact : HertzContact
        The contact (radii).
    lubricant : Lubricant
        Its viscosity eta_0 [Pa s] and ``film_factor``.
    entrainment_speed_m_s : float
        Entrainment speed u [m/s] (:func:`entrainment_speed`).

    Returns
    -------
    float
        C [N m^0.5]: 2.2e-3 at the 6205's inner race and 3.3e-3 at its outer at 1800 rpm in
        VG 68 at 40 C.
    """
    u = check_real("entrainment_speed_m_s", entrainment_speed_m_s, low=0.0, high=1e3, unit="m/s")
    rx, ry = contact.geometry.rx, contact.geometry.ry
    ratio = ry / rx
    side = 1.0 / (1.0 + 2.0 / (3.0 * ratio))
    film = 128.0 * ratio * side**2 * (0.131 * math.atan(ratio / 2.0) + 1.683) ** 2
    return lubricant.viscosity * u * rx**1.5 * math.sqrt(film * lubricant.film_factor)


def film_stiffness(load: float, central_film_thickness: float) -> float:
    """Film stiffness k_f = |dQ/dh_c| = Q / (0.067 h_c) (docs/model.md 4.4) [N/m].

    Parameters
    ----------
    load : float
        Contact load [N], >= 0.
    central_film_thickness : float
        Central film thickness h_c at that load [m], > 0 (:func:`film_thickness`).

    Returns
    -------
    float
        Film stiffness [N/m].
    """
    q = check_real("load", load, low=0.0, unit="N")
    h = check_real(
        "central_film_thickness", central_film_thickness, low=0.0, low_inclusive=False, unit="m"
    )
    return q / (-FILM_LOAD_EXPONENT * h)


def squeeze_film_shape_factor(epsilon: float) -> float:
    """f(eps) ~ 2 - eps^0.75 of the squeeze-film damping (docs/model.md 4.5, +/- 5 %) [-].

    Parameters
    ----------
    epsilon : float
        The contact's radius ratio R_x / R_y, in [0, 1].

    Returns
    -------
    float
        f(eps), dimensionless.
    """
    e = check_real("epsilon", epsilon, low=0.0, high=1.0)
    return 2.0 - e**0.75


def squeeze_film_damping(
    contact: HertzContact, lubricant: Lubricant, central_film_thickness: float | np.ndarray
) -> float | np.ndarray:
    """Squeeze-film damping of an ellipsoidal flooded gap (docs/model.md 4.5, option D2) [N s/m].

    c_sq = 6 pi eta_0 R_x^1.5 R_y^0.5 f(R_x/R_y) / h_c. An order-of-magnitude estimate (no
    piezo-viscosity, cavitation, starvation or elastic flattening).

    Parameters
    ----------
    contact : HertzContact
        The contact (its radii R_x, R_y [m]).
    lubricant : Lubricant
        The lubricant (its dynamic viscosity eta_0 [Pa s]).
    central_film_thickness : float or ndarray
        Central film thickness h_c [m], > 0.

    Returns
    -------
    float or ndarray
        Squeeze-film damping coefficient [N s/m].
    """
    check_real_array(
        "central_film_thickness", central_film_thickness, low=0.0, low_inclusive=False, unit="m"
    )
    cg = contact.geometry
    f = squeeze_film_shape_factor(min(cg.rx / cg.ry, 1.0))
    coef = 6.0 * math.pi * lubricant.viscosity * cg.rx**1.5 * cg.ry**0.5 * f
    return (
        coef / np.asarray(central_film_thickness, dtype=float)
        if np.ndim(central_film_thickness)
        else coef / float(central_film_thickness)
    )
