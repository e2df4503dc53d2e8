"""The Python client reads RBSIM_CONTACTS: a box resting on the ground is held
up by its weight at its four corners (tests/e2e/worlds/contacts.yaml, contacts
every step, the server paused and stepped)."""

import os

from harness import REPO, Client, CLIENT_TIMEOUT, Server, run
from rbsim.constants import ContactKind

WORLD = os.path.join(REPO, "tests", "e2e", "worlds", "contacts.yaml")


def resting_box(workdir):
    sim = Client(timeout=CLIENT_TIMEOUT)
    server = Server(workdir, WORLD, "--paused", "--state-rate", "0")
    try:
        sim.wait_state()
        world = sim.request_world()
        ack = sim.step(300, sync=True, check=True)
        last = ack.effective_step + 299
        contacts = sim.wait_contacts(step=last)
        assert contacts.step == last, contacts
        ground, crate = world["ground"].id, world["crate"].id
        corners = contacts.between(ground, crate)
        assert len(corners) == 4, (contacts, contacts.names(sim.state))
        assert ("ground", "crate") in contacts.names(sim.state)
        weight_impulse = world["crate"].mass * 9.81 * world.dt
        total = float(contacts.normal_impulses[corners].sum())
        assert abs(total - weight_impulse) < 1e-9 * weight_impulse + 1e-12, (total, weight_impulse)
        assert all(ContactKind(k) == ContactKind.RESTING for k in contacts.classifications[corners])
        assert contacts.positions.shape == (len(contacts), 3) and contacts.normals.shape == (len(contacts), 3)
        assert repr(contacts).startswith("Contacts(step=%d" % last)
    finally:
        sim.close()
        assert server.stop() == 0


if __name__ == "__main__":
    run({"resting_box": resting_box})
