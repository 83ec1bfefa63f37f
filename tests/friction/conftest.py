"""Shared materials and spectra of the rubber-friction tests (each test writes its own reference)."""

import numpy as np
import pytest

import persson_fp as pf


@pytest.fixture(scope="module")
def road():
    """A self-affine road: rms slope 1, H = 0.8, q from 1e3 to 1e8 1/m with a roll-off at 1e4 1/m."""
    return pf.SelfAffinePSD.from_rms_slope(1.0, H=0.8, q_l=1e3, q_r=1e4, q_s=1e8)


@pytest.fixture(scope="module")
def zener():
    """A Zener rubber: 3 MPa rubbery, 3 GPa glassy, tau = 1e-4 s, nu = 0.5."""
    return pf.viscoelastic.Zener(3e6, 3e9, 1e-4)


def prony_model(**kw):
    """A 12-element generalised Maxwell rubber made for these tests (times 1e-9..1e2 s)."""
    tau = np.logspace(-9, 2, 12)
    E_i = 4e7 * np.exp(-0.5 * ((np.log10(tau) + 4.0) / 2.5) ** 2)
    return pf.viscoelastic.Prony(2e6, E_i, tau, **kw)
