"""DE NIRO's arrange_coordinates: lowest layer first, left takes largest y, right smallest."""

from pyramid_sim import arrange, pyramid, pyramid_even


def test_bottom_up_outermost_first_alternating():
    order = arrange(pyramid_even(4))
    assert [a.arm for a in order] == ["left", "right"] * 10
    layers = [a.target.layer for a in order]
    assert layers == sorted(layers)
    bottom = [round(a.target.pose.y, 3) for a in order if a.target.layer == 0]
    assert bottom == [0.416, -0.396, 0.3, -0.28, 0.184, -0.164, 0.068, -0.048]


def test_odd_count_left_places_last():
    order = arrange(pyramid(2))  # 3 bricks: 2, 1
    assert [a.arm for a in order] == ["left", "right", "left"]
    assert order[-1].target.layer == 1


def test_middle_brick_of_an_odd_layer():
    order = arrange(pyramid(3))  # 6 bricks: 3, 2, 1
    # layer of three: left 0.126, right -0.106, then left the middle one
    assert [(a.arm, round(a.target.pose.y, 3)) for a in order[:3]] == [
        ("left", 0.126),
        ("right", -0.106),
        ("left", 0.01),
    ]


def test_indices_follow_build_order_and_cover_every_brick():
    targets = pyramid(4)
    order = arrange(targets)
    assert [a.index for a in order] == list(range(len(targets)))
    assert sorted(id(a.target) for a in order) == sorted(id(t) for t in targets)


def test_matches_de_niros_own_loop():
    """An independent port of DE NIRO's while-loop gives the same left and right lists."""
    targets = pyramid(4)
    lay = [[t.pose.x, t.pose.y, t.pose.z] for t in targets]
    r_arm, l_arm = [], []
    while lay:
        z = min(p[2] for p in lay)
        left = max((p for p in lay if p[2] == z), key=lambda p: p[1])
        l_arm.append(left)
        lay.remove(left)
        if lay:
            z = min(p[2] for p in lay)
            right = min((p for p in lay if p[2] == z), key=lambda p: p[1])
            r_arm.append(right)
            lay.remove(right)
    order = arrange(targets)
    assert [
        [a.target.pose.x, a.target.pose.y, a.target.pose.z] for a in order if a.arm == "left"
    ] == l_arm
    assert [
        [a.target.pose.x, a.target.pose.y, a.target.pose.z] for a in order if a.arm == "right"
    ] == r_arm
