"""Recording: lcm-logger (scenarios/recording.py) and rbserver --record."""

import numpy as np

from rbsim import world_state_t
from rbsim.log import load_log


def test_lcm_logger_session(scenario):
    scenario("recording.py", "lcm_logger")


def test_rbserver_record_has_every_step(recorded_log):
    """--state-rate 0 --real-time-factor 0 --duration 1: the record holds the
    state of every step 0..1000, each complete, in order."""
    log = load_log(recorded_log)
    assert len(log.states) == 1001, len(log.states)
    assert np.array_equal(log.states.step, np.arange(1001))
    assert log.states.missing_steps() == []
    assert log.incomplete_steps == []
    assert log.undecodable == []
    assert np.allclose(log.states.sim_time, log.states.step * 1e-3, rtol=0, atol=1e-12)
    # Every published state is in the file, in order: the initial one, one
    # per step, then repeats of step 1000 (the server republishes the state
    # when it stops stepping, and once more at exit).
    state_events = [e for e in log.events if e.channel == "RBSIM_STATE"]
    event_steps = [world_state_t.decode(e.data).step for e in state_events]
    assert event_steps[:1001] == list(range(1001))
    assert set(event_steps[1001:]) <= {1000}, event_steps[1001:]
    # The tumbling body tumbles, the others rest.
    spinner = log.states["spinner"]
    assert not np.allclose(spinner.orientation[0], spinner.orientation[-1])
    assert np.all(log.states["box"].position == log.states["box"].position[0])
    assert log.channels["RBSIM_WORLD"] >= 1 and log.channels["RBSIM_STATUS"] >= 1


def test_a_corrupt_step_in_a_replay_log_stops_at_once(recorded_log, tmp_path):
    """A log whose state claims step 2^62 is refused with exit 3 naming the
    event, in well under the time stepping to it would take."""
    import subprocess
    import time

    from conftest import RBSERVER, TESTS
    from rbsim import world_state_t
    from rbsim.lcm_ctypes import EventLog

    bad = tmp_path / "corrupt.lcmlog"
    corrupted = None
    with EventLog(str(recorded_log)) as source, EventLog(str(bad), "w") as out:
        for event in source:
            data = event.data
            if corrupted is None and event.channel == "RBSIM_STATE":
                message = world_state_t.decode(data)
                if message.step == 500:
                    message.step = 2 ** 62
                    data = message.encode()
                    corrupted = event.eventnum
            out.write(event.channel, data, event.timestamp)
    assert corrupted is not None
    started = time.monotonic()
    proc = subprocess.run([RBSERVER, "--config", str(TESTS + "/worlds/free_bodies.yaml"), "--replay", str(bad),
                           "--verify"], capture_output=True, text=True, timeout=60)
    assert time.monotonic() - started < 30
    assert proc.returncode == 3, proc.stdout + proc.stderr
    assert "event " in proc.stderr and "4611686018427387904" in proc.stderr, proc.stderr
    assert "corrupt log" in proc.stderr, proc.stderr
