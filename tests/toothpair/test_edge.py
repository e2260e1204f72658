"""Flank and edge pressure apart (fegear.toothpair.edge) on pressures whose parts are known."""

import math

import numpy as np
import pytest

from fegear.toothpair.edge import EDGE_ZONE, FlankEdge, flank_and_edge

E_STAR = 103_000.0


def _hertz(s, centre, b, p0):
    return p0 * np.sqrt(np.clip(1.0 - ((s - centre) / b) ** 2, 0.0, None))


def test_a_flank_contact_alone_is_all_flank():
    s = np.linspace(0.0, 1.0, 2001)
    p = _hertz(s, 0.6, 0.1, 500.0)
    split = flank_and_edge(s, p, s < 0.2, 5.0, 0.25, E_STAR)
    assert split.flank_MPa == pytest.approx(p.max(), rel=0.0)
    assert split.edge_MPa == 0.0 and split.edge_load_N == 0.0 and not split.edge


@pytest.mark.parametrize("round_at", [0.2, -1.0])   # with a tip round and without
def test_a_tooth_without_pressure_is_nothing_on_flank_or_round(round_at):
    # what a record gives an unloaded tooth without splitting its pressure
    # (fegear.toothpair.ring.results.tooth_result)
    s = np.linspace(0.0, 1.0, 41)
    assert flank_and_edge(s, np.zeros(41), s < round_at, 5.0, 0.25, E_STAR) == \
        FlankEdge(0.0, 0.0, 0.0)


def test_an_edge_spike_beside_a_flank_contact_is_split_at_its_own_width():
    """A Hertz spike of half-width b_e on the round (s < 0.2) beside a 500 MPa flank contact:
    the edge pressure is the spike's peak, the edge load its force on the round, and the flank
    pressure the flank's peak, though the spike's tail on the flank side is higher."""
    s = np.linspace(0.0, 1.0, 200001)
    q_round = 20.0                                      # N/mm on the round
    b_e = math.sqrt(4 * q_round * 0.25 / (math.pi * E_STAR))
    p0 = 2 * q_round / (math.pi * b_e)
    # centred on the round's end: half its force on the round
    spike = _hertz(s, 0.2, b_e, p0)
    flank = _hertz(s, 0.6, 0.3, 500.0)
    on_round = s <= 0.2
    tail = spike[(~on_round) & (s < 0.2 + 0.5 * b_e)].max()
    assert tail > 500.0
    split = flank_and_edge(s, spike + flank, on_round, 5.0, 0.25, E_STAR)
    assert split.edge_MPa == pytest.approx(p0 + _hertz(np.array([0.2]), 0.6, 0.3, 500.0)[0],
                                           rel=1e-6)
    on = np.trapezoid((spike + flank)[on_round], s[on_round])
    assert split.edge_load_N == pytest.approx(5.0 * on, rel=1e-3)
    far = (s > 0.2 + EDGE_ZONE * b_e)
    assert split.flank_MPa == pytest.approx((spike + flank)[far].max(), rel=1e-9)
    assert split.flank_MPa == pytest.approx(500.0, rel=1e-3)


def test_the_split_does_not_hang_on_which_side_of_the_tangent_point_an_edge_peaks():
    """A Hertz spike on the round's end, peaking a third of its half-width on the round or as
    far off it, with a tail falling slowly down the flank (as on these near-conformal flanks)
    beside a lighter flank contact: the round's load moves 2.4-fold between the two, its
    largest pressure by 6 %, and the flank pressure, the tail read 10 b_e from the round, by
    2.3 %. (With b_e from the round's load it moved by 13 %.)"""
    s = np.linspace(0.0, 1.0, 400001)
    on_round = s <= 0.2
    b_e = 0.004
    p0 = E_STAR * b_e / (2 * 0.25)
    tail = np.where(on_round, 0.0, 1200.0 * np.exp(-(s - 0.2) / 0.1))
    flank = _hertz(s, 0.6, 0.3, 300.0)
    reads = [flank_and_edge(s, _hertz(s, centre, b_e, p0) + tail + flank, on_round, 5.0, 0.25,
                            E_STAR) for centre in (0.2 - b_e / 3, 0.2 + b_e / 3)]
    assert reads[0].edge_load_N > 2.0 * reads[1].edge_load_N
    assert reads[1].edge_MPa == pytest.approx(reads[0].edge_MPa * math.sqrt(8) / 3, rel=1e-3)
    assert reads[0].flank_MPa > 600.0
    assert reads[0].flank_MPa == pytest.approx(reads[1].flank_MPa, rel=0.03)
