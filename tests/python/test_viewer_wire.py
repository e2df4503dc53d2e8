"""rbview bridge: the fast state decoder (clients/web/rbview_bridge/wire.py) and
the frame built from its pages (frames.frame_from_pages) against lcm-gen's
decoder and the reference frame (frames.state_frame), on real multi-page
states that rbserver recorded (bench/worlds/large_2000.yaml), and on pages
edited with lcm-gen's encoder: a body that freezes, a new world revision,
short and corrupt pages."""

import os
import sys

import numpy as np
import pytest

from conftest import RBSERVER, REPO, _netns_run

sys.path.insert(0, os.path.join(REPO, "clients", "web"))

from rbsim import world_state_t, world_t  # noqa: E402
from rbsim.lcm_ctypes import EventLog  # noqa: E402
from rbview_bridge import frames, wire  # noqa: E402
from rbview_bridge.live import FrameBuilder  # noqa: E402


@pytest.fixture(scope="module")
def large_log(tmp_path_factory):
    """Pages of rbserver on 2000 spheres (several pages a state), 0.1 s at 60 Hz."""
    path = tmp_path_factory.mktemp("viewer_wire") / "large.lcmlog"
    _netns_run([RBSERVER, "--config", os.path.join(REPO, "bench", "worlds", "large_2000.yaml"),
                "--state-rate", "60", "--duration", "0.1", "--record", str(path),
                "--log-level", "warning"], timeout=120.0)
    states, worlds = [], []
    with EventLog(str(path)) as log:
        for event in log:
            if event.channel == "RBSIM_STATE":
                states.append(event.data)
            elif event.channel == "RBSIM_WORLD":
                worlds.append(event.data)
    assert states and worlds
    return states, worlds


def reference_numbers(message):
    return np.array([list(b.position) + list(b.orientation) + list(b.linear_velocity)
                     + list(b.angular_velocity) for b in message.bodies], dtype=np.float64).reshape(-1, 13)


def assert_same_as_lcm_gen(page, data):
    message = world_state_t.decode(data)
    assert (page.utime, page.step, page.sim_time, page.world_revision) == (
        message.utime, message.step, message.sim_time, message.world_revision)
    assert (page.page, page.num_pages, page.total_bodies, page.first_body_index, page.num_bodies) == (
        message.page, message.num_pages, message.total_bodies, message.first_body_index, message.num_bodies)
    assert list(page.ids) == [b.id for b in message.bodies]
    assert page.names == [b.name for b in message.bodies]
    assert page.frozen == [b.frozen for b in message.bodies]
    np.testing.assert_array_equal(page.numbers, reference_numbers(message))


def complete_states(decoder, datas):
    """Groups of complete pages, each as (pages, datas)."""
    grouping = wire.Pages()
    by_page = {}
    for data in datas:
        page = decoder.decode(data)
        by_page[id(page)] = data
        group = grouping.add(page.key(), page, page.num_pages)
        if group is not None:
            yield group, [by_page[id(p)] for p in group]


def reference_frame(datas, mask):
    """state_frame from lcm-gen's decode of every page."""
    messages = [world_state_t.decode(d) for d in datas]
    numbers = np.concatenate([reference_numbers(m) for m in messages])
    return frames.state_frame(messages[0], numbers, mask)


def test_fast_decode_matches_lcm_gen_on_every_recorded_page(large_log):
    states, _ = large_log
    decoder = wire.StatePageDecoder()
    pages = [decoder.decode(d) for d in states]
    assert max(p.num_pages for p in pages) >= 3, "the state should take several pages"
    for _ in range(2):  # first with new layouts, then with the cached ones
        for data in states:
            assert_same_as_lcm_gen(decoder.decode(data), data)


def test_frame_from_pages_is_the_reference_frame(large_log):
    states, worlds = large_log
    decoder = wire.StatePageDecoder()
    world_pages = wire.Pages()
    builder = FrameBuilder()
    for data in worlds:
        page = world_t.decode(data)
        group = world_pages.add((page.utime, page.step, page.world_revision), page, page.num_pages)
        if group is not None:
            builder.set_world(wire.world_to_dict(group))
    assert builder.static_mask is not None
    count = 0
    for group, datas in complete_states(decoder, states):
        assert wire.pages_tile(group)
        assert builder.frame(group) == reference_frame(datas, builder.static_mask)
        lazy = builder.lazy_frame(group)
        assert lazy.get() == builder.frame(group) and lazy.get() is lazy.get()
        # Some bodies static, some at rest: the at-rest count must agree too.
        mask = np.zeros(group[0].total_bodies, dtype=bool)
        mask[::7] = True
        assert frames.frame_from_pages(group, mask) == reference_frame(datas, mask)
        count += 1
    assert count >= 2


def reencoded(data, edit):
    message = world_state_t.decode(data)
    edit(message)
    return message.encode()


def test_a_body_that_freezes_changes_the_layout(large_log):
    states, _ = large_log
    decoder = wire.StatePageDecoder()
    data = states[0]
    decoder.decode(data)  # the layout of the page, cached

    def freeze(index, why):
        def edit(message):
            message.bodies[index].frozen = why
            message.bodies[index].linear_velocity = [0.0, 0.0, 0.0]
            message.bodies[index].angular_velocity = [0.0, 0.0, 0.0]
        return edit

    frozen_3 = reencoded(data, freeze(3, "non-finite velocity"))
    page = decoder.decode(frozen_3)
    assert page.frozen[3] == "non-finite velocity"
    assert_same_as_lcm_gen(page, frozen_3)
    # The same length and page as frozen_3, but another body frozen: the cached
    # layout must not be taken for it.
    frozen_5 = reencoded(data, freeze(5, "non-finite velocity"))
    assert len(frozen_5) == len(frozen_3)
    page = decoder.decode(frozen_5)
    assert page.frozen[5] == "non-finite velocity" and page.frozen[3] == ""
    assert_same_as_lcm_gen(page, frozen_5)
    assert_same_as_lcm_gen(decoder.decode(data), data)  # and thawed again


def test_a_new_world_revision_with_other_names(large_log):
    states, _ = large_log
    decoder = wire.StatePageDecoder()
    data = states[0]
    decoder.decode(data)

    def new_world(message):
        message.world_revision += 1
        for i, body in enumerate(message.bodies):
            body.name = "body_%d_%s" % (i, "x" * (i % 5))
            body.id += 1000

    changed = reencoded(data, new_world)
    page = decoder.decode(changed)
    assert page.world_revision == world_state_t.decode(data).world_revision + 1
    assert_same_as_lcm_gen(page, changed)
    # Same length and revision as the page before, other names: found anew.
    renamed = reencoded(data, lambda m: setattr(m.bodies[0], "name", m.bodies[0].name[::-1]))
    page = decoder.decode(renamed)
    assert_same_as_lcm_gen(page, renamed)


@pytest.mark.parametrize("cut", ["empty", "fingerprint only", "header only", "one byte short",
                                 "half", "one byte more"])
def test_short_pages_are_rejected_with_a_reason(large_log, cut):
    states, _ = large_log
    data = states[0]
    decoder = wire.StatePageDecoder()
    decoder.decode(data)  # a cached layout must not hide the damage
    bad = {"empty": b"", "fingerprint only": data[:8], "header only": data[:8 + 44],
           "one byte short": data[:-1], "half": data[:len(data) // 2], "one byte more": data + b"\0"}[cut]
    with pytest.raises(wire.WireError) as error:
        decoder.decode(bad)
    assert "world_state_t" in str(error.value)
    assert_same_as_lcm_gen(decoder.decode(data), data)  # the decoder goes on


def test_corrupt_pages_of_the_cached_length_are_rejected(large_log):
    states, _ = large_log
    data = states[0]
    decoder = wire.StatePageDecoder()
    page = decoder.decode(data)
    offset = int(page.layout.offsets[10])
    name_length_at = offset - len(page.names[10].encode()) - 1 - 4
    frozen_length_at = offset + 13 * 8
    damaged = {
        "a name length": name_length_at,
        "a frozen length": frozen_length_at,
        "num_bodies": 8 + 40,
    }
    for what, at in damaged.items():
        bad = bytearray(data)
        bad[at:at + 4] = (0x7FFFFFF0).to_bytes(4, "big")
        with pytest.raises(wire.WireError):
            decoder.decode(bytes(bad))
    wrong_id = bytearray(data)
    wrong_id[name_length_at - 4:name_length_at] = (12345678).to_bytes(4, "big")
    # An id that changed is not a layout error (lcm-gen takes it too), but the
    # cached ids must not be reported for it.
    assert decoder.decode(bytes(wrong_id)).ids[10] == 12345678
    bad_fingerprint = b"\0" * 8 + data[8:]
    with pytest.raises(wire.WireError, match="fingerprint"):
        decoder.decode(bad_fingerprint)
    assert_same_as_lcm_gen(decoder.decode(data), data)


def test_pages_that_do_not_tile_are_refused(large_log):
    states, _ = large_log
    decoder = wire.StatePageDecoder()
    for group, _ in complete_states(decoder, states):
        assert wire.pages_tile(group)
        if len(group) > 1:
            assert not wire.pages_tile(group[:1] + group[2:] + group[1:2])
            assert wire.merge_state(group[::-1]) is None
        break
