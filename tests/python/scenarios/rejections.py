"""Bad requests are rejected with a reason and the server keeps stepping.

Server running in real time (a state every 10 ms). Each bad request must be
answered by one ack with accepted = false, effective_step = -1 and a reason;
undecodable messages are answered with client "" and seq -1.
"""

import time

from harness import run, session
from rbsim import ack_t, command_t
from rbsim.client import Rejected


def _rejected(ack, *words):
    assert not ack.accepted, "accepted, expected a rejection"
    assert ack.effective_step == -1, ack.effective_step
    for word in words:
        assert word in ack.reason, "reason %r lacks %r" % (ack.reason, word)
    return ack


def rejections(workdir):
    with session(workdir, "free_bodies", "--state-rate", "100") as (sim, server):
        sim.wait_state(predicate=lambda s: s.step > 100)
        status0 = sim.wait_status()

        _rejected(sim.apply_wrench("nosuch", (1, 0, 0), point=(0, 0, 0), wait=True, check=False),
                  "unknown body", "nosuch")
        _rejected(sim.apply_wrench("box", (float("nan"), 0, 0), wait=True, check=False), "finite")
        _rejected(sim.apply_wrench("box", (0, 0, 0), torque=(0, float("inf"), 0), wait=True, check=False), "finite")
        _rejected(sim.apply_wrench("box", (1, 0, 0), apply_at_step=1, wait=True, check=False), "past")
        _rejected(sim.apply_wrench("box", (1, 0, 0), mode="duration", duration=0.0, wait=True, check=False),
                  "duration")
        _rejected(sim.apply_wrench("box", (1e12, 0, 0), wait=True, check=False), "force")
        # By default a rejection raises, naming the reason: a typo is never silent.
        try:
            sim.apply_wrench("boxx", (1, 0, 0))
        except Rejected as exc:
            assert "unknown body 'boxx'" in str(exc) and not exc.ack.accepted, exc
        else:
            raise AssertionError("apply_wrench on an unknown body did not raise")
        _rejected(sim.send_command(0), "unknown command")
        _rejected(sim.send_command(42), "unknown command")
        _rejected(sim.remove("nosuch"), "nosuch")
        sent = 10

        # Garbage on both input channels: an ack with client "" and seq -1.
        for channel, kind in (("WRENCH", ack_t.KIND_WRENCH), ("COMMAND", ack_t.KIND_COMMAND)):
            mark = sim.ack_count
            sim.lcm.publish(sim.channel(channel), b"\x00\x01garbage, not an LCM message\xff" * 3)
            ack = sim.wait_any_ack(lambda a: a.kind == kind and a.client == "", since=mark)
            _rejected(ack, "undecodable")
            assert ack.seq == -1, ack.seq
            sent += 1
        # A valid command_t on the wrench channel is undecodable there too.
        message = command_t()
        message.command, message.client, message.seq = command_t.PAUSE, sim.client_id, 999
        mark = sim.ack_count
        sim.lcm.publish(sim.channel("WRENCH"), message.encode())
        _rejected(sim.wait_any_ack(lambda a: a.kind == ack_t.KIND_WRENCH and a.client == "",
                                   since=mark), "undecodable")
        sent += 1

        # Still stepping, and counting the rejections.
        a = sim.wait_state()
        time.sleep(0.1)
        b = sim.wait_state()
        assert b.step > a.step + 50, "server stopped stepping: %d -> %d" % (a.step, b.step)
        assert server.alive()
        status = sim.wait_status(predicate=lambda s: s.commands_rejected >= sent)
        assert status.commands_rejected - status0.commands_rejected == sent, (
            status.commands_rejected, status0.commands_rejected, sent)
        assert not status.paused


if __name__ == "__main__":
    run({"rejections": rejections})
