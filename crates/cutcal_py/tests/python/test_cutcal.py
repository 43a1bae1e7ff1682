"""End-to-end tests of the `cutcal` Python module against the `cutcal` command line.

Every expected value comes from the CLI run on the same fixtures (an independent face over the
same library: argument parsing, file reading and JSON writing are the CLI's own), or from the
paper's Table 4 where stated.
"""

import json
import math

import numpy as np
import pytest

import cutcal
from conftest import run_cli

C38 = "fixtures/materials/c38.toml"
C38_TESTS = "fixtures/tests/c38.csv"
AISI = "fixtures/materials/aisi1045.toml"
AISI_TESTS = "fixtures/tests/aisi1045.csv"
AISI_JC = "fixtures/jc/aisi1045_jaspers2002.toml"
C38_JC = "fixtures/jc/c38_table5.toml"


def assert_close(a, b, rel=1e-12, path="$"):
    """Recursive equality of JSON-like values, numbers to a relative tolerance."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and set(a) == set(b), f"{path}: keys {sorted(a)} != {sorted(b)}"
        for k in a:
            assert_close(a[k], b[k], rel, f"{path}.{k}")
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{path}: lengths differ"
        for i, (x, y) in enumerate(zip(a, b)):
            assert_close(x, y, rel, f"{path}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert math.isclose(a, b, rel_tol=rel, abs_tol=1e-300), f"{path}: {a} != {b}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


def pick(tests, test_id):
    return next(t for t in tests if t.test == test_id)


@pytest.mark.parametrize("model", ["enhanced", "original"])
def test_identify_c38_test3_equals_the_cli_json(model):
    cli = json.loads(run_cli("identify", "--material", C38, "--tests", C38_TESTS, "--test", "3",
                             "--model", model, "--preset", "paper", "--json").stdout)
    m = cutcal.Material.from_toml(C38)
    t3 = pick(cutcal.read_tests(C38_TESTS, as_frame=False), "3")
    res = cutcal.identify(m, t3, model=model, preset="paper")
    assert_close(res.to_dict(), cli, rel=1e-12)
    assert res.at_bounds == cli["at_bounds"]
    assert math.isclose(res.jc.a_mpa, cli["jc"]["a_mpa"], rel_tol=1e-12)
    # Paper Table 4: A = 589 (enhanced) / 671 (original) MPa; cutcal within 1.5 % (README table).
    assert abs(res.jc.a_mpa / {"enhanced": 589.0, "original": 671.0}[model] - 1) < 0.015


def test_identify_with_bootstrap_spread_equals_the_cli():
    args = ["identify", "--material", C38, "--tests", C38_TESTS, "--test", "3", "--json",
            "--starts", "4", "--bootstrap", "6", "--bootstrap-starts", "2", "--seed", "7"]
    cli = json.loads(run_cli(*args).stdout)
    m = cutcal.Material.from_toml(C38)
    t3 = pick(cutcal.read_tests(C38_TESTS, as_frame=False), "3")
    res = cutcal.identify(m, t3, starts=4, bootstrap=6, bootstrap_starts=2, seed=7)
    assert_close(res.to_dict(), cli)
    assert_close(res.spread, cli["bootstrap"])
    assert cutcal.identify(m, t3, starts=4).spread is None


def test_identify_default_preset_equals_the_cli_default():
    cli = json.loads(run_cli("identify", "--material", C38, "--tests", C38_TESTS, "--test", "3", "--json").stdout)
    m = cutcal.Material.from_toml(C38)
    t3 = pick(cutcal.read_tests(C38_TESTS, as_frame=False), "3")
    assert_close(cutcal.identify(m, t3).to_dict(), cli, rel=1e-12)


def test_fields_are_numpy_arrays_with_units_in_their_names_and_match_the_cli_csv(tmp_path):
    out = tmp_path / "fields.csv"
    run_cli("identify", "--material", C38, "--tests", C38_TESTS, "--test", "3", "--fields-csv", out)
    header, *rows = out.read_text().splitlines()
    m = cutcal.Material.from_toml(C38)
    t3 = pick(cutcal.read_tests(C38_TESTS, as_frame=False), "3")
    res = cutcal.identify(m, t3)
    f = res.fields
    names = ["x_mm", "gamma", "gamma_dot_per_s", "eps", "eps_dot_per_s", "tau_mpa", "sigma_eff_mpa", "temperature_c"]
    assert list(f) == names == header.split(",")
    table = np.array([[float(x) for x in r.split(",")] for r in rows])
    for j, name in enumerate(names):
        a = f[name]
        assert isinstance(a, np.ndarray) and a.dtype == np.float64 and a.shape == (201,), name
        # The CSV is rounded (6 decimals / 6 significant digits / 4 decimals): compare at that precision.
        assert np.allclose(a, table[:, j], rtol=1e-5, atol=1e-4), name
    # x spans the zone -h/2 .. h/2 with the h the identification used (by default the forward model's
    # l_AB/C0, reported as h_mm).
    h = res.to_dict()["h_mm"]
    assert 0.0 < h < 0.075
    assert f["x_mm"][0] == pytest.approx(-h / 2) and f["x_mm"][-1] == pytest.approx(h / 2)
    few = cutcal.identify(m, t3, field_points=7).fields
    assert all(v.shape == (7,) for v in few.values())


PREDICT_CASES = [
    # AISI 1045 (Ivester et al. 2000 conditions, sharp tool), C38 (paper Table 2, 25 um edge radius).
    (AISI, AISI_JC, AISI_TESTS),
    (C38, C38_JC, C38_TESTS),
]


@pytest.mark.parametrize("material,jc,tests", PREDICT_CASES)
@pytest.mark.parametrize("sharp", [False, True])
def test_predict_equals_the_cli_json(material, jc, tests, sharp):
    flags = ["--sharp"] if sharp else []
    cli = json.loads(run_cli("predict", "--material", material, "--jc", jc, "--tests", tests, "--json", *flags).stdout)
    m = cutcal.Material.from_toml(material)
    j = cutcal.JcParams.from_toml(jc)
    py = cutcal.predict(m, j, cutcal.read_tests(tests, as_frame=False), sharp=sharp)
    assert_close(py, cli)
    # A DataFrame from read_tests gives the same document.
    assert_close(cutcal.predict(m, j, cutcal.read_tests(tests), sharp=sharp), cli)


@pytest.mark.parametrize("material,jc,tests", PREDICT_CASES)
def test_predict_many_equals_the_cli_per_condition(material, jc, tests):
    cli = json.loads(run_cli("predict", "--material", material, "--jc", jc, "--tests", tests, "--json").stdout)
    m = cutcal.Material.from_toml(material)
    j = cutcal.JcParams.from_toml(jc)
    rows = [t.to_dict() for t in cutcal.read_tests(tests, as_frame=False)]
    keys = ("speed_m_min", "uncut_mm", "width_mm", "rake_deg", "edge_radius_um", "flank_wear_mm")
    cols = {k: np.array([np.nan if t[k] is None else t[k] for t in rows]) for k in keys}
    out = cutcal.predict_many(m, j, **cols)
    for i, row in enumerate(cli["rows"]):
        assert out["converged"][i]
        assert math.isclose(out["fc_n"][i], row["fc_n"], rel_tol=1e-9)
        assert math.isclose(out["ft_n"][i], row["ft_n"], rel_tol=1e-9)
        assert math.isclose(out["tc_mm"][i], row["tc_mm"], rel_tol=1e-9)
        assert math.isclose(out["t_int_c"][i], row["prediction"]["temperature_int_c"], rel_tol=1e-9)


def test_predict_many_broadcasts_and_masks_failures():
    m = cutcal.Material.from_toml(AISI)
    jc = cutcal.JcParams.from_toml(AISI_JC)
    # 3 speeds x 2 rakes; one invalid speed is masked with its reason, never NaN.
    speeds = np.array([[150.0], [200.0], [-5.0]])
    grid = cutcal.predict_many(m, jc, speeds, 0.15, 1.6, np.array([-7.0, 5.0]))
    assert grid["fc_n"].shape == (3, 2) and grid["converged"].shape == (3, 2)
    assert grid["converged"][:2].all() and not grid["converged"][2].any()
    assert grid["fc_n"].mask[2].all() and np.isfinite(grid["fc_n"].data).all()
    assert "speed_m_per_s" in grid["errors"][4]
    assert set(grid) >= {"fc_n", "ft_n", "fc_n_per_mm", "ft_n_per_mm", "tc_mm", "t_ab_c", "t_int_c", "phi_deg"}
    # A stated edge radius adds force (Waldorf et al. 1998 ploughing): Ft grows.
    sharp = cutcal.predict_many(m, jc, 200.0, 0.15, 1.6, -7.0)
    edged = cutcal.predict_many(m, jc, 200.0, 0.15, 1.6, -7.0, edge_radius_um=25.0)
    assert edged["ft_n"] > sharp["ft_n"]


def test_cards_rendered_from_python_are_byte_identical_to_the_cli(tmp_path):
    out = tmp_path / "cards"
    run_cli("export", "--material", C38, "--jc", C38_JC, "--format", "all", "--out", out)
    m = cutcal.Material.from_toml(C38)
    jc = cutcal.JcParams.from_toml(C38_JC)
    files = cutcal.render(m, jc, "all")
    assert sorted(files) == sorted(p.name for p in out.iterdir())
    for name, text in files.items():
        assert text.encode() == (out / name).read_bytes(), name
    # Other options: SI units, a 50 K step, LS-DYNA only.
    out2 = tmp_path / "si"
    run_cli("export", "--material", C38, "--jc", C38_JC, "--format", "lsdyna", "--units", "si",
            "--t-step-c", "50", "--out", out2)
    si = cutcal.render(m, jc, "lsdyna", units="si", t_step_c=50.0)
    assert si["c38_lsdyna.k"].encode() == (out2 / "c38_lsdyna.k").read_bytes()
    written = cutcal.export(m, jc, format="matml", out=tmp_path / "py")
    assert [p.rsplit("/", 1)[-1] for p in written] == ["c38_matml.xml"]
    assert (tmp_path / "py" / "c38_matml.xml").read_bytes() == (out / "c38_matml.xml").read_bytes()


def test_contact_temperature_and_cutting_speed_give_the_clis_lsdyna_deck(tmp_path):
    out = tmp_path / "cli"
    run_cli("export", "--material", C38, "--jc", C38_JC, "--format", "lsdyna", "--out", out,
            "--contact-temperature-c", "600", "--cutting-speed-m-min", "180")
    m, jc = cutcal.Material.from_toml(C38), cutcal.JcParams.from_toml(C38_JC)
    deck = cutcal.render(m, jc, "lsdyna", contact_temperature_c=600.0, cutting_speed_m_per_min=180.0)
    assert deck["c38_lsdyna.k"] == (out / "c38_lsdyna.k").read_text()
    # The options reach the deck: Tc stated, and ENDTIM = 8 mm / (180 m/min) = 8e-3 / 3 s (paper Sec 5.1).
    assert "Tc = 600. degC" in deck["c38_lsdyna.k"] and "ENDTIM = 0.002666667" in deck["c38_lsdyna.k"]
    assert deck != cutcal.render(m, jc, "lsdyna")
    written = cutcal.export(m, jc, format="lsdyna", out=tmp_path / "py", contact_temperature_c=600.0,
                            cutting_speed_m_per_min=180.0)
    assert [open(p).read() for p in written] == [(out / "c38_lsdyna.k").read_text()]
    # Above the melting temperature the exporter refuses, as the CLI does.
    with pytest.raises(cutcal.CutcalError, match="contact_temperature_c"):
        cutcal.render(m, jc, "lsdyna", contact_temperature_c=1500.0)


def test_joint_identification_equals_the_cli_and_withholds_an_undetermined_set():
    args = ["identify", "--method", "oxley", "--material", AISI, "--tests", AISI_TESTS, "--starts", "2", "--json"]
    cli = json.loads(run_cli(*args).stdout)
    m = cutcal.Material.from_toml(AISI)
    tests = cutcal.read_tests(AISI_TESTS, as_frame=False)
    r = cutcal.joint(m, tests, starts=2)
    assert_close(r["report"], cli, rel=1e-12)
    # Four tests (Ivester et al. 2000) determine 2 of 5 directions: refused, no set returned.
    assert r["status"] == cli["verdict"]["status"] == "undetermined"
    assert not r["determined"] and r["jc"] is None
    assert r["effective_rank"] == cli["identifiability"]["effective_rank"] < r["free_parameters"] == 5
    assert math.isclose(r["condition_number"], cli["identifiability"]["condition_number"], rel_tol=1e-12)
    assert r["verdict"].startswith("REFUSED, not determined")
    assert math.isclose(r["best_fit"].a_mpa, cli["jc"]["a_pa"] / 1e6, rel_tol=1e-12)


def test_joint_with_fixed_parameters_equals_the_cli():
    # n, C and m fixed at the Jaspers & Dautzenberg 2002 set (fixtures/jc/aisi1045_jaspers2002.toml).
    fix = {"n": 0.234, "c": 0.0134, "m": 1.0}
    args = ["identify", "--method", "oxley", "--material", AISI, "--tests", AISI_TESTS, "--starts", "2", "--json"]
    for k, v in fix.items():
        args += ["--fix", f"{k}={v}"]
    cli = json.loads(run_cli(*args).stdout)
    r = cutcal.joint(cutcal.Material.from_toml(AISI), cutcal.read_tests(AISI_TESTS, as_frame=False), starts=2,
                     fix=fix)
    assert_close(r["report"], cli, rel=1e-12)
    assert r["determined"] == (cli["verdict"]["status"] == "determined")
    assert (r["jc"] is not None) == r["determined"]
    if r["determined"]:
        assert math.isclose(r["jc"].b_mpa, cli["jc"]["b_pa"] / 1e6, rel_tol=1e-12)
    with pytest.raises(cutcal.CutcalError, match="--fix q=1"):
        cutcal.joint(cutcal.Material.from_toml(AISI), [], fix={"q": 1.0})


def test_joint_returns_the_set_when_determined_and_equals_the_cli(tmp_path):
    # Six conditions around Ivester et al. 2000's (200 m/min, 0.15 mm, -7 deg, 1.6 mm) whose Fc, Ft
    # and tc are cutcal's own predictions with the Jaspers & Dautzenberg 2002 set: with n, C and m
    # fixed at that set, the data determine A and B, and the fit must give the set back.
    m = cutcal.Material.from_toml(AISI)
    jc = cutcal.JcParams.from_toml(AISI_JC)
    speed = np.array([150.0, 200.0, 250.0, 300.0, 200.0, 200.0])
    uncut = np.array([0.15, 0.15, 0.15, 0.15, 0.10, 0.30])
    p = cutcal.predict_many(m, jc, speed, uncut, 1.6, -7.0)
    assert p["converged"].all()
    rows = ["test,speed_m_min,uncut_mm,width_mm,rake_deg,fc_n_per_mm,ft_n_per_mm,chip_mm"]
    for i in range(len(speed)):
        rows.append(f"{i + 1},{float(speed[i])!r},{float(uncut[i])!r},1.6,-7,{float(p['fc_n_per_mm'][i])!r},"
                    f"{float(p['ft_n_per_mm'][i])!r},{float(p['tc_mm'][i])!r}")
    csv = tmp_path / "model_tests.csv"
    csv.write_text("\n".join(rows) + "\n")
    fix = {"n": jc.n, "c": jc.c, "m": jc.m}
    args = ["identify", "--method", "oxley", "--material", AISI, "--tests", csv, "--starts", "2", "--json"]
    for k, v in fix.items():
        args += ["--fix", f"{k}={v!r}"]
    cli = json.loads(run_cli(*args).stdout)
    r = cutcal.joint(m, cutcal.read_tests(csv, as_frame=False), starts=2, fix=fix)
    assert_close(r["report"], cli, rel=1e-12)
    assert r["status"] == "determined" and r["determined"] and r["effective_rank"] == r["free_parameters"] == 2
    assert math.isclose(r["jc"].a_mpa, cli["jc"]["a_pa"] / 1e6, rel_tol=1e-12)
    assert math.isclose(r["jc"].a_mpa, jc.a_mpa, rel_tol=1e-6) and math.isclose(r["jc"].b_mpa, jc.b_mpa, rel_tol=1e-6)


def test_material_from_keywords_equals_from_toml():
    import tomllib

    with open(C38, "rb") as f:
        keys = tomllib.load(f)
    # The file's keys as keywords; the source is the file's path so the tool file (h13a.toml) is found.
    m = cutcal.Material(source=C38, **keys)
    ref = cutcal.Material.from_toml(C38)
    assert (m.name, m.melting_c, m.room_c) == (ref.name, ref.melting_c, ref.room_c)
    jc = cutcal.JcParams.from_toml(C38_JC)
    tests = cutcal.read_tests(C38_TESTS, as_frame=False)
    assert_close(cutcal.predict(m, jc, tests), cutcal.predict(ref, jc, tests), rel=0.0)
    assert cutcal.render(m, jc, "all") == cutcal.render(ref, jc, "all")
    t3 = pick(tests, "3")
    assert_close(cutcal.identify(m, t3, preset="paper", starts=4).to_dict(),
                 cutcal.identify(ref, t3, preset="paper", starts=4).to_dict(), rel=0.0)
    # A bad value is rejected by the file reader, naming the field.
    with pytest.raises(cutcal.InputError, match="melting_c"):
        cutcal.Material(**{**keys, "melting_c": -5.0})
    with pytest.raises(ValueError, match="not both"):
        cutcal.Material("name = 'x'", **keys)
    with pytest.raises(ValueError, match="no TOML form"):
        cutcal.Material(**{**keys, "name": None})


@pytest.mark.parametrize("material,tests", [
    ("fixtures/bad/material_nan_melting.toml", C38_TESTS),
    ("fixtures/bad/material_syntax_error.toml", C38_TESTS),
    (C38, "fixtures/bad/tests_negative_force.csv"),
    (C38, "fixtures/bad/tests_short_row.csv"),
    (C38, "fixtures/bad/tests_non_utf8.csv"),
])
def test_bad_input_raises_the_clis_located_error(material, tests):
    proc = run_cli("identify", "--material", material, "--tests", tests, check=False)
    assert proc.returncode != 0
    message = proc.stderr.strip().removeprefix("error: ")
    with pytest.raises(cutcal.InputError) as e:
        cutcal.Material.from_toml(material)
        cutcal.read_tests(tests)
    assert str(e.value) == message
    assert isinstance(e.value, cutcal.CutcalError)


def test_bad_jc_file_and_bad_values_raise_located_errors():
    proc = run_cli("predict", "--material", AISI, "--jc", "fixtures/bad/jc_nan_c.toml", "--tests", AISI_TESTS,
                   check=False)
    with pytest.raises(cutcal.InputError) as e:
        cutcal.JcParams.from_toml("fixtures/bad/jc_nan_c.toml")
    assert str(e.value) == proc.stderr.strip().removeprefix("error: ")
    with pytest.raises(cutcal.InputError, match=r"^<JcParams>:\d+: field `m`"):
        cutcal.JcParams(589, 145, 0.25, 0.069, -1.1, tm_c=1460)
    with pytest.raises(cutcal.InputError, match=r"^<CuttingTest>:2: field `rake_deg` = '60.0'"):
        cutcal.CuttingTest("1", 240, 0.075, 1.95, 60)
    with pytest.raises(cutcal.CutcalError, match="ansys"):
        cutcal.render(cutcal.Material.from_toml(C38), cutcal.JcParams.from_toml(C38_JC), "ansys")


def test_read_tests_gives_a_dataframe_with_the_csv_columns():
    frame = cutcal.read_tests(AISI_TESTS)
    assert list(frame.columns) == list(cutcal.TEST_COLUMNS)
    assert frame.shape == (4, 12)
    # Ivester et al. 2000 case 1: 610 N over 1.6 mm = 381.25 N/mm.
    assert frame["fc_n_per_mm"][0] == pytest.approx(381.25, rel=1e-12)
    t = cutcal.CuttingTest("3", 240, 0.075, 1.95, 0, fc_n_per_mm=224, ft_n_per_mm=88, chip_mm=0.157)
    assert t.to_dict()["chip_mm"] == pytest.approx(0.157, rel=1e-14)


def test_diagnose_equals_the_cli_json():
    args = ["--recordings", C38_TESTS, "--simulation", "fixtures/diagnose/c38_table6_enhanced_sim.csv",
            "--material", C38]
    cli = json.loads(run_cli("diagnose", *args, "--json").stdout)
    py = cutcal.diagnose(C38_TESTS, simulation="fixtures/diagnose/c38_table6_enhanced_sim.csv", material=C38)
    assert_close(py, cli)


def test_the_table4_example_runs_headless_and_matches_the_cli(tmp_path, root):
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, str(root / "examples/table4.py"), str(tmp_path)], cwd=root,
                          capture_output=True, text=True, env={**__import__("os").environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr
    table = json.loads((tmp_path / "table4.json").read_text())
    for model in ("original", "enhanced"):
        cli = json.loads(run_cli("identify", "--material", C38, "--tests", C38_TESTS, "--test", "3",
                                 "--model", model, "--preset", "paper", "--json").stdout)
        for k, v in table[model]["cutcal"].items():
            assert math.isclose(v, cli["jc"][k], rel_tol=1e-12), (model, k)
        assert table[model]["at_bounds"] == cli["at_bounds"]
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return
    png = (tmp_path / "fig4_fields.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000
