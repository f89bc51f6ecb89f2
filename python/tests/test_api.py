"""The Python API against the library's own answers: specs and their errors, solves (the same
status and objective as the `netspec` binary), models written, read and solved on every backend
(and read by highspy), the checker, comparisons and their DataFrame, backends, levels, cities."""

from __future__ import annotations

import csv
import io
import json
import subprocess
from pathlib import Path

import pytest

import netspec
from conftest import BAD, DATA, INFEASIBLE, ROOT, SMALL, TINY

BACKENDS = [s["name"] for s in netspec.solvers()]


def test_solvers_lists_every_compiled_backend() -> None:
    names = [s["name"] for s in netspec.solvers()]
    assert names[0] == "highs"
    for s in netspec.solvers():
        assert s["version"]
        assert isinstance(s["capabilities"]["interrupt"], bool)
        assert s["summary"].startswith("mip")
    # The binary lists the same.
    assert set(names) >= {"highs", "microlp"}


def test_a_spec_from_a_file_text_and_dict_is_the_same_spec() -> None:
    from_file = netspec.read_spec(SMALL)
    from_text = netspec.Spec.from_toml(SMALL.read_text())
    from_dict = netspec.Spec.from_dict(from_file.to_dict())
    assert from_file.name == from_text.name == from_dict.name == "small_6x6"
    assert from_file.path == str(SMALL)
    assert from_text.path is None
    assert from_file.to_dict() == from_text.to_dict() == from_dict.to_dict()
    assert netspec.Spec.from_json(json.dumps(from_file.to_dict())).to_dict() == from_file.to_dict()
    assert "small_6x6" in repr(from_file)


@pytest.mark.parametrize(
    "make, field",
    [
        (lambda: netspec.read_spec(BAD).build(), "user.forced_vertices[0]"),
        (lambda: netspec.solve(BAD), "user.forced_vertices[0]"),
        (lambda: netspec.Spec.from_toml('name = "x"\n[mesh]\ngrid = { width = "a", height = 2 }\n'), "mesh.grid.width"),
        (lambda: netspec.Spec.from_dict({"name": "x", "mesh": {"grid": {"width": 3, "height": "b"}}}), "mesh.grid.height"),
        (lambda: netspec.Spec.from_toml('name = "x\\u0007"\n[mesh]\ngrid = { width = 2, height = 2 }\n[sinks]\nall_boundary = true\n'), "name"),
        (lambda: netspec.read_spec(DATA / "no-such-spec.toml"), None),
    ],
)
def test_a_bad_spec_raises_spec_error_naming_the_field(make, field) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(netspec.SpecError) as e:
        make()
    assert isinstance(e.value, ValueError)
    assert e.value.field == field
    if field is not None:
        assert f"field `{field}`" in str(e.value)


def test_bad_arguments_raise_before_any_work() -> None:
    with pytest.raises(ValueError, match="solver"):
        netspec.solve(SMALL, solver="gurobi")
    with pytest.raises(ValueError, match="formulation"):
        netspec.solve(SMALL, formulation="weakest")
    with pytest.raises(netspec.NetspecError, match="gap"):
        netspec.solve(SMALL, gap=-1.0)
    with pytest.raises(TypeError):
        netspec.solve(42)  # type: ignore[arg-type]


def cli_solve(binary: Path, spec: Path, out: Path, *args: str) -> dict[str, str]:
    """The status and objective lines `netspec solve` prints."""
    run = subprocess.run(
        [str(binary), "solve", str(spec), "--no-explain", "--out", str(out), *args],
        capture_output=True,
        text=True,
        check=True,
    )
    lines = {}
    for line in run.stdout.splitlines():
        key, _, value = line.partition(" ")
        if key in ("status", "objective"):
            lines[key] = value.strip()
    return lines


@pytest.mark.parametrize("spec", [SMALL, TINY, INFEASIBLE], ids=["small", "tiny", "infeasible"])
def test_solve_gives_the_status_and_objective_of_the_binary(netspec_bin: Path, tmp_path: Path, spec: Path) -> None:
    cli = cli_solve(netspec_bin, spec, tmp_path / "cli", "--time-limit", "10")
    r = netspec.solve(spec, time_limit=10)
    assert r.status == cli["status"]
    assert ("-" if r.objective is None else f"{r.objective:.6f}") == cli["objective"]
    if spec == INFEASIBLE:
        assert r.termination == "infeasible" and r.design is None and not r.valid
        assert r.svg() is None and r.to_geojson() is None
    else:
        assert r.termination == "optimal" and r.valid


def test_a_result_gives_the_outputs_of_the_binary(tmp_path: Path) -> None:
    r = netspec.solve(netspec.read_spec(SMALL), solver="highs", threads=1, seed=3, start=False)
    assert r.termination == "optimal" and r.valid
    assert r.objective == pytest.approx(17.0) and r.bound == pytest.approx(17.0)
    assert r.gap is not None and r.gap <= 1e-6
    assert r.time > 0 and r.nodes is not None and r.solver_time is not None
    d = r.design
    assert d is not None
    assert len(d.edges) == d.metrics["edges"] == 17
    assert all(0 <= a < len(d.points) and 0 <= b < len(d.points) for a, b in d.edges)
    data = r.to_dict()
    assert data["schema"] == "netspec.design" and data["solve"]["objective"] == r.objective
    svg = r._repr_svg_()
    assert svg is not None and svg.lstrip().startswith("<svg")
    geo = json.loads(r.to_geojson() or "")
    assert geo["type"] == "FeatureCollection" and geo["features"]
    out = r.write(tmp_path / "out")
    for name in ["result.json", "network.svg", "network.png", "network.geojson"]:
        assert (Path(out) / name).is_file(), name
    written = json.loads((Path(out) / "result.json").read_text())
    assert written["solve"]["objective"] == r.objective and written["status"] == "finished"
    assert r.explanation is None
    assert "optimal" in repr(r)


def test_an_infeasible_spec_is_explained_when_asked() -> None:
    r = netspec.solve(INFEASIBLE, time_limit=10, explain=True)
    assert r.termination == "infeasible"
    assert r.explanation is not None and r.explanation["conflicts"]
    assert r.svg() is not None  # the conflicting requirements


def test_formulations_build_models_of_their_own_size() -> None:
    spec = netspec.read_spec(SMALL)
    sizes = {f: spec.build(formulation=f).num_vars for f in ["paper", "tight", "strong"]}
    assert len(set(sizes.values())) > 1
    tight = spec.build(formulation="tight")
    assert not tight.compact and tight.num_integers > 0 and tight.sense == "minimize"
    assert netspec.solve(spec, formulation="tight", start=False).objective == pytest.approx(17.0)


def test_a_model_by_name() -> None:
    m = netspec.read_spec(SMALL).build()
    assert m.compact  # strong separates its cutset rows: the complete equivalent
    names = m.column_names()
    assert len(names) == m.num_vars and len(m.row_names()) == m.num_rows
    col = m.column(names[0])
    assert col["kind"] == "binary" and col["lb"] == 0 and col["ub"] == 1
    row = m.row(m.row_names()[0])
    assert set(row) == {"name", "lhs", "rhs", "terms"} and row["terms"]
    with pytest.raises(KeyError):
        m.column("no such column")
    assert m.num_nonzeros >= sum(len(m.row(n)["terms"]) for n in m.row_names()[:5])
    assert "vars=" in repr(m)


@pytest.mark.parametrize("suffix", [".mps", ".lp", ".mps.gz"])
def test_a_written_model_read_back_has_the_optimum_on_every_backend(tmp_path: Path, suffix: str) -> None:
    optimum = netspec.solve(SMALL).objective
    m = netspec.read_spec(SMALL).build()
    path = tmp_path / f"m{suffix}"
    m.write(path)
    back = netspec.read_model(path)
    assert (back.num_vars, back.num_rows, back.num_nonzeros) == (m.num_vars, m.num_rows, m.num_nonzeros)
    for solver in BACKENDS:
        r = back.solve(solver=solver, time_limit=60)
        assert r.termination == "optimal", (solver, r.status)
        assert r.objective == pytest.approx(optimum), solver
        assert r.valid and r.solver == solver
        assert r.x is not None and netspec.check(back, r.x)["feasible"]
        values = r.values()
        assert values is not None and back.objective_value(values) == pytest.approx(optimum)
        assert r.to_dict()["schema"] == "netspec.solve" and "check" in r.summary()


@pytest.mark.parametrize("suffix", [".mps", ".lp"])
def test_highspy_reads_the_written_model_to_the_same_optimum(tmp_path: Path, suffix: str) -> None:
    highspy = pytest.importorskip("highspy")
    optimum = netspec.solve(SMALL).objective
    path = tmp_path / f"m{suffix}"
    netspec.read_spec(SMALL).build().write(path)
    h = highspy.Highs()
    h.setOptionValue("output_flag", False)
    assert h.readModel(str(path)) == highspy.HighsStatus.kOk
    h.run()
    assert h.getModelStatus() == highspy.HighsModelStatus.kOptimal
    assert h.getInfo().objective_function_value == pytest.approx(optimum)


def test_the_checker_finds_violations_and_the_start_is_used() -> None:
    m = netspec.read_spec(SMALL).build()
    zero = netspec.check(m, [0.0] * m.num_vars)
    assert not zero["feasible"] and zero["violations"] and zero["max_row_violation"] > 0
    best = m.solve()
    assert best.x is not None
    again = m.solve(solver="highs", start=best.x)
    assert again.objective == pytest.approx(best.objective)
    assert again.to_dict()["result"]["mip_start"]["accepted"]
    with pytest.raises(ValueError, match="columns"):
        netspec.check(m, [0.0])
    with pytest.raises(ValueError, match="no column"):
        netspec.check(m, {"nope": 1.0})


def test_compare_records_and_their_frame(tmp_path: Path) -> None:
    pd = pytest.importorskip("pandas")
    records = netspec.compare([SMALL, TINY], solvers=["highs", "microlp"], time_limit=30, out=tmp_path)
    assert [(r["instance"], r["solver"]) for r in records] == [
        ("small_6x6", "highs"),
        ("small_6x6", "microlp"),
        ("tiny_network", "highs"),
        ("tiny_network", "microlp"),
    ]
    assert all(r["status"] == "optimal" and r["valid"] for r in records)
    frame = netspec.records_frame(records)
    assert isinstance(frame, pd.DataFrame)
    header = (tmp_path / "results.csv").read_text().splitlines()[0].split(",")
    assert list(frame.columns) == header == netspec.csv_columns()
    assert list(frame["objective"]) == [r["objective"] for r in records]
    # The same CSV as `netspec compare` writes.
    assert netspec.records_csv(records) == (tmp_path / "results.csv").read_text()
    assert list(csv.DictReader(io.StringIO(netspec.records_csv(records))))[0]["instance"] == "small_6x6"


def test_compare_a_manifest_with_formulations(tmp_path: Path) -> None:
    manifest = tmp_path / "rows.toml"
    manifest.write_text(
        f'[[row]]\nname = "small"\nspec = "{SMALL}"\n\n[[row]]\nname = "tiny"\nspec = "{TINY}"\n'
        '\n[[row]]\nname = "later"\nmissing = "not yet"\n'
    )
    records = netspec.compare(str(manifest), solvers=["highs"], formulations=["tight", "strong"], rows=["sm*"], time_limit=30)
    assert [(r["instance"], r["solver"]) for r in records] == [("small", "highs/tight"), ("small", "highs/strong")]
    assert records[0]["objective"] == records[1]["objective"]
    failed = netspec.compare([BAD], solvers=["highs"], time_limit=5)
    assert failed[0]["status"] == "failed" and "forced_vertices" in failed[0]["error"]


def test_level_and_city_run_as_the_binary_does(tmp_path: Path) -> None:
    lv = netspec.level(ROOT / "models" / "levels" / "fig1.toml", time_limit=10, out=tmp_path / "level")
    assert lv["status"] == "feasible" and lv["layouts"]
    assert (tmp_path / "level").is_dir()
    city = netspec.city(ROOT / "fixtures" / "city" / "two-regions.toml", time_limit=10, out=tmp_path / "city")
    assert city["schema"] == "netspec.city" and city["regions"]
    assert (tmp_path / "city" / "city.json").is_file()
    with pytest.raises(ValueError, match="method"):
        netspec.level(ROOT / "models" / "levels" / "fig1.toml", method="guess")
    bad = tmp_path / "bad-city.toml"
    bad.write_text((ROOT / "fixtures" / "city" / "two-regions.toml").read_text().replace("metres_per_unit = 100", "metres_per_unit = -1"))
    with pytest.raises(netspec.SpecError) as e:
        netspec.city(bad, out=tmp_path / "bad")
    assert e.value.path == str(bad) and e.value.field is not None and e.value.field in str(e.value)
