"""lcm-logger records a session; rbsim.log.load_log reads it back.

lcm-logger and the server run in the same private namespace. The server
publishes a state every step (1 kHz, real time) for 0.5 s of simulated time,
then exits; a client sends a wrench and a command meanwhile.
"""

import os
import signal
import subprocess
import time

from harness import CLIENT_TIMEOUT, Client, Server, np, run
from rbsim.log import load_log

URL = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152"


def lcm_logger(workdir):
    path = os.path.join(workdir, "session.lcmlog")
    logger = subprocess.Popen(["lcm-logger", "-q", "-f", "--lcm-url=" + URL, path],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        time.sleep(0.5)  # the logger joins the group
        assert logger.poll() is None, "lcm-logger exited: %s" % logger.stdout.read()
        with Client(client_id="recorder-test", timeout=CLIENT_TIMEOUT) as sim:
            server = Server(workdir, "free_bodies", "--state-rate", "0", "--real-time-factor", "1",
                            "--duration", "0.5")
            sim.wait_state()
            wrench_ack = sim.apply_wrench("box", (1.0, 0.0, 0.0), mode="duration", duration=0.1,
                                          wait=True, check=True)
            command_ack = sim.set_real_time_factor(1.0, check=True)
            assert server.wait(10.0) == 0, "rbserver failed"
        time.sleep(0.3)  # the last messages reach the logger
    finally:
        if logger.poll() is None:
            logger.send_signal(signal.SIGINT)
        logger.wait(5.0)
    assert logger.returncode == 0, "lcm-logger exited with %d" % logger.returncode

    log = load_log(path)
    steps = log.states.step
    assert len(log.states) == 501, "expected steps 0..500, got %d states (%s..%s), missing %s" % (
        len(log.states), steps.min(), steps.max(), log.states.missing_steps()[:20])
    assert np.array_equal(steps, np.arange(501)), "steps out of order or missing"
    assert log.states.missing_steps() == [] and log.incomplete_steps == []
    assert np.allclose(log.states.sim_time, steps * 0.001, rtol=0, atol=1e-12)
    assert log.states.names == ["box", "yawed", "spinner"]
    assert log.states["box"].position.shape == (501, 3)
    assert log.states["spinner"].orientation.shape == (501, 4)
    assert log.states["box"].present.all()

    # The box was pushed along +x from the wrench's effective step on, for 100 steps.
    k = wrench_ack.effective_step
    vx = log.states["box"].linear_velocity[:, 0]
    assert vx[k - 1] == 0.0 and vx[k] > 0.0
    assert abs(vx[k + 99] - 0.1 / 2.5) < 1e-12, vx[k + 99]

    ours = [w for w in log.wrenches if w.client == "recorder-test"]
    assert [w.seq for w in ours] == [wrench_ack.seq]
    assert [c.seq for c in log.commands if c.client == "recorder-test"] == [command_ack.seq]
    acks = {(a.kind, a.seq): a for a in log.acks if a.client == "recorder-test"}
    assert acks[(wrench_ack.kind, wrench_ack.seq)].effective_step == k
    assert acks[(command_ack.kind, command_ack.seq)].accepted
    assert log.statuses and log.worlds and log.worlds[0].by_name.keys() == {"box", "yawed", "spinner"}


if __name__ == "__main__":
    run({"lcm_logger": lcm_logger})
