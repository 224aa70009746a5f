"""Synthetic datasets: recipe validation, reproducibility, atomic/resumable writes, failures,
local parallel and Dask distributed generation."""

import os
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

from cmtool.cli import main
from cmtool.datasets import DatasetError, dataset_info, generate_dataset, read_dataset
from generators import ParameterError
from generators._lanes import LANES
from generators.cases import expand_cases
from generators.recipe import DEFAULT_CHUNK_SIZE, validate_recipe

REPO = Path(__file__).resolve().parents[2]

TINY = """
name = "tiny"
seed = 11
chunk_size = 2
[operating]
rpm = [1500, 2100]
load_n = { min = 200, max = 800 }
[sensor]
fs_hz = 5120
duration_s = 0.1
settle_s = 0.02
snr_db = 10
[[conditions]]
label = "healthy"
count = 3
[[conditions]]
label = "outer"
surface = "outer"
order = { min = 8, max = 10 }
amplitude_m = { min = 0.5e-6, max = 1e-6 }
count = 3
"""


@pytest.fixture
def tiny(tmp_path):
    path = tmp_path / "tiny.toml"
    path.write_text(TINY)
    return path


def test_chunk_size_defaults_to_whole_simd_blocks():
    raw = tomllib.loads(TINY.replace("chunk_size = 2\n", ""))
    assert validate_recipe(raw)["chunk_size"] == DEFAULT_CHUNK_SIZE
    assert DEFAULT_CHUNK_SIZE % LANES == 0  # every lane block of a chunk full


def test_shipped_recipes_validate():
    from generators.recipe import recipe_content_warnings

    for name in ("small.toml", "waviness.toml", "cwru-rig.toml"):
        recipe = validate_recipe(tomllib.loads((REPO / "datasets" / name).read_text()))
        cases = expand_cases(recipe)
        assert len(cases) == sum(c["count"] for c in recipe["conditions"])
    # and every shipped recipe's signals can show their labels (generators.content)
    for path in sorted((REPO / "datasets").glob("*.toml")):
        recipe = validate_recipe(tomllib.loads(path.read_text()))
        assert recipe_content_warnings(recipe) == [], path.name
    big = validate_recipe(tomllib.loads((REPO / "datasets" / "waviness.toml").read_text()))
    assert len(expand_cases(big)) >= 1000


@pytest.mark.parametrize(
    ("patch", "match"),
    [
        (("seed = 11", "seed = -1"), "recipe key seed = -1"),
        (("rpm = [1500, 2100]", "rpm = []"), "recipe key operating.rpm"),
        (
            ("load_n = { min = 200, max = 800 }", "load_n = { min = 900, max = 800 }"),
            "min is larger than max",
        ),
        (('surface = "outer"', 'surface = "cage"'), "conditions\\[1\\].surface = 'cage'"),
        (("fs_hz = 5120", "fs_hz = 5"), "sensor.fs_hz = 5"),
        (("count = 3\n[[conditions]]", "count = 0\n[[conditions]]"), "conditions\\[0\\].count = 0"),
        (("snr_db = 10", "snr_db = 10\ncolour = 3"), "sensor.colour"),
        (("snr_db = 10", "snr_db = 10\nbackground_db = 20"), "sensor.background_db = 20"),
        (("snr_db = 10", "fault_snr_db = 0"), "needs background_db"),
        (("snr_db = 10", "snr_db = 10\nresonance_hz = 3000"), "sensor.resonance_hz = 3000"),
        (('surface = "outer"', 'surface = "outer"\ndefect = "spall"'), "defect = 'spall'"),
        (
            ('surface = "outer"', 'surface = "outer"\ndefect = "localized"'),
            "conditions\\[1\\].amplitude_m = .* not a key of a localized defect",
        ),
        (("[sensor]", "[model]\nerror_bound = 0.7\n[sensor]"), "model.error_bound = 0.7"),
        # named by the recipe's key, before any case is built (until stop 85: "step = 0 s")
        (("[sensor]", "[model]\nstep_s = 0\n[sensor]"), "recipe key model.step_s = 0"),
        (("[sensor]", '[model]\nstep_s = "2e-5"\n[sensor]'), "model.step_s = '2e-5'"),
        (("[sensor]", "[model]\nrtol = 1.0\n[sensor]"), "recipe key model.rtol = 1.0"),
        (
            ("[sensor]", "[model]\nerror_bound = 0.01\nstep_s = 1e-5\n[sensor]"),
            "give error_bound or step_s",
        ),
        (
            ("[sensor]", '[model]\nerror_bound = 0.01\nintegrator = "dopri5"\n[sensor]'),
            "needs integrator = 'rk4'",
        ),
    ],
)
def test_recipe_errors_name_key_and_value(patch, match):
    raw = tomllib.loads(TINY.replace(*patch, 1))
    with pytest.raises(ParameterError, match=match):
        validate_recipe(raw)


def test_a_recipe_error_bound_gives_each_group_a_step_that_meets_it(tmp_path):
    """model.error_bound: one step per bearing, rate and condition, from pilots of the group's
    extremes; every case of the group (not only those) within the bound at it, against the
    same run at an eighth of the step, in lines and octave bands (generators.accuracy)."""
    import dataclasses

    from generators.accuracy import _lines, _pilot, band_error, line_error
    from generators.synthesis import _setup, bound_steps, step_group

    bound = 0.02
    text = (
        TINY.replace("[sensor]", f"[model]\nerror_bound = {bound}\n[sensor]")
        .replace("rpm = [1500, 2100]", "rpm = [1200, 2400, 3600]")
        .replace("duration_s = 0.1", "duration_s = 0.3")
        .replace("count = 3", "count = 4")
    )
    path = tmp_path / "bounded.toml"
    path.write_text(text)
    summary = generate_dataset(path, tmp_path / "ds")
    groups = {row["label"]: row for row in summary["error_bound_steps"]}
    assert set(groups) == {"healthy", "outer"}
    assert all(row["error_estimate"] <= bound for row in groups.values())
    frame = read_dataset(tmp_path / "ds")
    for label, row in groups.items():
        assert (frame.loc[frame["label"] == label, "step_s"] == row["step_s"]).all()
    recipe = validate_recipe(tomllib.loads(text))
    cases = expand_cases(recipe)
    steps = bound_steps(recipe, cases)
    assert {k[2]: v[0] for k, v in steps.items()} == {k: v["step_s"] for k, v in groups.items()}
    shared: dict = {}
    for case in cases:
        prep = _setup(recipe, case, "housing_acceleration_y", shared).run
        prep = dataclasses.replace(prep, settings=dataclasses.replace(prep.settings, step=None))
        step = steps[step_group(case)][0]
        n = int(0.3 * case.fs_hz)
        x, reference = _pilot(prep, step, 4, n), _pilot(prep, step / 8, 4, n)
        error = max(
            line_error(reference, x, case.fs_hz, _lines(prep)), band_error(reference, x, case.fs_hz)
        )
        assert error <= bound, (case.label, case.rpm, case.radial_load_n, step, error)


def test_generate_writes_labelled_parquet(tiny, tmp_path):
    out = tmp_path / "ds"
    summary = generate_dataset(tiny, out, workers=1)
    assert summary["written"] == 6 and summary["failed"] == 0
    frame = read_dataset(out)
    assert list(frame["id"]) == [f"tiny-{i:06d}" for i in range(6)]
    assert set(frame["label"]) == {"healthy", "outer"}
    assert frame["signal"].map(len).eq(512).all()
    assert frame["signal"].iloc[0].dtype == np.float32
    for col in ("rpm", "radial_load_n", "bpfo_hz", "seed", "operating_point_id", "snr_db"):
        assert col in frame.columns
    outer = frame[frame.label == "outer"]
    assert outer["waviness_order"].between(8, 10).all()
    meta = pq.read_schema(next((out / "data").glob("*.parquet"))).metadata
    assert b"tiny" in meta[b"recipe"] and meta[b"cmtool_version"]
    text = dataset_info(out)
    assert "healthy" in text and "rpm" in text
    # noise level follows the SNR: noise rms = clean rms / 10^(SNR/20), so the stored (noisy)
    # signal has rms^2 = noise_rms^2 (1 + 10^(SNR/10)); independent noise of 512 samples leaves
    # a cross term of a few per cent
    assert (frame["noise_rms"] > 0).all()
    for _, row in frame.iterrows():
        stored = np.sqrt(np.mean(np.square(np.asarray(row["signal"], dtype=float))))
        expected = row["noise_rms"] * np.sqrt(1 + 10 ** (row["snr_db"] / 10))
        assert stored == pytest.approx(expected, rel=0.1), (stored, expected)


def test_same_recipe_same_bytes_whatever_the_workers(tiny, tmp_path):
    a, b = tmp_path / "a", tmp_path / "b"
    generate_dataset(tiny, a, workers=1)
    generate_dataset(tiny, b, workers=2)
    files = sorted(p.name for p in (a / "data").glob("*.parquet"))
    assert files == sorted(p.name for p in (b / "data").glob("*.parquet"))
    for name in files:
        assert (a / "data" / name).read_bytes() == (b / "data" / name).read_bytes()


def test_refuses_to_overwrite_and_resume_checks_recipe(tiny, tmp_path):
    out = tmp_path / "ds"
    generate_dataset(tiny, out)
    with pytest.raises(DatasetError, match="not empty; use --resume"):
        generate_dataset(tiny, out)
    other = tmp_path / "other.toml"
    other.write_text(TINY.replace("seed = 11", "seed = 12"))
    with pytest.raises(DatasetError, match="different recipe"):
        generate_dataset(other, out, resume=True)
    # files of an older schema (other columns) are not topped up with this one's
    import pyarrow.parquet as pq

    from cmtool.datasets import DATASET_SCHEMA_VERSION

    first = sorted((out / "data").glob("*.parquet"))[0]
    table = pq.read_table(first)
    old = {**table.schema.metadata, b"schema_version": str(DATASET_SCHEMA_VERSION - 1).encode()}
    pq.write_table(table.replace_schema_metadata(old), first)
    with pytest.raises(DatasetError, match=f"schema version {DATASET_SCHEMA_VERSION - 1}"):
        generate_dataset(tiny, out, resume=True)
    # nor files of another generator revision (the same cases give other signals): a file
    # written before the revision was recorded is revision 1
    from generators.synthesis import GENERATOR_REVISION

    assert table.schema.metadata[b"generator_revision"] == str(GENERATOR_REVISION).encode()
    before = {k: v for k, v in table.schema.metadata.items() if k != b"generator_revision"}
    pq.write_table(table.replace_schema_metadata(before), first)
    with pytest.raises(DatasetError, match="generator revision 1 and this cmtool generates"):
        generate_dataset(tiny, out, resume=True)
    pq.write_table(table, first)  # as written: it resumes
    assert generate_dataset(tiny, out, resume=True)["generator_revision"] == GENERATOR_REVISION


def test_resume_removes_what_a_killed_write_left(tiny, tmp_path):
    out = tmp_path / "ds"
    generate_dataset(tiny, out)
    (out / "data" / "part-00001.parquet").unlink()
    stale = out / "data" / ".part-00001.parquet.k1ll3d.tmp"
    stale.write_bytes(b"PAR1 half a file")  # what SIGKILL leaves in the middle of a write
    summary = generate_dataset(tiny, out, resume=True)
    assert not stale.exists() and summary["written"] == 2
    assert sorted(read_dataset(out)["id"]) == [f"tiny-{i:06d}" for i in range(6)]


@pytest.mark.parametrize("part", ["part-00000.parquet", "part-00001.parquet"])
def test_a_cut_part_is_named_and_resume_generates_it_again(tiny, tmp_path, part):
    """A part cut short (a copy that stopped, a full disk outside cmtool's atomic writes) is
    named by read_dataset with the command that mends it; resume moves it aside and writes
    it again, the same bytes, instead of counting it as present. The first part is also the
    one resume reads the versions from."""
    out = tmp_path / "ds"
    generate_dataset(tiny, out)
    path = out / "data" / part
    whole = path.read_bytes()
    path.write_bytes(whole[: len(whole) // 2])
    with pytest.raises(DatasetError, match=rf"{part} unreadable .*--resume` generates it again"):
        read_dataset(out)
    with pytest.warns(UserWarning, match=rf"{part}: unreadable .*generated again"):
        summary = generate_dataset(tiny, out, resume=True)
    assert summary["written"] == 2 and summary["skipped_existing"] == 4
    assert path.read_bytes() == whole
    assert (out / "data" / f".{part}.unreadable").read_bytes() == whole[: len(whole) // 2]
    assert sorted(read_dataset(out)["id"]) == [f"tiny-{i:06d}" for i in range(6)]


def test_a_column_the_signals_lack_is_named(tmp_path, capsys):
    """A part rewritten without a column (by hand, or by a tool of the user's): reading it
    for that column names it. Before, ``cmtool dataset info`` printed pyarrow's "No match
    for FieldRef.Name(label)" followed by the whole schema."""
    small = Path(__file__).resolve().parents[2] / "datasets" / "small" / "data"
    data = tmp_path / "cut" / "data"
    data.mkdir(parents=True)
    table = pq.read_table(small / "part-00000.parquet")
    pq.write_table(table.drop_columns(["label"]), data / "part-00000.parquet")
    with pytest.raises(DatasetError, match=r"cut: its signals have no column 'label' \(`cmtool"):
        read_dataset(data.parent, columns=["label", "rpm"], allow_incomplete=True)
    assert main(["dataset", "info", str(data.parent)]) == 2
    assert "no column 'label'" in capsys.readouterr().err


def test_a_failing_worker_stops_the_run_and_resume_finishes_it(monkeypatch, tiny, tmp_path):
    import cmtool.datasets as cd

    real = cd.run_and_write_chunk

    def crash_on_chunk_1(recipe, cases, out, chunk, text):
        if chunk == 1:
            raise RuntimeError("worker crashed")
        return real(recipe, cases, out, chunk, text)

    out = tmp_path / "ds"
    monkeypatch.setattr(cd, "run_and_write_chunk", crash_on_chunk_1)
    with pytest.raises(RuntimeError, match="worker crashed"):
        generate_dataset(tiny, out, workers=2)
    assert not (out / "data" / "part-00001.parquet").exists()
    assert not (out / "_dataset.json").exists()  # written only by a run that completed
    monkeypatch.setattr(cd, "run_and_write_chunk", real)
    seen = []
    summary = generate_dataset(
        tiny, out, workers=2, resume=True, progress=lambda d, t: seen.append((d, t))
    )
    assert summary["written"] + summary["skipped_existing"] == 6 and summary["written"] >= 2
    assert seen[0] == (0, 6) and seen[-1] == (6, 6)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)
    assert sorted(read_dataset(out)["id"]) == [f"tiny-{i:06d}" for i in range(6)]


def test_resume_after_a_killed_run_gives_every_signal_once(tmp_path):
    tiny = tmp_path / "twenty.toml"  # 10 parts of 2 signals: the kill lands long before the end
    tiny.write_text(TINY.replace("count = 3", "count = 10"))
    out = tmp_path / "ds"
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "cmtool",
            "generate",
            str(tiny),
            "--out",
            str(out),
            "--workers",
            "1",
        ],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and not (out / "data" / "part-00000.parquet").exists():
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL and not (out / "_dataset.json").exists()
    assert (out / "data" / "part-00000.parquet").exists()
    # a part being written when the process died is a hidden temporary file, never a
    # truncated .parquet: every visible part reads whole
    for part in (out / "data").glob("*.parquet"):
        assert pq.read_table(part).num_rows == 2
    summary = generate_dataset(tiny, out, resume=True)
    assert not list(out.rglob("*.tmp"))  # the resumed run removed what the killed one left
    frame = read_dataset(out)
    assert sorted(frame["id"]) == [f"tiny-{i:06d}" for i in range(20)]
    assert summary["skipped_existing"] >= 2 and summary["written"] >= 2
    # the resumed dataset equals an uninterrupted one
    ref = tmp_path / "ref"
    generate_dataset(tiny, ref)
    for p in (ref / "data").glob("*.parquet"):
        assert p.read_bytes() == (out / "data" / p.name).read_bytes()


def test_ctrl_c_finishes_the_parts_being_written_and_resume_completes(tmp_path):
    recipe = tmp_path / "longer.toml"
    # 300 chunks of 2 signals: the interrupt arrives long before the last
    recipe.write_text(TINY.replace("count = 3", "count = 300"))
    out = tmp_path / "ds"
    proc = subprocess.Popen(
        [sys.executable, "-m", "cmtool", "generate", str(recipe), "--out", str(out)]
        + ["--workers", "2"],
        env={**os.environ, "PYTHONUNBUFFERED": "1"},
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        # a suite started in the background (no job control) hands its children SIGINT
        # ignored, and Python then installs no KeyboardInterrupt handler: restore the default
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and not (out / "data" / "part-00000.parquet").exists():
        time.sleep(0.02)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130 and "--resume" in err and "Traceback" not in err
    assert not list(out.rglob("*.tmp"))  # the parts being written were finished, not left
    for part in (out / "data").glob("*.parquet"):
        assert pq.read_table(part).num_rows == 2
    written_before = len(list((out / "data").glob("*.parquet")))
    assert 0 < written_before < 300  # the interrupt landed mid-run
    assert main(["generate", str(recipe), "--out", str(out), "--resume", "--workers", "2"]) == 0
    assert sorted(read_dataset(out)["id"]) == [f"tiny-{i:06d}" for i in range(600)]


def test_diverging_simulations_are_recorded_as_failures(tmp_path):
    recipe = tmp_path / "bad.toml"
    recipe.write_text(
        TINY.replace("[sensor]", '[model]\nscene = "full"\nehl = false\nstep_s = 1e-4\n[sensor]')
    )
    summary = generate_dataset(recipe, tmp_path / "ds")
    assert summary["failed"] == 6 and summary["written"] == 0
    failures = pq.read_table(tmp_path / "ds" / "failures").to_pandas()
    assert failures["error"].str.contains("diverged").all()
    assert "signal" not in failures.columns


def test_cli_generate_and_info(tiny, tmp_path, capsys):
    out = tmp_path / "ds"
    assert main(["generate", str(tiny), "--out", str(out), "--workers", "1"]) == 0
    assert "6 written" in capsys.readouterr().out
    assert main(["dataset", "info", str(out)]) == 0
    assert "signals per label" in capsys.readouterr().out
    assert main(["generate", str(tiny), "--out", str(out)]) == 2
    assert "--resume" in capsys.readouterr().err


def test_dask_cluster_with_a_worker_killed_mid_run(tiny, tmp_path):
    distributed = pytest.importorskip("distributed")
    out = tmp_path / "ds"
    recipe = tmp_path / "more.toml"
    recipe.write_text(
        TINY.replace("count = 3", "count = 8").replace("chunk_size = 2", "chunk_size = 1")
    )
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        import threading

        result = {}

        def run():  # through the command line's --scheduler
            argv = ["generate", str(recipe), "--out", str(out)]
            result["rc"] = main([*argv, "--scheduler", cluster.scheduler_address])

        thread = threading.Thread(target=run)
        thread.start()
        deadline = time.monotonic() + 120
        while (
            time.monotonic() < deadline
            and len(list((out / "data").glob("*.parquet")) if (out / "data").exists() else []) < 2
        ):
            time.sleep(0.05)
        # kill one worker process outright (as a crash would), while parts are still missing
        with distributed.Client(cluster.scheduler_address) as client:
            pids = client.run(os.getpid)
            victim = sorted(pids.values())[0]
        os.kill(victim, signal.SIGKILL)
        assert len(list((out / "data").glob("*.parquet"))) < 16  # the kill landed mid-run
        thread.join(timeout=300)
        assert not thread.is_alive()
    frame = read_dataset(out)
    assert sorted(frame["id"]) == [f"tiny-{i:06d}" for i in range(16)]
    assert result["rc"] == 0


def test_a_scheduler_that_cannot_be_reached_is_named_and_nothing_is_written(tiny, tmp_path):
    """Before: dask's OSError as a traceback (after 30 s), and a folder holding recipe.toml
    that the next try refused as "not empty" until --resume."""
    import dask

    out = tmp_path / "ds"
    with pytest.raises(DatasetError, match=r"scheduler = 'nonsense': cannot connect \(missing"):
        generate_dataset(tiny, out, scheduler="nonsense")
    with dask.config.set({"distributed.comm.timeouts.connect": "1s"}):
        with pytest.raises(DatasetError, match=r"'tcp://127.0.0.1:1': cannot connect \(Timed out"):
            generate_dataset(tiny, out, scheduler="tcp://127.0.0.1:1")
    assert not out.exists()
    # dask's own configuration as it was: a failed Client leaves the distributed scheduler
    # asked for, and any later compute() in the process failed
    assert dask.config.get("scheduler", None) is None
    assert dask.delayed(sum)([1, 2]).compute() == 3


def test_committed_dataset_reads_with_pyarrow_and_dask():
    data = REPO / "datasets" / "small" / "data"
    table = pq.read_table(data, columns=["id", "label", "signal"])
    assert table.num_rows == 192
    dd = pytest.importorskip("dask.dataframe")
    frame = dd.read_parquet(str(data), columns=["id", "label", "rpm"]).compute()
    assert sorted(frame["id"]) == [f"small-{i:06d}" for i in range(192)]


def test_a_case_without_static_equilibrium_is_a_recorded_failure(monkeypatch, tiny):
    import generators.synthesis as gd
    from cmtool.datasets import load_recipe

    recipe, _ = load_recipe(tiny)
    case = expand_cases(recipe)[0]

    def no_equilibrium(*args, **kwargs):
        raise ParameterError("radial_load = 1 N: static equilibrium not found")

    monkeypatch.setattr(gd, "prepare_checked", no_equilibrium)
    row = gd.generate_case(recipe, case)
    assert "signal" not in row and row["error"].startswith("not simulated: radial_load")


LOCAL = """
name = "local"
seed = 5
[operating]
rpm = [1797]
load_n = { min = 100, max = 400 }
[sensor]
fs_hz = [12000, 24000]
duration_s = 0.1
settle_s = 0.05
resonance_hz = { min = 2500, max = 4000 }
background_db = 20
fault_snr_db = { min = 0, max = 10 }
[[conditions]]
label = "healthy"
count = 2
[[conditions]]
label = "outer"
surface = "outer"
defect = "localized"
length_m = 0.18e-3
depth_m = { min = 5e-6, max = 50e-6 }
position_rad = { min = 6.5, max = 7.0 }
count = 2
[[conditions]]
label = "ball"
surface = "ball"
defect = "localized"
length_m = 0.18e-3
depth_m = 0.1e-3
axis_drift_rad_s = { min = 0, max = 50 }
count = 2
"""


def test_localized_defect_recipe(tmp_path):
    """Local-defect conditions, alternating sample rates, resonance range, background noise."""
    recipe = validate_recipe(tomllib.loads(LOCAL))
    cases = expand_cases(recipe)
    assert [c.defect_kind for c in cases] == ["none"] * 2 + ["localized"] * 4
    assert [c.fs_hz for c in cases] == [12000, 24000] * 3
    outer = [c for c in cases if c.label == "outer"]
    assert all(6.5 <= c.defect_position_rad <= 7.0 for c in outer)
    assert all(5e-6 <= c.defect_depth_m <= 50e-6 for c in outer)
    ball = [c for c in cases if c.label == "ball"]
    assert all(0 <= c.defect_axis_drift_rad_s <= 50 for c in ball)
    assert all(np.isnan(c.fault_snr_db) for c in cases if c.label == "healthy")
    path = tmp_path / "local.toml"
    path.write_text(LOCAL)
    generate_dataset(path, tmp_path / "ds", workers=1)
    frame = read_dataset(tmp_path / "ds")
    assert list(frame["signal"].map(len)) == [1200, 2400] * 3
    assert set(frame["defect_kind"]) == {"none", "localized"}
    assert frame["resonance_hz"].between(2500, 4000).all()
    # background: the same level relative to the healthy bearing for every case; a fault's
    # noise is at least that, and at least its signature over 10^(fault_snr/20)
    assert (frame["noise_rms"] > 0).all()
    # dataset info: what the recipe varies with its range, what it fixes on one line, no
    # waviness columns for a dataset without waviness, and how many faults train would keep
    text = dataset_info(tmp_path / "ds")
    ranges = {ln.split()[0]: ln for ln in text.splitlines() if ln.startswith("  ")}
    assert {"defect_depth_m", "radial_load_n", "fs_hz", "fault_snr_db"} <= set(ranges)
    assert "waviness_order" not in text and "rpm" not in ranges
    assert "in every fault): rpm 1797" in text and "defect_length_m 0.00018" in text
    low, high = (float(v) for v in ranges["defect_position_rad"].split()[1::2])
    assert -np.pi <= low < high <= np.pi  # the pits at 6.5-7 rad, shown round the circle
    faults = frame[frame["label"] != "healthy"]
    kept = {k: int((v["fault_snr_db"] >= -10).sum()) for k, v in faults.groupby("label")}
    assert f"keeps): ball {kept['ball']}/2, outer {kept['outer']}/2" in text


def test_the_recipe_keys_in_the_readme_are_the_schema():
    """datasets/README.md shows generators.recipe.RECIPE_SCHEMA, the table the validator walks."""
    from generators.recipe import RECIPE_SCHEMA, schema_table

    text = (REPO / "datasets" / "README.md").read_text()
    shown = text.split("<!-- recipe-schema: start -->\n")[1].split("<!-- recipe-schema: end -->")[0]
    assert shown == schema_table()
    assert len(shown.splitlines()) == len(RECIPE_SCHEMA) + 2


def test_every_schema_key_is_checked_against_its_range():
    """Each ranged key of the schema refuses a value above its range, naming the key (set
    where a shipped recipe already has it, or in its table when the recipe lacks it)."""
    import copy
    import math

    from generators.recipe import RECIPE_SCHEMA

    bases = [
        tomllib.loads((REPO / "datasets" / n).read_text()) for n in ("cwru-rig.toml", "small.toml")
    ]
    checked = 0
    for key in RECIPE_SCHEMA:
        section, _, name = key.path.rpartition(".")
        if key.kind not in ("values", "grid", "number", "integer") or not math.isfinite(key.high):
            continue
        for base in bases:
            recipe = copy.deepcopy(base)
            if section == "conditions":
                tables = [c for c in recipe["conditions"] if name in c]
            else:
                tables = [recipe.setdefault(section, {}) if section else recipe]
            if not tables:
                continue
            for table in tables:
                table[name] = key.high * 2 + 1
            with pytest.raises(ParameterError, match=rf"recipe key \S*{name} = "):
                validate_recipe(recipe)
            checked += 1
            break
    assert checked >= 35, checked


def test_a_missing_or_empty_folder_is_not_a_complete_dataset(tmp_path):
    import pandas as pd

    from cmtool.datasets import dataset_complete

    assert not dataset_complete(tmp_path / "nowhere")
    assert not dataset_complete(tmp_path)  # exists, holds nothing
    (tmp_path / "data").mkdir()
    pd.DataFrame({"x": [1.0]}).to_parquet(tmp_path / "data" / "part-0.parquet")
    assert dataset_complete(tmp_path) and dataset_complete(tmp_path / "data")  # not ours: as is
    (tmp_path / "recipe.toml").write_text("name = 'x'\n")
    assert not dataset_complete(tmp_path)  # ours, interrupted
    (tmp_path / "_dataset.json").write_text("{}")
    assert dataset_complete(tmp_path)


def test_a_recipe_beyond_its_bearings_ratings_is_warned_about_once(tmp_path):
    """A recipe whose largest load passes a bearing's C0r (or whose fastest speed its limiting
    speed) is warned about once, by bearing, before generation; the shipped recipes are
    within every rating of their bearings."""
    from generators import OperatingRangeWarning
    from generators.recipe import recipe_rating_warnings

    for recipe in sorted((REPO / "datasets").glob("*.toml")):
        assert recipe_rating_warnings(validate_recipe(tomllib.loads(recipe.read_text()))) == []
    text = (REPO / "datasets" / "small.toml").read_text()
    heavy = text.replace("load_n = [300, 550, 800]", "load_n = [300, 550, 9000]")
    heavy = heavy.replace("count = 48", "count = 1").replace(
        'bearings = ["6205"]', 'bearings = ["6205", "6203"]'
    )
    messages = recipe_rating_warnings(validate_recipe(tomllib.loads(heavy)))
    assert [m.split(":")[0] for m in messages] == ["recipe bearing 6205", "recipe bearing 6203"]
    assert "C0r = 7850 N" in messages[0] and "C0r = 4750 N" in messages[1]
    (tmp_path / "heavy.toml").write_text(heavy)
    with pytest.warns(OperatingRangeWarning) as caught:
        generate_dataset(tmp_path / "heavy.toml", tmp_path / "out")
    assert len(caught) == 2  # once per bearing, not per case


def test_a_recipes_cage_slip_lowers_the_ball_pass_and_leaves_the_rate_columns_kinematic(tmp_path):
    """operating.cage_slip: the run's cage lags by it (its ball-pass line lies 1 - s lower), the
    rate columns stay the kinematic rates a detector is given, and nothing else drawn moves."""
    from generators import bearing, characteristic_frequencies

    plain = """
name = "slip"
seed = 5
[operating]
rpm = [1800]
load_n = { min = 400, max = 600 }
[sensor]
fs_hz = 12800
duration_s = 1.0
settle_s = 0.05
[[conditions]]
label = "healthy"
count = 2
"""
    frames = {}
    for slip in (None, 0.05):
        path = tmp_path / f"slip{slip}.toml"
        drawn = "" if slip is None else f"cage_slip = [{slip}]\n"
        path.write_text(plain.replace("[sensor]", drawn + "[sensor]"))
        generate_dataset(path, tmp_path / f"ds{slip}")
        frames[slip] = read_dataset(tmp_path / f"ds{slip}")
    kinematic = characteristic_frequencies(bearing("6205"), 30.0)
    for slip, frame in frames.items():
        assert frame["cage_slip"].eq(slip or 0.0).all()
        assert frame["bpfo_hz"].eq(kinematic.bpfo).all()
        assert frame["bpfi_hz"].eq(kinematic.bpfi).all()
        for x in frame["signal"]:
            x = np.asarray(x, dtype=float)
            spec = np.abs(np.fft.rfft((x - x.mean()) * np.hanning(x.size)))
            freqs = np.fft.rfftfreq(x.size, 1 / 12800)
            near = (freqs > 0.9 * kinematic.bpfo) & (freqs < 1.05 * kinematic.bpfo)
            found = freqs[near][np.argmax(spec[near])]
            assert found == pytest.approx(kinematic.bpfo * (1 - (slip or 0.0)), abs=1.0)
    for column in ("seed", "radial_load_n", "rpm", "label"):
        assert frames[None][column].tolist() == frames[0.05][column].tolist()
