r"""The sliding contact problem: a rubber sliding on a rough surface as a :class:`ContactProblem`.

The contact-pressure PDF of a rubber sliding at speed :math:`v` obeys the same diffusion equation as the static
problem (Xu, Li, Chen, Zhou tutorial ``E:diffusion_equ``) with the variance :math:`V(\zeta; v)` of the sliding
response (:class:`persson_fp.theory.sliding.SlidingViscoelastic`; Persson, J. Chem. Phys. 115 (2001) 3840), so
:func:`persson_fp.exact`, :func:`persson_fp.solve` (every method) and ``compare()`` work on it.
"""

from __future__ import annotations

import numpy as np

from persson_fp.problems.contact import ContactProblem
from persson_fp.theory.sliding import SlidingViscoelastic, check_spectrum

__all__ = ["sliding_contact"]


def sliding_contact(
    psd,
    material,
    sigma0,
    velocity,
    temperature=None,
    fudge=None,
    modulus_in_G: str = "reduced",
    strain_softening=None,
) -> ContactProblem:
    r"""The contact problem of a rubber sliding at speed ``velocity`` under the nominal pressure ``sigma0``.

    A :class:`~persson_fp.ContactProblem` whose response is
    :class:`~persson_fp.theory.sliding.SlidingViscoelastic`: its ``exact()`` contact area at magnification
    :math:`\zeta` is Persson's sliding :math:`P(q) = \mathrm{erf}(1/(2\sqrt{G(q)}))` at :math:`q = \zeta q_l`,
    :math:`G = V(\zeta; v)/(2\sigma_0^2)` (Persson, J. Chem. Phys. 115 (2001) 3840), the same as
    :func:`persson_fp.rubber_friction`'s ``P``.

    With ``fudge=`` the problem is the fudge factor *in the loop*: the diffusion equation with
    :math:`B_2 = S(A^*)\,dV/d\zeta`, whose :math:`A^*(\zeta; v)` differs from :func:`persson_fp.rubber_friction`'s
    ``contact_area`` (there the fudge factor only weights the friction integrand and the contact area is the plain
    :math:`P(q_1)`, as in Persson's papers).

    The problem's ``E_star`` is the rms effective modulus :math:`\sqrt{V(\zeta_{max}; v)/(\frac{\pi}{2}\int q^3C\,dq)}`
    (pressure), used only in messages and the unit check; the mean separation, the gaps, leakage and adhesion need a
    stored elastic energy that a sliding rubber does not have, and refuse it with a ``ValueError``.

    Parameters
    ----------
    psd : PSD
        The rough surface's spectrum (the rigid counter-surface, e.g. a road).
    material : ViscoelasticMaterial
        The rubber (:mod:`persson_fp.theory.viscoelastic`).
    sigma0 : float or array_like, pressure
        Nominal contact pressure(s) (the loads ``p_bar``), finite and > 0.
    velocity : float, length/s
        Sliding speed (the spectrum's length unit per second), finite and > 0.
    temperature : float, optional, degrees C
        Required when the material has a shift law.
    fudge : None, str, FudgeFactor or callable
        The fudge factor in the loop (above); default None.
    modulus_in_G : {"reduced", "plain"}
        E/(1-nu^2) (default) or E in V.
    strain_softening : StrainSoftening, optional
        The Payne effect.

    Returns
    -------
    ContactProblem
        On the sliding response.

    Raises
    ------
    ValueError
        A parameter out of range (named).
    """
    check_spectrum(psd)
    response = SlidingViscoelastic(material, velocity, temperature, modulus_in_G, strain_softening)
    V_max = float(response.V(psd))
    m3 = float(psd.moment_unchecked(3, np.float64(psd.zeta_max)))
    E_rms = float(np.sqrt(V_max / (0.5 * np.pi * m3))) if m3 > 0 and V_max > 0 else 1.0
    return ContactProblem(psd, E_star=E_rms, p_bar=sigma0, fudge=fudge).with_response(response)
