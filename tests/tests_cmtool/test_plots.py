"""The figures cmtool writes: atomically, and the report's time waveform."""

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from impact_trains import ringing_impact_train

from cmtool.plots import plot_waveform, plt, save_figure, waveform_window


def test_save_figure_keeps_the_previous_file_when_writing_fails(tmp_path):
    path = tmp_path / "spectrum.png"
    fig, ax = plt.subplots()
    ax.plot([0, 1], [1, 0])
    assert save_figure(fig, path) == path
    first = path.read_bytes()
    assert first.startswith(b"\x89PNG")
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])

    def fail(target, *args, **kwargs):  # half a file written, then the disk is full
        with open(target, "wb") as half:
            half.write(first[:100])
        raise OSError("disk full")

    fig.savefig = fail
    try:
        save_figure(fig, path)
    except OSError:
        pass
    else:
        raise AssertionError("the failure was swallowed")
    assert path.read_bytes() == first
    assert [p.name for p in tmp_path.iterdir()] == ["spectrum.png"]
    assert not plt.get_fignums()  # both figures closed
    svg = save_figure(plt.figure(), tmp_path / "empty.svg")
    assert b"<svg" in svg.read_bytes()[:400]


def test_the_waveform_zooms_on_three_turns_about_the_largest_peak(tmp_path):
    """The report's waveform.png: its zoom spans three shaft turns centred on the largest
    |x| (cut to the record at its ends), and a band of the whole span or one edge plots."""
    fs, shaft = 12000.0, 30.0
    x = np.random.default_rng(2).standard_normal(24000)
    for peak in (12000, 100, 23990):
        y = x.copy()
        y[peak] = -50.0
        window = waveform_window(y, fs, shaft)
        assert window.stop - window.start == 1200  # 3 turns of 1/30 s at 12 kHz
        assert window.start <= peak < window.stop
        assert 0 <= window.start and window.stop <= y.size
    assert waveform_window(x[:500], fs, shaft) == slice(0, 500)  # a record under three turns
    for band in ((500.0, 3000.0), (0.0, 6000.0), (0.0, 2000.0), (800.0, 6000.0), None):
        path = plot_waveform(
            x,
            fs,
            tmp_path / "w.png",
            title="t",
            shaft_hz=shaft,
            band=band,
            fault_hz=107.0,
            fault_name="outer race",
        )
        assert path.read_bytes().startswith(b"\x89PNG")


@settings(max_examples=6, deadline=None)
@example(fs=200.0, rpm=6.0, samples=64, low=0.0, high=0.5, fault_orders=None)
@example(fs=200.0, rpm=6.0, samples=64, low=0.25, high=0.25, fault_orders=None)  # no width
@example(fs=54083.5, rpm=6.0, samples=5801, low=2.9e-193, high=2.9e-193, fault_orders=None)
@example(fs=12000.0, rpm=1797.0, samples=12000, low=0.04, high=0.39, fault_orders=3.58)
@given(
    fs=st.floats(200.0, 200_000.0),
    rpm=st.floats(6.0, 60_000.0),
    samples=st.integers(64, 30_000),
    low=st.floats(0.0, 0.5),
    high=st.floats(0.0, 0.5),
    fault_orders=st.floats(0.4, 8.0) | st.none(),
)
def test_the_waveform_plots_for_any_rate_speed_length_and_band(
    tmp_path_factory, fs, rpm, samples, low, high, fault_orders
):
    """Whatever rate, speed, record length and band (fractions of fs, given in any order, a
    zero or Nyquist edge included) the report's waveform is drawn, its zoom inside the
    record."""
    x = np.random.default_rng(samples).standard_normal(samples)
    shaft = rpm / 60.0
    window = waveform_window(x, fs, shaft)
    assert 0 <= window.start < window.stop <= samples
    band = (min(low, high) * fs, max(low, high) * fs)
    fault = None if fault_orders is None else fault_orders * shaft
    path = tmp_path_factory.mktemp("w") / "w.png"
    plot_waveform(x, fs, path, title="t", shaft_hz=shaft, band=band, fault_hz=fault)
    assert path.read_bytes().startswith(b"\x89PNG")


def test_the_verdicts_comb_is_marked_across_the_span_and_the_others_at_three_harmonics(
    tmp_path, monkeypatch
):
    """An analyst reads the verdict's whole comb of harmonics; the other rates keep three."""
    import cmtool.plots as plots

    captured = {}

    def keep(fig, path):
        captured["fig"] = fig
        return path

    monkeypatch.setattr(plots, "save_figure", keep)
    f = np.arange(0.0, 1200.0, 0.5)
    plots.plot_spectrum(
        f,
        np.ones_like(f),
        tmp_path / "e.png",
        title="t",
        ylabel="a",
        markers={"bpfo": 100.0, "bpfi": 137.0},
        fmax=1050.0,
        emphasis="bpfo",
        sidebands=10.0,
    )
    xs = [line.get_xdata()[0] for line in captured["fig"].axes[0].lines[1:]]
    assert sorted(x for x in xs if x % 100.0 == 0) == [100.0 * k for k in range(1, 11)]
    assert sorted(x for x in xs if x % 137.0 == 0) == [137.0, 274.0, 411.0]
    assert sorted(x for x in xs if x % 10.0 == 0 and x % 100.0) == [90, 110, 190, 210, 290, 310]


def test_the_reports_envelope_spectrum_is_linear_with_its_lines_over_the_markers(
    tmp_path, monkeypatch
):
    """An envelope spectrum is read on a linear axis from 0 (its lines against their floor; a
    log axis spends half its height on the floor's dips), the plain spectrum on a log one; in
    both the data is drawn over the markers, so the verdict's solid marker does not hide the
    line it marks."""

    import cmtool.plots as plots
    from cmtool.diagnose import diagnose_signal
    from cmtool.report import write_report
    from generators import bearing, characteristic_frequencies

    figures = {}

    def keep(fig, path):
        figures[path.name] = fig
        return path

    monkeypatch.setattr(plots, "save_figure", keep)
    fs, n = 12000.0, 12000
    bpfo = characteristic_frequencies(bearing("6205"), 1797 / 60).bpfo
    rng = np.random.default_rng(5)
    x = ringing_impact_train(bpfo, fs, n, rng)  # slip: 1 % jitter
    wander = 1 + 0.8 * np.sin(2 * np.pi * 1.3 * np.arange(n) / fs)  # a load wandering at 1.3 Hz
    x = x * wander + 0.05 * rng.standard_normal(n)
    d = diagnose_signal(x, fs, 1797.0, "6205", waviness=False)
    assert d.verdict == "outer race"
    write_report(d, tmp_path, title="t", x=x, fs=fs)
    envelope, spectrum = figures["envelope.png"].axes[0], figures["spectrum.png"].axes[0]
    assert envelope.get_yscale() == "linear" and envelope.get_ylim()[0] == 0.0
    assert spectrum.get_yscale() == "log"
    for ax in (envelope, spectrum):
        data, *markers = ax.lines
        assert markers and all(data.get_zorder() > m.get_zorder() for m in markers)
    # its height: the lines from half the cage rate up, not the first bins' slow wander, which
    # would squash them (on 200 simulated rig records a quarter had their highest point under
    # half the shaft rate: in the first bins, up to 7.5 times the lines, or at the cage rate,
    # a ball pit's line, which stays in)
    f, amplitude = d.spectra.envelope_frequencies, d.spectra.envelope_amplitude
    plotted = (f > 0) & (f <= 5 * d.frequencies["bpfi"])
    lines = plotted & (f >= 0.5 * d.frequencies["ftf"])
    assert amplitude[lines].max() < 0.9 * amplitude[plotted].max()  # the wander is highest
    assert envelope.get_ylim()[1] == pytest.approx(1.08 * amplitude[lines].max())
    f = np.arange(0.0, 600.0, 1.0)
    amplitude = np.full(f.size, 0.1)
    amplitude[1], amplitude[12], amplitude[107] = 50.0, 2.0, 1.0  # wander, cage, BPFO
    plots.plot_spectrum(
        f,
        amplitude,
        tmp_path / "w.png",
        title="t",
        ylabel="a",
        markers={"bpfo": 107.0},
        log=False,
        top_from=0.5 * 11.9,
    )
    assert figures["w.png"].axes[0].get_ylim() == pytest.approx((0.0, 1.08 * 2.0))


def test_the_waveforms_period_ticks_take_the_colour_of_the_verdicts_marker(tmp_path, monkeypatch):
    """The ticks of the verdict's period in waveform.png are drawn in the colour its rate's
    marker has in spectrum.png and envelope.png (they were red for every fault)."""
    from matplotlib.colors import to_hex

    import cmtool.plots as plots

    captured = {}

    def keep(fig, path):
        captured["fig"] = fig
        return path

    monkeypatch.setattr(plots, "save_figure", keep)
    x = np.random.default_rng(5).standard_normal(12000)
    expected = {"outer race": "tab:red", "inner race": "tab:blue", "ball": "tab:green"}
    for fault, colour in [*expected.items(), (None, "tab:red")]:
        plots.plot_waveform(
            x, 12000.0, tmp_path / "w.png", title="t", shaft_hz=30.0, band=(500.0, 3000.0),
            fault_hz=107.0, fault_name=fault,
        )  # fmt: skip
        fig = captured.pop("fig")
        for ax in fig.axes[1:]:  # the zoom and the band's panel
            ticks = [line for line in ax.lines if line.get_linestyle() == "--"]
            assert len(ticks) >= 3, fault
            assert {to_hex(line.get_color()) for line in ticks} == {to_hex(colour)}, fault
        plt.close(fig)
