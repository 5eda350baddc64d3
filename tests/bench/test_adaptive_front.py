"""tools/bench adaptive's reading of its measurements: which points it pairs and what it reports."""

from tracer_tools.bench import adaptive


def row(kind, variant, seconds, levels, rays):
    return {"kind": kind, "variant": variant, "seconds": seconds, "mean_levels": levels, "rays": rays}


ROWS = [
    row("uniform", "1x1", 1.0, 1.2, 100),
    row("uniform", "2x2", 4.0, 0.5, 400),
    row("uniform", "4x4", 16.0, 0.2, 1600),
    row("adaptive", "a", 0.5, 0.9, 40),  # under 1 level, worse than 2x2
    row("adaptive", "b", 2.0, 0.45, 150),  # as good as 2x2
    row("adaptive", "c", 3.0, 0.6, 120),  # beaten by b in error, cheaper in rays
    row("adaptive", "d", 20.0, 0.1, 2000),
]


def test_the_fewest_rays_under_one_level_of_each():
    found = adaptive.matched(ROWS)["rays_at_1_level"]
    assert (found["adaptive"], found["uniform"]) == ("a", "2x2")
    assert found["ratio"] == 40 / 400


def test_the_strict_pairing_sets_each_point_against_a_uniform_as_good():
    # a (0.9) is matched by 2x2 (0.5 <= 0.9): 40/400; b (0.45) by 4x4: 150/1600; c by 2x2: 120/400.
    found = adaptive.matched(ROWS)["rays_as_good"]
    assert (found["adaptive"], found["uniform"]) == ("b", "4x4")
    assert found["ratio"] == 150 / 1600


def test_time_at_matched_error_takes_the_fastest_adaptive_as_good():
    pairs = {p["at"]: p for p in adaptive.matched(ROWS)["adaptive_against_uniform"]}
    assert pairs["1x1"]["adaptive"] == "a" and pairs["1x1"]["time_ratio"] == 0.5
    assert pairs["2x2"]["adaptive"] == "b" and pairs["2x2"]["time_ratio"] == 0.5
    assert pairs["4x4"]["adaptive"] == "d" and pairs["4x4"]["time_ratio"] == 20.0 / 16.0


def test_the_same_error_within_one_percent_admits_a_point_just_over():
    rows = ROWS + [row("adaptive", "e", 10.0, 0.2 * 1.005, 900)]  # 0.5% over 4x4's error
    pairs = {p["at"]: p for p in adaptive.matched(rows)["adaptive_against_uniform"]}
    assert pairs["4x4"]["adaptive"] == "d"  # strictly: only d is as good
    assert pairs["4x4"]["adaptive_within"] == "e" and pairs["4x4"]["time_ratio_within"] == 10.0 / 16.0
    assert pairs["2x2"]["adaptive_within"] == "b"  # nothing within 1% is cheaper than b


def test_the_front_keeps_only_points_nothing_beats():
    assert adaptive.front(ROWS) == [(0.5, 0.9), (2.0, 0.45), (20.0, 0.1)]


def test_labels_name_the_cell_only_when_it_is_not_a_pixel():
    assert adaptive.adaptive_label(0.05, 3, 1) == "0.05 depth 3"
    assert adaptive.adaptive_label(0.1, 2, 8) == "0.1 depth 2 cell 8"
