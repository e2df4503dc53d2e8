"""Two servers on one URL and channel prefix: the second refuses to start
(unless --allow-other-instances, which only warns), every status names its
instance, and clients that see two instances say so."""

import os
import subprocess
import time

from harness import BUILD, CLIENT_TIMEOUT, Client, Server, run, run_cli, subprocess_env, wait_until

RBCTL = os.path.join(BUILD, "clients", "cpp", "rbctl")


def second_server(workdir):
    sim = Client(timeout=CLIENT_TIMEOUT)
    first = Server(workdir, "free_bodies")
    others = []
    try:
        sim.wait_state()
        status = sim.wait_status()
        assert status.instance_id and status.other_instance_id == "", status
        first_id = status.instance_id

        # The same prefix: refused, with the reason and the way out; the first runs on.
        refused = Server(workdir, "free_bodies")
        assert refused.wait(10) != 0, "a second server on the same prefix started"
        text = refused.output()
        assert "another server publishes on channel prefix 'RBSIM_'" in text, text
        assert "--allow-other-instances" in text and "--channel-prefix" in text, text
        assert first.alive()

        # Another prefix: no conflict.
        apart = Server(workdir, "free_bodies", "--channel-prefix", "APART_")
        others.append(apart)
        time.sleep(1.0)
        assert apart.alive(), apart.output()
        assert "another server" not in apart.output()

        # Forced: it warns and runs; each server's status then names the other,
        # and clients say so.
        forced = Server(workdir, "free_bodies", "--allow-other-instances")
        others.append(forced)
        wait_until(lambda: len(sim.server_instances) == 2, 10, "statuses of two instances")
        assert first_id in sim.server_instances
        assert "two servers publish on prefix 'RBSIM_'" in sim.instance_conflict()
        assert "running anyway (--allow-other-instances)" in forced.output(), forced.output()
        wait_until(lambda: sim.status is not None and sim.status.other_instance_id != "", 10,
                   "a status that names the other instance")
        wait_until(lambda: "another server publishes on RBSIM_STATUS" in first.output(), 10,
                   "the first server's warning")

        # A status names the other instance (each server hears the other's),
        # so a CLI that reads one says so, whichever server's it reads.
        proc = subprocess.run([RBCTL, "--timeout", str(CLIENT_TIMEOUT), "status"], capture_output=True,
                              text=True, timeout=30, env=subprocess_env())
        assert proc.returncode == 0 and "\ninstance_id " in proc.stdout, proc.stdout
        assert "rbctl: warning: " in proc.stderr and "hears another server" in proc.stderr, proc.stderr
        proc = run_cli("status")
        assert proc.returncode == 0 and "\nother_instance_id " in proc.stdout, proc.stdout
        assert "rbsim status: warning: " in proc.stderr, proc.stderr
    finally:
        sim.close()
        for server in others:
            server.stop()
        assert first.stop() == 0


if __name__ == "__main__":
    run({"second_server": second_server})
