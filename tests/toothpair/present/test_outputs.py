"""The files of a mesh cycle for ParaView: VTU fields named with their units, and a .pvd time
series over the rolling angle that lists every position's VTUs."""

import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest

from fegear.toothpair import prepare_job, run_job


@pytest.fixture(scope="module")
def cycle(tmp_path_factory):
    out = tmp_path_factory.mktemp("cycle")
    job = prepare_job({"quality": "coarse", "positions": 3, "no-estimate": True})
    return out, run_job(job, out)


def test_the_pvd_lists_both_gears_at_every_position(cycle):
    out, result = cycle
    root = ET.parse(out / "cycle.pvd").getroot()
    assert root.get("type") == "Collection"
    sets = root.findall("./Collection/DataSet")
    betas = [r["position_deg"] for r in result.rows]
    for part, name in ((0, "gear1"), (1, "gear2")):
        mine = [d for d in sets if d.get("part") == str(part)]
        assert [float(d.get("timestep")) for d in mine] == pytest.approx(betas)
        for k, d in enumerate(mine):
            assert d.get("file") == f"cycle/{name}_{k:03d}.vtu"
            m = meshio.read(out / d.get("file"))
            assert "triangle6" in m.cells_dict
            assert m.point_data["contact_pressure_MPa"].max() > 0   # the loaded teeth are in
            assert all(k.endswith(("_mm", "_MPa")) for k in m.point_data)
    # a tenth or so of the whole gear: the loaded sectors and one either side
    whole = meshio.read(out / "gear1.vtu").points.shape[0]
    assert meshio.read(out / "cycle" / "gear1_000.vtu").points.shape[0] < whole / 3


def test_the_series_holds_the_fields_of_its_position(cycle):
    """The position written as the pair's own VTU is in the series with the same stresses."""
    out, result = cycle
    k = max(range(3), key=lambda i: result.rows[i]["root_stress_gear1_MPa"])
    whole = meshio.read(out / "gear1.vtu").point_data["von_mises_MPa"]
    part = meshio.read(out / "cycle" / f"gear1_{k:03d}.vtu").point_data["von_mises_MPa"]
    assert part.max() == pytest.approx(whole.max(), rel=1e-12)


def test_pyvista_reads_the_series_as_time(cycle):
    from fegear.figures import pyvista

    pv = pyvista()
    out, result = cycle
    reader = pv.get_reader(str(out / "cycle.pvd"))
    assert np.allclose(reader.time_values, [r["position_deg"] for r in result.rows])
    reader.set_active_time_value(reader.time_values[1])
    blocks = reader.read()
    assert blocks.n_blocks == 2 and blocks[0].n_points > 1000


PNG = b"\x89PNG\r\n\x1a\n"


def test_every_picture_is_written(cycle):
    out, result = cycle
    for name in ("von_mises.png", "flank_pressure.png", "root_stress.png", "cycle.png"):
        data = (out / name).read_bytes()
        assert data.startswith(PNG) and len(data) > 20_000, name
    assert {"png", "flank_png", "root_png", "cycle_png", "pvd"} <= set(result.files)


@pytest.fixture(scope="module")
def solved(baseline, baseline_ring):
    from fegear.toothpair import SolveCase, solve_pair

    return solve_pair(SolveCase(baseline, quality="coarse"), model=baseline_ring)


def test_the_root_hot_spots_are_the_reported_root_stresses(solved):
    """The marks on the von Mises picture sit where each gear's reported root stress is."""
    from fegear.toothpair.present.marks import root_hot_spots

    spots = root_hot_spots(solved, solved.detail.body_fields())
    assert [s.gear for s in spots] == [1, 2]
    for s in spots:
        assert s.value == pytest.approx(solved.root_stress[s.gear - 1], rel=0.01)


def test_the_flank_curves_peak_at_the_reported_pressures(solved):
    from fegear.toothpair.present.marks import pressure_curve

    teeth = {t.tooth: t for t in solved.teeth}
    flanks = solved.detail.flank_pressures()
    assert sorted(f.tooth for f in flanks) == sorted(t.tooth for t in solved.teeth
                                                      if t.load_N > 0)
    for f in flanks:
        t = teeth[f.tooth]
        curve = pressure_curve(f, t)
        assert f.pressure.max() == pytest.approx(t.p_max_MPa, rel=1e-6)
        lo, hi = curve.window_um
        loaded = curve.s_um[f.pressure > 0]
        assert lo <= loaded.min() and loaded.max() <= hi      # the window shows the contact
        if curve.hertz is not None:
            assert curve.hertz.max() == pytest.approx(t.hertz_p0_MPa, rel=0.02)
        if t.edge_contact:     # the spike is drawn off the axis, the flank fills it
            assert t.flank_p_MPa < curve.top < f.pressure.max()
        else:
            assert curve.top >= f.pressure.max()


def test_flank_distances_start_at_the_tip_corner(solved):
    """0 where the round meets the flank, < 0 on the round, > 0 where the flank carries load:
    the arc measured on the profile agrees with the grid's own round/flank junction."""
    for f in solved.detail.flank_pressures():
        d = f.from_corner
        assert np.all(np.abs(np.diff(d)) == pytest.approx(np.diff(f.s), rel=1e-9, abs=1e-12))
        assert np.all(d[f.on_round] <= 1e-4)
        assert np.all(d[~f.on_round & (f.pressure > 0)] > 0)
        # where the grid crosses from the round onto the loaded flank (its other end meets
        # the top land, a round's length further), the corner lies between the two points
        junction = np.flatnonzero(np.diff(f.on_round.astype(int)))
        if len(junction):
            assert min(max(abs(d[j]), abs(d[j + 1])) - abs(f.s[j + 1] - f.s[j])
                       for j in junction) <= 1e-9


def test_the_tooth_labels_of_pair_png_sit_on_their_teeth(baseline):
    """Each label lies inside gear 1 and nearest to its own tooth's centre line."""
    from fegear.geometry import Gear1Profile, ToothContact
    from fegear.geometry.plot import tooth_labels

    g1 = Gear1Profile(baseline)
    teeth = ToothContact(baseline, g1).state(0.0).teeth
    tip = float(g1.radius(np.array([g1.tooth_center]))[0])
    labels = tooth_labels([(t.tooth, t.position_deg) for t in teeth], baseline.e, tip, 0.3)
    for (number, x), t in zip(labels, teeth):
        assert number == t.tooth
        assert np.hypot(x[0], x[1] - baseline.e) == pytest.approx(tip - 0.3)
        angle = np.degrees(np.arctan2(-x[0], x[1] - baseline.e))
        assert angle == pytest.approx(t.position_deg, abs=1e-9)
    # at β = 0 the first tooth to touch turning + (11) sits just left of the pitch point
    x11 = dict(labels)[11]
    assert -2.0 < x11[0] < 0.0


def test_with_sharp_tips_the_distances_start_at_the_kink(baseline):
    """--tip-round 0: no round, the corner is the tip's kink; the pressure next to it (the
    tip corner presses into gear 2's flank) starts within 10 µm of 0, on the flank side."""
    from fegear.toothpair import SolveCase, solve_pair

    sharp = solve_pair(SolveCase(baseline, quality="coarse", tip_round=0.0))
    flanks = sharp.detail.flank_pressures()
    assert flanks and not any(f.on_round.any() for f in flanks)
    corner_loaded = 0
    for f in flanks:
        d = f.from_corner[f.pressure > 0]
        assert d.min() > -1e-3                    # nothing loaded beyond the corner
        corner_loaded += d.min() < 0.01           # loaded within 10 µm of it
    assert corner_loaded >= 1


def test_the_cycle_picture_carries_the_allowable_and_the_smallest_factors():
    """cycle.png's stress panels: the allowable as a line while within twice the largest
    stress (else in the legend only), and the smallest S_F at the β where it occurs."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fegear.fe import Allowables
    from fegear.toothpair.analyses.cycle.plot import cycle_figure

    rows = [{"position_deg": b, "share_10": 1.0, "root_stress_gear1_MPa": s1,
             "root_stress_gear2_MPa": s2, "contact_pressure_MPa": 1000.0,
             "safety_bending_gear1": 558 / s1, "safety_bending_gear2": 558 / s2,
             "rotation_urad": 0.0, "first_touch_urad": 0.0, "transmission_error_urad": 0.0}
            for b, s1, s2 in ((0.0, 280.0, 270.0), (4.0, 300.0, 250.0), (8.0, 290.0, 275.0))]
    stresses = {"root_stress_gear1_MPa": "gear 1", "root_stress_gear2_MPa": "gear 2",
                "contact_pressure_MPa": "peak pressure"}
    near, far = (cycle_figure(rows, "cycle", stresses, Allowables(bending=limit, contact=1500.0))
                 for limit in (558.0, 5580.0))
    roots = near.axes[1]                 # the root stresses' panel
    labels = [t.get_text() for t in roots.get_legend().get_texts()]
    assert labels[-3:] == ["allowable σ_FP 558 MPa", "smallest S_F gear 1 1.86, at β 4°",
                           "smallest S_F gear 2 2.03, at β 8°"]
    assert [tuple(line.get_ydata()) for line in roots.lines
            if tuple(line.get_ydata()) == (558.0, 558.0)] == [(558.0, 558.0)]
    assert "allowable σ_FP 5580 MPa (off the scale)" in [
        t.get_text() for t in far.axes[1].get_legend().get_texts()]
    assert all(len(line.get_ydata()) != 2 or line.get_ydata()[0] != 5580.0
               for line in far.axes[1].lines)
    plt.close(near)
    plt.close(far)


def test_the_cycle_picture_s_title_of_a_class_over_a_revolution_fits_over_its_panels():
    """A class's pairs over a revolution add a second line to the pictures' title; on the
    narrow cycle picture it stays inside the figure and clear of the first panel (one line
    of it ran off both sides)."""
    from types import SimpleNamespace

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fegear.toothpair.analyses.cycle.plot import cycle_figure
    from fegear.toothpair.present.output import pictures_title

    rows = [{"position_deg": b, "share_10": 1.0, "root_stress_gear1_MPa": 280.0,
             "contact_pressure_MPa": 1000.0, "rotation_urad": 0.0, "first_touch_urad": 0.0,
             "transmission_error_urad": 0.0} for b in (0.0, 4.0)]
    # what pictures_title reads of a solved class over a revolution: a design whose numbers
    # run long, 8 places a pitch, the pairs screened
    inputs = {"m": 1.58867, "h1": 0.26827, "f1": 0.199558, "torque_Nm": 200.0,
              "quality": "standard"}
    solved = SimpleNamespace(
        summary={"inputs": inputs, "samples": {"positions_solved_per_pair": 171.6}},
        solutions=[None] * 8, job=SimpleNamespace(revolution=True, betas=[0.0] * 352))
    title = pictures_title(solved)
    assert title.endswith("quality standard\n8 positions a pitch over a revolution (352; "
                          "screened: 172 a pair solved)")
    fig = cycle_figure(rows, title, {"root_stress_gear1_MPa": "gear 1",
                                     "contact_pressure_MPa": "peak pressure"})
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    shown = next(t for t in fig.texts if t.get_text() == title)
    box, whole = shown.get_window_extent(renderer), fig.bbox
    assert whole.x0 <= box.x0 and box.x1 <= whole.x1 and box.y1 <= whole.y1
    assert box.y0 > fig.axes[0].get_tightbbox(renderer).y1
    plt.close(fig)


@pytest.fixture(scope="module")
def summary(solved):
    from fegear.toothpair import pair_summary

    return pair_summary(solved)


@pytest.fixture
def plt():
    from fegear.figures import pyplot

    p = pyplot()
    yield p
    p.close("all")


def test_the_von_mises_labels_cover_no_mark_and_their_leaders_do_not_cross(solved, summary,
                                                                           plt):
    """Read off the drawn picture: both gears named, every loaded tooth and both root hot
    spots labelled, no label over a marker (the hot spots, the maximum) or another label, no
    leaders crossing; the verdict above it names each factor and its allowable."""
    from labels import label_boxes, label_faults

    from fegear.toothpair.present.plot import von_mises_figure

    fig = von_mises_figure(solved, summary, solved.detail.body_fields(),
                           solved.detail.peak_fields())
    left, zoom = fig.axes[:2]
    loaded = sum(t.load_N > 0 for t in solved.teeth)
    assert len(label_boxes(left)) == 2 + loaded + 2 and len(label_boxes(zoom)) == 1
    assert label_faults(left) == [] and label_faults(zoom) == []
    verdict = fig.get_suptitle()
    for key in ("safety_bending_gear1", "safety_bending_gear2", "safety_contact"):
        assert f"{summary[key]:.2f}" in verdict
    assert "σ_FP 558 MPa" in verdict and "σ_HP 745 MPa" in verdict
    texts = [t.get_text() for t in left.texts]
    assert any(f"S_F {summary['safety_bending_gear1']:.2f}" in t for t in texts)


def test_the_verdict_names_the_smallest_factor_and_whether_it_passes():
    from fegear.toothpair.present.marks import VerdictCaption

    s = {"inputs": {"allowable_bending_MPa": 558.0, "allowable_contact_MPa": 745.0},
         "safety_bending_gear1": 1.95, "safety_bending_gear2": 2.09, "safety_contact": 0.40,
         "safety_contact_flank": 1.19, "contact_peak_on_tip_round": True,
         "contact_pressure_MPa": 1880.0, "flank_contact_pressure_MPa": 624.0}
    fails = VerdictCaption.of(s)
    assert fails.text.endswith("S_H 0.40 below 1: the stress exceeds the allowable")
    assert "S_H flank 1.19 at 624 MPa" in fails.text
    passes = VerdictCaption.of({**s, "safety_contact": 1.19, "contact_peak_on_tip_round": False,
                         "contact_pressure_MPa": 624.0})
    assert "every safety factor at least 1" in passes.text and "S_H flank" not in passes.text
    assert passes.colour != fails.colour


def test_the_flank_panels_share_one_legend_above_them(solved, summary, plt):
    """No legend inside a panel (it covered the p ref line); the one legend lies above every
    panel; each panel's values in its title; the edge peak's label covers no curve."""
    from labels import label_faults

    from fegear.toothpair.present.plot import flank_pressure_figure

    fig = flank_pressure_figure(solved, summary)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    panels = [a for a in fig.axes if a.get_visible()]
    assert all(a.get_legend() is None for a in panels)
    legend, = fig.legends
    assert legend.get_window_extent(renderer).y0 > max(
        a.get_tightbbox(renderer).y1 for a in panels)
    teeth = {t.tooth: t for t in solved.teeth}
    for a in panels:
        tooth = teeth[int(a.get_title().split(":")[0].split()[1])]
        if tooth.halfplane_flank_MPa:
            assert f"p ref {tooth.halfplane_flank_MPa:.0f}" in a.get_title()
        assert label_faults(a) == []


def test_the_legends_of_root_stress_and_cycle_cover_no_data(cycle, solved, summary, plt):
    from fegear.figures.labels import legend_cover
    from fegear.toothpair import DEFAULT_ALLOWABLES, HEADLINE
    from fegear.toothpair.analyses.cycle.plot import cycle_figure
    from fegear.toothpair.present.plot import root_stress_figure

    fig = root_stress_figure(solved, summary)
    ax, = fig.axes
    assert legend_cover(ax, ax.get_legend()) == 0
    _, result = cycle
    fig = cycle_figure(result.rows, "cycle", HEADLINE, DEFAULT_ALLOWABLES)
    for ax in fig.axes:
        assert legend_cover(ax, ax.get_legend()) == 0


def test_the_zoom_window_on_pair_png_cuts_no_tooth_number(baseline, plt):
    """Its dashed outline passes between the overview's numbers (it cut "13"), and the
    legend covers no gear."""
    from fegear.figures.labels import legend_cover
    from fegear.geometry import build_geometry
    from fegear.geometry.plot import pair_figure

    geo = build_geometry(baseline, backlash_positions=None)
    fig = pair_figure(geo.gear1, geo.gear2, baseline.e, baseline.r0, "pair",
                      6.5 * baseline.m, teeth=[(t.tooth, t.position_deg)
                                               for t in geo.contact.teeth],
                      tip_radius=geo.tip_radius)
    overview = fig.axes[0]
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    window, = [p for p in overview.patches if not p.get_fill()]
    x0, y0, x1, y1 = window.get_window_extent(renderer).extents
    for t in overview.texts:
        b = t.get_window_extent(renderer)
        inside = x0 < b.x0 and b.x1 < x1 and y0 < b.y0 and b.y1 < y1
        outside = b.x1 < x0 or b.x0 > x1 or b.y1 < y0 or b.y0 > y1
        assert inside or outside, t.get_text()
    legend = overview.get_legend()
    assert (legend_cover(overview, legend) == 0
            or legend.get_window_extent(renderer).x0 > overview.get_window_extent(renderer).x1)


class Painters:
    """An executor whose processes made ready to draw keep the name of the function each is
    handed and run it here when its result is read, with what it was sent pickled and loaded
    again (as a :class:`~fegear.running.Primed` copy gets it); ``stopped``: reading a result
    raises KeyboardInterrupt instead, as a run stopped while its copies draw."""

    workers = 2
    shares_memory = True

    def __init__(self, stopped: bool = False) -> None:
        self.stopped, self.handed, self._left = stopped, [], 2

    def ready(self):
        if not self._left:
            return None
        self._left -= 1
        return self

    def submit(self, fn, /, *args):
        import pickle
        from types import SimpleNamespace

        from fegear.running import SERIAL

        self.handed.append(fn.__name__)
        if self.stopped:
            def stop():
                raise KeyboardInterrupt
            return SimpleNamespace(result=stop, done=lambda: False)
        return SERIAL.submit(fn, *pickle.loads(pickle.dumps(args)))

    def close(self) -> None:
        """Nothing runs elsewhere."""


def _contents(out):
    """Each file's bytes by name; summary.json's with the folder it lists its files in left
    out."""
    return {p.name: p.read_bytes().replace(str(out).encode(), b"OUT")
            for p in sorted(out.iterdir())}


@pytest.fixture(scope="module")
def written_here(solved, summary, tmp_path_factory):
    """The pair's files written by this process alone: what every other way must give."""
    from fegear.toothpair import write_pair_outputs

    out = tmp_path_factory.mktemp("here")
    return write_pair_outputs(solved, out, summary), _contents(out)


def test_the_pictures_are_handed_to_the_processes_made_ready_to_draw(solved, summary, tmp_path,
                                                                   written_here):
    """The charts go to one process made ready to draw, von Mises (from the part of the
    fields it shows) to the other, each by pickle; the files are the same, byte for byte, as
    those drawn here from the whole fields. An executor without such processes (SERIAL, a
    Dask cluster) has every picture drawn here."""
    from fegear.toothpair import Drawing, write_pair_outputs

    files, contents = written_here
    assert {"png", "flank_png", "root_png", "summary"} <= set(files)
    executor = Painters()
    got = write_pair_outputs(solved, tmp_path, summary, drawing=Drawing(executor))
    assert executor.handed == ["chart_pngs", "von_mises_bytes"]
    assert [(k, v.name) for k, v in got.items()] == [(k, v.name) for k, v in files.items()]
    assert _contents(tmp_path) == contents


def test_von_mises_from_the_part_it_shows_is_the_picture_of_the_whole_fields(solved, summary):
    """The cells sent to draw von Mises are a few of the whole bodies', and the picture of
    them is the very picture of the whole fields (what `fegear solve --out` drew before)."""
    from fegear.figures import png_bytes
    from fegear.toothpair.present.pictured import for_pictures
    from fegear.toothpair.present.plot import von_mises_bytes, von_mises_figure

    bodies, peaks = solved.detail.body_fields(), solved.detail.peak_fields()
    shown = for_pictures(solved, bodies, peaks)
    assert sum(len(b.cells) for b in shown.bodies) < 0.5 * sum(len(b.cells) for b in bodies)
    whole = png_bytes(von_mises_figure(solved, summary, bodies, peaks), 100)
    assert von_mises_bytes(shown.sol, summary, shown.bodies, shown.peaks, shown.spots) == whole


def test_von_mises_drawn_from_the_loaded_sectors_is_the_picture_of_the_whole_fields(
        solved, summary, written_here):
    """von Mises is sent to draw from the loaded sectors' fields before the whole gears' are
    formed, and the file is the picture of the whole fields."""
    from fegear.figures import png_bytes
    from fegear.toothpair.present.plot import von_mises_figure

    _, contents = written_here
    bodies, peaks = solved.detail.body_fields(), solved.detail.peak_fields()
    assert contents["von_mises.png"] == png_bytes(
        von_mises_figure(solved, summary, bodies, peaks), 100)


def test_where_the_loaded_sectors_miss_a_shown_cell_von_mises_is_drawn_again(
        solved, summary, tmp_path, written_here):
    """Where the first drawing's fields lack cells the picture shows (here: every other
    sector's cells cut from them), :func:`same_drawing` says so and the file is drawn again
    here from the whole fields: the same picture."""
    import dataclasses

    from fegear.toothpair import Drawing, write_pair_outputs

    class Holed:
        """The solved detail, its loaded sectors' fields with half their cells cut."""

        def __init__(self, detail):
            self._detail = detail

        def __getattr__(self, name):
            return getattr(self._detail, name)

        def body_fields(self, around=None):
            bodies = self._detail.body_fields(around)
            if around is None:
                return bodies
            return tuple(dataclasses.replace(b, cells=b.cells[: len(b.cells) // 2])
                         for b in bodies)

    executor = Painters()
    holed = dataclasses.replace(solved, detail=Holed(solved.detail))
    write_pair_outputs(holed, tmp_path, summary, drawing=Drawing(executor))
    assert executor.handed == ["chart_pngs", "von_mises_bytes"]
    assert _contents(tmp_path) == written_here[1]


def test_same_drawing_takes_rounding_for_none_and_a_changed_value_for_one(solved):
    """Values within the last bits' rounding of each other draw the same; a stress changed
    by a millionth, a cell fewer or a hot spot moved do not."""
    import dataclasses

    from fegear.toothpair.present.pictured import for_pictures, same_drawing

    a = for_pictures(solved, solved.detail.body_fields(), solved.detail.peak_fields())

    def scaled(factor: float, cut: int = 0):
        b = a.bodies[0]
        data = {k: v * factor for k, v in b.data.items()}
        changed = dataclasses.replace(b, data=data, cells=b.cells[cut:])
        return dataclasses.replace(a, bodies=(changed, *a.bodies[1:]))

    assert same_drawing(scaled(1 + 1e-13), a)
    assert not same_drawing(scaled(1 + 1e-6), a)
    assert not same_drawing(scaled(1.0, cut=1), a)
    moved = dataclasses.replace(a.spots[0], point=a.spots[0].point + 1e-3)
    assert not same_drawing(dataclasses.replace(a, spots=(moved, *a.spots[1:])), a)


def test_drawn_in_a_forked_copy_the_files_are_the_same_byte_for_byte(solved, summary, tmp_path,
                                                                       written_here):
    """As `fegear solve --out` writes them: the pictures drawn in the copies of this process
    that the spare core's executor made ready come back as the very PNG files drawn here
    alone, and the VTUs and summary.json are the same too."""
    from fegear.running import Forks
    from fegear.toothpair import Drawing, write_pair_outputs
    from fegear.toothpair.present.plot import prepare_pictures

    _, contents = written_here
    with Forks(2, prepare_pictures, ready=2) as forks:
        write_pair_outputs(solved, tmp_path, summary, drawing=Drawing(forks))
        assert forks.ready() is None   # both were used
    assert _contents(tmp_path) == contents
    for name in ("von_mises.png", "flank_pressure.png", "root_stress.png"):
        assert contents[name].startswith(PNG) and contents[name].endswith(b"IEND\xaeB`\x82")


def test_a_run_stopped_while_the_charts_are_drawn_leaves_no_file_half_written(solved, summary,
                                                                              tmp_path):
    """What is there when a run stops while its copies draw is whole: every VTU complete,
    no temporary file, and neither a picture nor summary.json (written last, it lists the
    files) half-written or there at all."""
    from fegear.toothpair import Drawing, write_pair_outputs

    with pytest.raises(KeyboardInterrupt):
        write_pair_outputs(solved, tmp_path, summary, drawing=Drawing(Painters(stopped=True)))
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted(["gear1.vtu", "gear2.vtu", "gear1_contact.vtu", "gear2_contact.vtu"])
    for name in names:
        data = (tmp_path / name).read_bytes()
        assert data.endswith(b"</VTKFile>\n" if name.endswith(".vtu") else b"IEND\xaeB`\x82")


def test_the_charts_handed_out_while_the_submodels_are_solved_are_the_charts_after(tmp_path):
    """solve_job hands its ``meanwhile`` the pictured position before its contact submodels
    are solved (the von Mises peak still the surface estimate), with the same teeth; the
    charts drawn from it then are the files drawn from the finished solve, byte for byte."""
    from fegear.toothpair import write_job
    from fegear.toothpair.job import solve_job
    from fegear.toothpair.present.pictured import light
    from fegear.toothpair.present.plot import chart_pngs

    seen = []
    job = prepare_job({"quality": "coarse", "no-estimate": True})
    solved = solve_job(job, meanwhile=lambda sol, summary: seen.append((sol, summary)))
    (early, summary), = seen
    assert early.von_mises_estimated and not solved.solution.von_mises_estimated
    assert early.teeth == solved.solution.teeth
    assert summary["inputs"] == solved.summary["inputs"]
    charts = Painters().ready().submit(chart_pngs, light(early), summary)
    write_job(solved, tmp_path / "early", charts=charts)
    write_job(solved, tmp_path / "after")
    early_files, after = _contents(tmp_path / "early"), _contents(tmp_path / "after")
    for name in ("flank_pressure.png", "root_stress.png"):
        assert early_files[name] == after[name]


def test_the_fields_are_formed_with_blas_on_one_thread(tmp_path, monkeypatch):
    """write_job forms and writes the fields with BLAS on one thread, as the solve does (the
    pictures are drawn on the other core meanwhile), and leaves the threads as it found them."""
    from threadpoolctl import threadpool_info, threadpool_limits

    from fegear.toothpair import write_job
    from fegear.toothpair.job import solve_job
    from fegear.toothpair.present import output

    def blas():
        return {i["filepath"]: i["num_threads"] for i in threadpool_info()
                if i["user_api"] == "blas"}

    seen = []
    write_vtu = output.write_vtu
    monkeypatch.setattr(output, "write_vtu", lambda *a: seen.append(blas()) or write_vtu(*a))
    solved = solve_job(prepare_job({"quality": "coarse", "no-estimate": True}))
    with threadpool_limits(limits=2, user_api="blas"):
        before = blas()
        assert set(before.values()) == {2}
        write_job(solved, tmp_path, pictures=False)
        assert seen and all(set(s.values()) == {1} for s in seen)
        assert blas() == before
