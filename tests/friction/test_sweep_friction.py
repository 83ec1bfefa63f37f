"""pf.sweep over rubbers, speeds and temperatures: the quantities friction and sliding_area are
pf.rubber_friction's, one by one."""

import pytest

import persson_fp as pf


def test_sweep_friction_equals_one_by_one(road):
    mat = pf.viscoelastic.Zener(3e6, 3e9, 1e-4, T_ref=20.0, shift=pf.viscoelastic.WLF(8.86, 101.6))
    models = {f"{v:g} m/s, {T:g} C": {"material": mat, "velocity": v, "temperature": T, "fudge": "YP08"}
              for v in (1e-3, 1e-1) for T in (0.0, 40.0)}  # fmt: skip
    loads = [1e5, 2e5]
    res = pf.sweep(road, loads, models, quantities=["friction", "sliding_area"], progress=False)
    for j, spec in enumerate(models.values()):
        for k, p in enumerate(loads):
            one = pf.rubber_friction(road, mat, p, spec["velocity"], spec["temperature"])
            assert res["friction"][0, j, k] == pytest.approx(float(one.mu), rel=1e-12)
            assert res["sliding_area"][0, j, k] == pytest.approx(float(one.contact_area), rel=1e-12)


def test_sweep_friction_of_a_static_model_is_a_recorded_failure(road):
    with pytest.warns(UserWarning):
        res = pf.sweep(road, [1e5], ["YP08"], quantities=["friction"], progress=False)
    assert res.failures and "sliding model" in str(res.failures[0])


@pytest.mark.parametrize(
    "model, message",
    [({"material": 1.0}, "velocity"), ({"velocity": 1.0, "material": None, "hardness": 1.0}, "sliding")],
)
def test_sweep_refuses_an_incomplete_sliding_model(road, model, message):
    with pytest.raises(ValueError, match=message):
        pf.sweep(road, [1e5], model, quantities=["friction"], progress=False)
