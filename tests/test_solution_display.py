"""summary(), repr, HTML repr and plot() of a Solution on every problem kind: the true error where a closed form
exists, the solver's own estimate where none does (a moving yield wall, general coefficients)."""

import re

import numpy as np
import pytest

import persson_fp as pf

PSD = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=64.0)


def _general():
    dV = lambda z: float(PSD.dV_dzeta(z))  # noqa: E731
    return pf.FokkerPlanckProblem(
        PSD, p_bar=0.02, B1=lambda p, z: 0.3 * p * dV(z), B2=lambda p, z: 0.8 * np.ones_like(p) * dV(z)
    )


KINDS = {
    "elastic": (lambda: pf.ContactProblem.reference(p_bar_ratio=[0.5, 1.0]), True),
    "hardness": (lambda: pf.ContactProblem.reference(p_bar_ratio=0.5, hardness=0.1), True),
    "moving wall": (
        lambda: pf.ContactProblem(
            pf.SelfAffinePSD.from_rms_slope(4.0, H=0.8, q_l=1.0, q_r=1.0, q_s=10.0),
            p_bar=0.3,
            hardness=pf.hardness.PowerLaw(1.0, 0.2),
        ),
        False,
    ),
    "general": (_general, False),
}


@pytest.mark.parametrize("kind", list(KINDS))
def test_summary_repr_and_plot_on_every_problem_kind(kind):
    make, closed = KINDS[kind]
    pr = make()
    assert pr.has_closed_form == closed
    sol = pf.solve(pr, "fv", n_p=100, n_steps=60)
    line = sol.summary()
    r = repr(sol)
    html = sol._repr_html_()
    fig = sol.plot()
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "fv (markers)" in labels  # the legend names the numerical markers, not only the lines
    if closed:
        c = sol.compare().final()
        assert f"L1={c['L1']:.3e}" in line and f"|dA*|={c['area_error']:.3e}" in line
        assert f"error={'='}{c['area_error']:.2e}" in r
        assert "exact (lines)" in labels
        if pr.n_loads == 1:
            assert ax.get_title().startswith(f"fv: L1 = {c['L1']:.2e}")
        else:  # one legend entry per load, each with its own L1 (not the worst over the loads)
            for j in range(pr.n_loads):
                assert any(f"L1 = {sol.compare().L1[-1, j]:.2e}" in t for t in labels)
    else:
        with pytest.raises(ValueError, match="no exact"):
            sol.compare()
        est = sol.error_estimate
        dA = float(np.max(est["contact_area"][-1]))
        assert "estimate" in line and f"|dA*|~{dA:.3e}" in line
        # the load drift is the result's own: against p_bar, or against the first-moment law (general coefficients)
        law = sol.info.get("load_law")
        target = pr.p_bar if law is None else np.asarray(law).reshape(sol.load_all.shape)[-1]
        drift = float(np.max(np.abs(sol.load_all[-1] - target) / pr.p_bar))
        assert f"load drift={drift:.3e}" in line
        assert ("first-moment law" in line) == (law is not None)
        assert f"error=~{dA:.2e}" in r
        assert "no closed form" in ax.get_title() and f"{dA:.2e}" in ax.get_title()
    if pr.hardness is not None:
        assert re.search(r"A_pl=0\.\d+", line)
    assert "Solution(" in r and "persson-fp Solution" in html


@pytest.mark.filterwarnings("ignore:fv. P0 has negative values")  # a coarse grid, on purpose
def test_solve_command_writes_p0_and_plot_without_a_closed_form(tmp_path, capsys):
    from persson_fp.cli.app import main

    out, png = tmp_path / "p.csv", tmp_path / "p.png"
    # a moving yield wall: --output / --plot used to be refused
    argv = ["solve", "--hardness", "1", "--hardness-exponent", "0.2", "--n-p", "80", "--n-steps", "40"]
    assert main([*argv, "--output", str(out), "--plot", str(png)]) == 0
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    assert rows.shape == (80, 2) and png.stat().st_size > 0
    assert "estimate" in capsys.readouterr().out


def test_elastoplastic_example_shows_plasticity():
    """An elastoplastic example: A_pl of order 0.1 under both walls, quiet (no oscillation warning), its numbers."""
    import warnings

    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ex = pf.exact(pf.ContactProblem(psd, p_bar=0.03, hardness=0.08))
        pr2 = pf.ContactProblem(psd, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))
        sol = pf.solve(pr2, method="fv")
    assert (round(float(ex.elastic_area), 3), round(float(ex.plastic_area), 3)) == (0.171, 0.290)
    assert (round(float(sol.elastic_area[-1]), 3), round(float(sol.plastic_area[-1]), 3)) == (0.364, 0.117)
    est = float(sol.error_estimate["plastic_area"][-1, 0])
    assert 1e-5 < est < 1e-4 and "estimate" in sol.summary()


def test_area_plot_asymptote_is_not_clipped_onto_a_plateau():
    from persson_fp import plotting

    ratio = np.geomspace(1e-3, 3.0, 200)
    fig = plotting.plot_area_curve(
        ratio, {"none": pf.exact(pf.ContactProblem.reference(p_bar_ratio=ratio)).contact_area}
    )
    line = [ln for ln in fig.axes[0].get_lines() if "asymptote" in ln.get_label()][0]
    y = np.asarray(line.get_ydata(), float)
    assert np.nanmax(y) <= 1.0 and np.all(np.isnan(y[np.sqrt(2 / np.pi) * ratio > 1]))  # no flat segment at 1


def test_summary_names_a_worse_intermediate_station():
    """The error stated for the last station is not the whole story where an earlier one is worse (fv's default grid:
    L1 4.9e-4 at zeta = 2 against 7.2e-6 at zeta_max): the line says so, with compare()'s true errors."""
    pr = pf.ContactProblem.reference(p_bar_ratio=0.5)
    sol = pf.solve(pr, "fv", zeta_out=[2.0, 5.0, 20.0, pr.zeta_max])
    c = sol.compare()
    L1, dA = c.L1.max(axis=1), c.area_error.max(axis=1)
    assert np.argmax(L1) == 0 and L1[0] > 10 * L1[-1]
    assert f"; worst station zeta=2: L1={L1[0]:.3e}, |dA*|={dA[0]:.3e}" in sol.summary()
    single = pf.solve(pr, "fv")  # one station: nothing to add
    assert "worst station" not in single.summary()
