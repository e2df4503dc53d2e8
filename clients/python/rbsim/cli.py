"""``python3 -m rbsim``: command line for an rbsim server.

    python3 -m rbsim state [--body NAME]        print the next complete state
    python3 -m rbsim status                     print the next heartbeat
    python3 -m rbsim bodies                     print the world description
    python3 -m rbsim wrench BODY [--force FX FY FZ] [--torque ...] [--point ...]
                            [--frame world|body] [--point-frame world|body]
                            [--mode one-step|duration|persistent|clear|clear-all]
                            [--duration S] [--at-step K]
    python3 -m rbsim pause | resume | reset
    python3 -m rbsim step [N] [--no-wait]
    python3 -m rbsim rtf X
    python3 -m rbsim spawn FILE | - | --yaml TEXT
    python3 -m rbsim remove NAME | --joint NAME
    python3 -m rbsim joints                     print the joints and their state
    python3 -m rbsim joint NAME off|velocity|position|effort [TARGET]
                           [--max-effort E] [--stiffness K] [--damping D] [--at-step K]
    python3 -m rbsim robot state NAME [--json] [--dynamics]
    python3 -m rbsim robot command NAME [--joint J[,J...]]... [--mode M[,M...]]
                           [--position Q,...] [--velocity V,...] [--effort E,...]
                           [--stiffness K,...] [--damping D,...] [--max-effort E,...]
                           [--at-step K] [--state-rate HZ] [--steps N]
    python3 -m rbsim plot LOG -o OUT.png [--bodies NAME ...]

The verbs, options, defaults, outputs and exit statuses are those of rbctl,
specified once in docs/cli.md (docs/cli_spec.json, checked against both by
tests/python/test_cli_conformance.py). Global options (before or after the
verb): --url, --prefix, --timeout, --client-id. Exit status: 0 done/accepted,
1 rejected by the server (or nothing to plot), 2 usage error, 3 no answer
within --timeout, 4 LCM could not be opened (or another error).
"""

import argparse
import os
import sys
import threading
import time

EXIT_OK, EXIT_REJECTED, EXIT_USAGE, EXIT_TIMEOUT, EXIT_ERROR = 0, 1, 2, 3, 4


class CliError(Exception):
    """A failure to report as one line on stderr, with an exit status."""

    def __init__(self, message, status):
        super().__init__(message)
        self.status = status


_clients = []  # every Client a verb opened, for the instance-conflict warning


def _client(args):
    import warnings

    from .client import Client

    warnings.simplefilter("ignore", RuntimeWarning)  # main() reports conflicts once, on stderr
    client = Client(url=args.url, prefix=args.prefix, client_id=args.client_id)
    _clients.append(client)
    return client


def did_you_mean(name, known):
    """" (did you mean 'a', 'b' or 'c'?)" with the names of ``known``
    closest to ``name``, as the server's refusals put it (the rule of
    rbsim.errors.closest_names), or ""."""
    from .errors import closest_names

    names = ["'%s'" % n for n in closest_names(name, known)]
    if not names:
        return ""
    return " (did you mean %s?)" % (names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1])


def _report(ack, what):
    """Prints an accepted ack as rbctl does ("WHAT accepted: effective_step K
    [cleared N] [note TEXT]") or raises CliError for a rejection."""
    from .constants import AckKind, WrenchMode

    if not ack.accepted:
        raise CliError("%s rejected: %s" % (what, ack.reason or "no reason given"), EXIT_REJECTED)
    line = "%s accepted: effective_step %d" % (what, ack.effective_step)
    if ack.kind == AckKind.WRENCH and ack.request in (WrenchMode.CLEAR, WrenchMode.CLEAR_ALL):
        line += " cleared %d" % ack.wrenches_cleared
    if ack.reason:
        line += " note %s" % ack.reason
    print(line)
    return ack


# -- verbs -----------------------------------------------------------------------------


def cmd_state(args):
    from . import printing

    with _client(args) as sim:
        state = sim.wait_state(args.timeout)
    unknown = [n for n in args.body or [] if n not in state]
    if unknown:
        raise CliError("no body named '%s' in the state of step %d%s" % (
            unknown[0], state.step, did_you_mean(unknown[0], state.names())), EXIT_REJECTED)
    names = set(args.body or [])
    if args.json:
        print(printing.state_json(state, names))
    else:
        print("\n".join(printing.state_lines(state, names)))


def cmd_status(args):
    from . import printing

    with _client(args) as sim:
        status = sim.wait_status(args.timeout)
    print(printing.status_json(status) if args.json else "\n".join(printing.status_lines(status)))


def cmd_bodies(args):
    from . import printing

    with _client(args) as sim:
        sim.wait_state(args.timeout)  # the server is up and subscribed: the request is not lost
        world = sim.request_world(args.timeout)
    print(printing.world_json(world) if args.json else "\n".join(printing.world_lines(world)))


def cmd_wrench(args):
    mode = args.mode
    if mode is None:
        mode = "duration" if args.duration is not None else "one-step"
    mode = mode.replace("_", "-")
    if mode == "duration" and args.duration is None:
        raise CliError("--mode duration needs --duration S", EXIT_USAGE)
    clear = mode in ("clear", "clear-all")
    if clear and args.duration is not None:
        raise CliError("--duration goes with --mode duration, not %s" % mode, EXIT_USAGE)
    if not args.body and not clear:
        raise CliError("missing BODY (only --mode clear or clear-all may leave it out, for every body)",
                       EXIT_USAGE)
    with _client(args) as sim:
        ack = sim.apply_wrench(
            args.body, args.force, torque=args.torque, point=args.point, frame=args.frame,
            point_frame=args.point_frame, mode=mode, duration=args.duration or 0.0,
            apply_at_step=args.at_step, wait=True, check=False, timeout=args.timeout,
        )
    _report(ack, "wrench seq %d" % ack.seq)


def _simple_command(name):
    def run(args):
        with _client(args) as sim:
            ack = getattr(sim, name)(timeout=args.timeout)
        _report(ack, name)

    run.__name__ = "cmd_" + name
    return run


def cmd_step(args):
    if args.n < 1:
        raise CliError("step N: expected N >= 1, got %d" % args.n, EXIT_USAGE)
    with _client(args) as sim:
        ack = sim.step(args.n, timeout=args.timeout)
        _report(ack, "step %d" % args.n)
        if not args.no_wait:
            # The server publishes the state after the last requested step.
            state = sim.wait_for_step(ack.effective_step + args.n - 1, args.timeout + 1e-3 * args.n)
            print("step %d" % state.step)


def cmd_rtf(args):
    with _client(args) as sim:
        ack = sim.set_real_time_factor(args.factor, timeout=args.timeout)
    _report(ack, "rtf")


def cmd_spawn(args):
    if args.yaml is not None:
        if args.source is not None:
            raise CliError("give FILE, - or --yaml TEXT, not two of them", EXIT_USAGE)
        text = args.yaml
    elif args.source is None:
        raise CliError("missing FILE, - or --yaml TEXT", EXIT_USAGE)
    elif args.source == "-":
        text = sys.stdin.read()
    else:
        try:
            with open(args.source, encoding="utf-8") as f:
                text = f.read()
        except OSError as exc:
            raise CliError("cannot read '%s': %s (inline YAML goes after --yaml)"
                           % (args.source, exc.strerror or exc), EXIT_USAGE)
    with _client(args) as sim:
        ack = sim.spawn(text, timeout=args.timeout)
    _report(ack, "spawn")


def cmd_remove(args):
    if (args.name is None) == (args.joint is None):
        raise CliError("give a body NAME or --joint NAME, one of the two", EXIT_USAGE)
    with _client(args) as sim:
        if args.joint is not None:
            ack = sim.remove_joint(args.joint, timeout=args.timeout)
            _report(ack, "remove joint %s" % args.joint)
        else:
            ack = sim.remove(args.name, timeout=args.timeout)
            _report(ack, "remove %s" % args.name)


def cmd_joints(args):
    from . import printing

    with _client(args) as sim:
        sim.wait_state(args.timeout)  # the server is up and subscribed: the request is not lost
        world = sim.request_world(args.timeout)
        joints = None
        if world.joints:
            # The joints' state of the description's revision.
            joints = sim.joints
            if joints is None or joints.world_revision != world.world_revision:
                joints = sim._wait(
                    lambda: sim.joints if sim.joints is not None
                    and sim.joints.world_revision == world.world_revision else None,
                    args.timeout, "joint states on %s" % sim.channel("JOINTS"))
    print(printing.joints_json(world, joints) if args.json else "\n".join(printing.joint_lines(world, joints)))


def cmd_sensor(args):
    from .sensors import SensorReader, format_sensor

    if args.count < 1:
        raise CliError("sensor: --count must be at least 1", EXIT_USAGE)
    with _client(args) as sim, SensorReader(sim, args.name) as reader:
        for reading in reader.wait(count=args.count, timeout=args.timeout):
            print(format_sensor(reading))


def cmd_joint(args):
    off = args.mode == "off"
    if off and args.target is not None:
        raise CliError("MODE off takes no TARGET", EXIT_USAGE)
    if not off and args.target is None:
        raise CliError("MODE %s needs a TARGET" % args.mode, EXIT_USAGE)
    with _client(args) as sim:
        ack = sim.command_joint(args.name, args.mode, args.target or 0.0, max_effort=args.max_effort,
                                stiffness=args.stiffness, damping=args.damping,
                                apply_at_step=args.at_step, wait=True, check=False, timeout=args.timeout)
    _report(ack, "joint %s %s" % (args.name, args.mode))


def cmd_plot(args):
    from .log import load_log
    from .plot import make_figure

    try:
        log = load_log(args.log, prefix=args.prefix)
    except OSError as exc:
        raise CliError(str(exc), EXIT_ERROR)
    states = log.states
    unknown = [n for n in args.bodies or [] if n not in states]
    if unknown:
        raise CliError("no body named %s in %s (bodies: %s)" % (
            ", ".join(map(repr, unknown)), args.log, ", ".join(states.names) or "none"), EXIT_REJECTED)
    if len(states) == 0:
        raise CliError("no %sSTATE messages with bodies in %s" % (args.prefix, args.log), EXIT_REJECTED)
    try:
        figure = make_figure(log, args.quantity, args.bodies, os.path.basename(args.log))
    except ValueError as exc:
        raise CliError(str(exc), EXIT_REJECTED)
    figure.savefig(args.output, dpi=args.dpi)
    print("wrote %s (%d states, %d bodies, %s%s)" % (
        args.output, len(states), len(figure.rbsim_bodies),
        args.quantity, ", %d incomplete steps" % len(log.incomplete_steps) if log.incomplete_steps else ""))


# -- robot -------------------------------------------------------------------------------

# ack_t.KIND_ROBOT_COMMAND: the answer to a robot_command_t.
ROBOT_ACK_KIND = 4
# robot_command_t's modes by the names of --mode (docs/cli.md).
ROBOT_MODES = {"keep": -1, "off": 0, "velocity": 1, "position": 2, "effort": 3}
# The per-joint values of `robot command`: option, robot_command_t field.
ROBOT_VALUES = (("--position", "position"), ("--velocity", "velocity"), ("--effort", "effort"),
                ("--stiffness", "stiffness"), ("--damping", "damping"), ("--max-effort", "max_effort"))
# The modes whose target must be given: the value of the same name (the
# other values default to 0).
ROBOT_MODES_WITH_TARGET = ("velocity", "position", "effort")


class RobotStates:
    """The robot_state_t messages on <prefix>ROBOT_STATE, the newest of each
    robot, received on the client's LCM thread from the moment it exists."""

    def __init__(self, sim):
        from . import robot_state_t

        self._type = robot_state_t
        self._cond = threading.Condition()
        self._latest = {}  # robot -> its newest robot_state_t
        self._counts = {}  # robot -> how many arrived
        self.channel = sim.channel("ROBOT_STATE")
        sim.lcm.subscribe(self.channel, self._on_message, queue_capacity=1000)

    def _on_message(self, _channel, data, _utime):
        try:
            message = self._type.decode(data)
        except Exception:  # not a robot_state_t: not ours to report
            return
        with self._cond:
            self._latest[message.robot] = message
            self._counts[message.robot] = self._counts.get(message.robot, 0) + 1
            self._cond.notify_all()

    def heard(self):
        """The robots whose states arrived, sorted."""
        with self._cond:
            return sorted(self._latest)

    def count(self, robot):
        with self._cond:
            return self._counts.get(robot, 0)

    def wait(self, robot, timeout, after=0, ready=lambda state: True):
        """The newest state of ``robot`` once more than ``after`` arrived and
        it satisfies ``ready``, or None after ``timeout`` s."""
        deadline = time.monotonic() + timeout
        with self._cond:
            while True:
                state = self._latest.get(robot)
                if state is not None and self._counts[robot] > after and ready(state):
                    return state
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    return None
                self._cond.wait(remaining)


def _no_robot(sim, robots, name, timeout):
    """The error for a robot whose state did not come: rejected (exit 1) when
    the server was heard, naming the robots it publishes; else no answer."""
    heard = robots.heard()
    if heard:
        return CliError("no robot named '%s' on %s within %.3g s%s; robots heard: %s" % (
            name, robots.channel, timeout, did_you_mean(name, heard), ", ".join(heard)), EXIT_REJECTED)
    if sim.state is not None or sim.status is not None:
        return CliError("no robot named '%s': no robot states on %s within %.3g s (robots heard: none)"
                        % (name, robots.channel, timeout), EXIT_REJECTED)
    return TimeoutError("no robot state on %s within %.3g s (is rbserver running on %s with prefix %s?)"
                        % (robots.channel, timeout, sim.url, sim.prefix))


def _robot_state(sim, robots, name, timeout, after=0, ready=lambda state: True):
    state = robots.wait(name, timeout, after, ready)
    if state is None:
        if robots.count(name) > after:  # it came, but never as asked
            raise TimeoutError("no state of robot '%s' as expected on %s within %.3g s"
                               % (name, robots.channel, timeout))
        raise _no_robot(sim, robots, name, timeout)
    return state


def _send_robot_command(sim, robot, apply_at_step=-1, names=(), entries=None, state_rate=0.0,
                        state_dynamics=-1, steps=0):
    """Publishes one robot_command_t; returns its seq. ``entries``: field ->
    per-joint list (mode and the values), all of one length."""
    from . import robot_command_t

    message = robot_command_t()
    message.utime = int(time.time() * 1e6)
    message.client = sim.client_id
    message.seq = sim._next_seq()
    message.robot = robot
    message.apply_at_step = int(apply_at_step)
    entries = entries or {}
    message.num_joints = len(entries.get("mode", []))
    message.num_names = len(names)
    message.joint_names = list(names)
    message.mode = list(entries.get("mode", []))
    for _option, field in ROBOT_VALUES:
        setattr(message, field, list(entries.get(field, [0.0] * message.num_joints)))
    message.state_rate = float(state_rate)
    message.state_dynamics = int(state_dynamics)
    message.steps = int(steps)
    sim.lcm.publish(sim.channel("ROBOT_COMMAND"), message.encode())
    return message.seq


def _comma_list(option, text, convert, what):
    items = text.split(",")
    if any(item == "" for item in items):
        raise CliError("%s: expected %s separated by commas, got '%s'" % (option, what, text), EXIT_USAGE)
    return [convert(item) for item in items]


def _finite(option):
    def convert(item):
        try:
            value = float(item)
        except ValueError:
            value = float("nan")
        if value != value or value in (float("inf"), float("-inf")):
            raise CliError("%s: expected a finite number, got '%s'" % (option, item), EXIT_USAGE)
        return value

    return convert


def _robot_mode(item):
    mode = ROBOT_MODES.get(item)
    if mode is None:
        raise CliError("--mode: expected keep, off, velocity, position or effort, got '%s'" % item, EXIT_USAGE)
    return item


def _per_joint(option, values, count):
    """``values`` for ``count`` joints: one value for all, or one each."""
    if len(values) == 1:
        return values * count
    if len(values) != count:
        raise CliError("%s: %d values for %d joints (give one for all, or one per joint)"
                       % (option, len(values), count), EXIT_USAGE)
    return values


def cmd_robot_state(args):
    from . import printing

    with _client(args) as sim:
        robots = RobotStates(sim)
        if args.dynamics:
            after = robots.count(args.name)
            seq = _send_robot_command(sim, args.name, state_dynamics=1)
            ack = sim.wait_ack(seq, ROBOT_ACK_KIND, args.timeout)
            if not ack.accepted:
                raise CliError("robot %s dynamics rejected: %s" % (args.name, ack.reason or "no reason given"),
                               EXIT_REJECTED)
            # A state that carries them (or says why it cannot), from the
            # ones published since the request.
            state = _robot_state(sim, robots, args.name, args.timeout, after,
                                 lambda s: s.num_dofs > 0 or s.dynamics_note != "")
        else:
            state = _robot_state(sim, robots, args.name, args.timeout)
    if args.json:
        print(printing.robot_state_json(state, args.dynamics))
    else:
        print("\n".join(printing.robot_state_lines(state, args.dynamics)))


def cmd_robot_command(args):
    # Everything that does not depend on the robot is checked first, as rbctl does.
    names = [n for text in args.joint or [] for n in _comma_list("--joint", text, str, "joint names")]
    modes = _comma_list("--mode", args.mode, _robot_mode, "modes") if args.mode is not None else None
    values = {}
    for option, field in ROBOT_VALUES:
        text = getattr(args, field)
        if text is not None:
            values[field] = _comma_list(option, text, _finite(option), "numbers")
    if (names or values) and modes is None:
        raise CliError("give --mode for the joints commanded", EXIT_USAGE)
    for mode in modes or []:
        if mode in ROBOT_MODES_WITH_TARGET and mode not in values:
            raise CliError("--mode %s needs --%s" % (mode, mode), EXIT_USAGE)
    if args.steps < 0:
        raise CliError("--steps: expected N >= 0, got %d" % args.steps, EXIT_USAGE)
    with _client(args) as sim:
        robots = RobotStates(sim)
        entries = None
        if modes is not None:
            # No --joint: every joint of the robot, in its order, so its count.
            count = len(names) if names else _robot_state(sim, robots, args.name, args.timeout).num_joints
            entries = {"mode": [ROBOT_MODES[m] for m in _per_joint("--mode", modes, count)]}
            for option, field in ROBOT_VALUES:
                if field in values:
                    entries[field] = _per_joint(option, values[field], count)
        after = robots.count(args.name)
        seq = _send_robot_command(sim, args.name, args.at_step, names, entries, args.state_rate,
                                  steps=args.steps)
        ack = sim.wait_ack(seq, ROBOT_ACK_KIND, args.timeout)
        _report(ack, "robot %s command" % args.name)
        if args.steps > 0:
            # The server publishes the robot's state after the last step.
            last = ack.effective_step + args.steps - 1
            state = _robot_state(sim, robots, args.name, args.timeout + 1e-3 * args.steps, after,
                                 lambda s: s.step >= last)
            print("step %d" % state.step)


# -- parser ------------------------------------------------------------------------------


def _global_options(parser, suppress):
    """--url, --prefix, --timeout, --client-id; on sub-parsers they default to
    SUPPRESS so that a value given before the verb survives."""

    def default(value):
        return argparse.SUPPRESS if suppress else value

    parser.add_argument("--url", default=default(None),
                        help="LCM URL (default: $LCM_DEFAULT_URL, else "
                             "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152)")
    parser.add_argument("--prefix", default=default("RBSIM_"),
                        help="channel prefix (default RBSIM_)")
    parser.add_argument("--timeout", type=float, default=default(2.0),
                        help="seconds to wait for the server's answer (default 2)")
    parser.add_argument("--client-id", default=default(None),
                        help="client id echoed in acks (default py-<host>-<pid>)")


def build_parser():
    parser = argparse.ArgumentParser(
        prog="python3 -m rbsim",
        description="Command line for an rbsim server over LCM (SI units; world frame "
                    "right-handed, z up; quaternions w, x, y, z).",
        epilog="exit status: 0 ok, 1 rejected, 2 usage, 3 timeout, 4 other error",
    )
    _global_options(parser, suppress=False)
    verbs = parser.add_subparsers(dest="verb", metavar="VERB")
    verbs.required = True

    def verb(name, function, help_text):
        sub = verbs.add_parser(name, help=help_text, description=help_text)
        _global_options(sub, suppress=True)
        sub.set_defaults(function=function)
        return sub

    sub = verb("state", cmd_state, "print the next complete world state")
    sub.add_argument("--body", action="append", metavar="NAME",
                     help="only this body (repeatable; exit 1 if there is none)")
    sub.add_argument("--json", action="store_true", help="print JSON")

    sub = verb("status", cmd_status, "print the next status heartbeat")
    sub.add_argument("--json", action="store_true", help="print JSON")

    sub = verb("bodies", cmd_bodies, "print the world description (asks the server to publish it)")
    sub.add_argument("--json", action="store_true", help="print JSON")

    sub = verb("wrench", cmd_wrench, "apply a force and torque to a body")
    sub.add_argument("body", nargs="?", default="",
                     help="body name (may be left out with --mode clear or clear-all: every body)")
    sub.add_argument("--force", nargs=3, type=float, default=[0.0, 0.0, 0.0],
                     metavar=("FX", "FY", "FZ"), help="N, in --frame (default 0 0 0)")
    sub.add_argument("--torque", nargs=3, type=float, default=[0.0, 0.0, 0.0],
                     metavar=("TX", "TY", "TZ"), help="N*m, pure couple, in --frame (default 0 0 0)")
    sub.add_argument("--point", nargs=3, type=float, default=None, metavar=("PX", "PY", "PZ"),
                     help="m, where the force acts, in --point-frame (default: the centre of mass, "
                          "placed exactly by the server)")
    sub.add_argument("--frame", choices=["world", "body"], default="world",
                     help="frame of force and torque (default world: keeps its world direction; "
                          "body: the body's config frame, turning with it)")
    sub.add_argument("--point-frame", choices=["world", "body"], default=None,
                     help="frame of point (default: --frame): world = a world position when the "
                          "wrench first acts, carried with the body; body = fixed in the body")
    sub.add_argument("--mode", choices=["one-step", "duration", "persistent", "clear", "clear-all",
                                        "one_step", "clear_all"],
                     default=None, metavar="MODE",
                     help="one-step (default), duration, persistent, clear (this client's duration "
                          "and persistent wrenches) or clear-all (every client's); a clear's ack "
                          "says how many it cleared")
    sub.add_argument("--duration", type=float, default=None, metavar="S",
                     help="s of simulated time (implies --mode duration)")
    sub.add_argument("--at-step", type=int, default=-1, metavar="K",
                     help="the step during which it first acts (default -1: the next)")

    for name, help_text in (("pause", "stop stepping"), ("resume", "step again"),
                            ("reset", "return to the initial world (step 0)")):
        verb(name, _simple_command(name), help_text)

    sub = verb("step", cmd_step, "take N steps while paused (send pause first); waits for the state "
                                 "after the last of them unless --no-wait")
    sub.add_argument("n", type=int, nargs="?", default=1, help="number of steps (default 1)")
    sub.add_argument("--no-wait", action="store_true", help="return once the STEP is acknowledged")
    sub.add_argument("--sync", action="store_true", help=argparse.SUPPRESS)  # the old default-off wait

    sub = verb("rtf", cmd_rtf, "set the real-time factor")
    sub.add_argument("factor", type=float, metavar="X",
                     help="simulated s per wall-clock s: X > 0 paces the simulation, 0 runs it as "
                          "fast as possible")

    sub = verb("spawn", cmd_spawn, "add bodies and joints described in YAML (a bodies: entry of a world "
                                   "file, or bodies: and joints: lists as a world file has them)")
    sub.add_argument("source", nargs="?", default=None, metavar="FILE",
                     help="a YAML file, or '-' for standard input")
    sub.add_argument("--yaml", default=None, metavar="TEXT", help="the body's YAML given inline")

    sub = verb("remove", cmd_remove, "remove a body (with its joints) or a joint")
    sub.add_argument("name", nargs="?", default=None, help="body name")
    sub.add_argument("--joint", default=None, metavar="NAME", help="remove this joint instead (its bodies stay)")

    sub = verb("joints", cmd_joints, "print the joints (type, bodies, axis, limits) and their state "
                                     "(asks the server to publish the world description)")
    sub.add_argument("--json", action="store_true", help="print JSON")

    sub = verb("sensor", cmd_sensor, "print a sensor's readings (on <prefix>SENSOR_NAME), one line each: "
                                     "imu (specific force m/s^2 and angular velocity rad/s in the sensor "
                                     "frame, orientation w x y z), contact and force_torque (N, N*m in the "
                                     "sensor frame), range_scan (returns, nearest and farthest, and the "
                                     "ranges with at most 16 beams: inf no return, -inf below min range)")
    sub.add_argument("name", metavar="NAME", help="the sensor's name (the world file's sensors:)")
    sub.add_argument("--count", type=int, default=1, metavar="N", help="print N readings (default 1)")

    sub = verb("joint", cmd_joint, "command a joint's motor, position drive or effort (the modes are "
                                   "exclusive: each turns the joint's other actuators off)")
    sub.add_argument("name", metavar="NAME", help="joint name")
    sub.add_argument("mode", choices=["off", "velocity", "position", "effort"], metavar="MODE",
                     help="off (no TARGET), velocity (the motor drives the rate to TARGET, rad/s or "
                          "m/s), position (a spring and damper pull the joint to TARGET, rad or m) or "
                          "effort (a constant TARGET, N*m or N, along the axis)")
    sub.add_argument("target", type=float, nargs="?", default=None, metavar="TARGET",
                     help="rad/s or m/s, rad or m, N*m or N by MODE")
    sub.add_argument("--max-effort", type=float, default=0.0, metavar="E",
                     help="N*m or N: velocity: the motor's largest effort (default 0: the joint's effort "
                          "limit, refused for a joint without one); position: the drive's cap "
                          "(default 0: uncapped)")
    sub.add_argument("--stiffness", type=float, default=0.0, metavar="K",
                     help="position: N*m/rad or N/m (default 0)")
    sub.add_argument("--damping", type=float, default=0.0, metavar="D",
                     help="position: N*m*s/rad or N*s/m (default 0)")
    sub.add_argument("--at-step", type=int, default=-1, metavar="K",
                     help="the step from which it acts (default -1: the next)")

    robot = verbs.add_parser("robot", help="a robot's joints in one message: its state (robot_state_t) "
                             "or a command for all of them (robot_command_t)",
                             description="A robot's joints in one message (its joints are named "
                             "'<robot>/...'): robot state prints its robot_state_t, robot command "
                             "sends one robot_command_t.")
    _global_options(robot, suppress=True)
    robot_verbs = robot.add_subparsers(dest="robot_verb", metavar="state|command")
    robot_verbs.required = True

    def robot_verb(name, function, help_text):
        sub = robot_verbs.add_parser(name, help=help_text, description=help_text)
        _global_options(sub, suppress=True)
        sub.set_defaults(function=function)
        sub.add_argument("name", metavar="NAME", help="the robot's name")
        return sub

    sub = robot_verb("state", cmd_robot_state, "print the next state of robot NAME (robot_state_t): "
                     "its joints (full names, rad or m, rad/s or m/s, N*m or N; a mimic follower "
                     "names its leader) and its base's pose and twist (world frame)")
    sub.add_argument("--json", action="store_true", help="print JSON (the wire field names)")
    sub.add_argument("--dynamics", action="store_true",
                     help="turn the robot's dynamics on first (they stay on) and print them too: "
                          "the mass matrix M, the bias h and gravity g (and in JSON the links' "
                          "poses and Jacobians)")

    sub = robot_verb("command", cmd_robot_command,
                     "send one robot_command_t to robot NAME: applied whole at one step or refused "
                     "whole (exit 1); values are comma lists, one per joint (one value: all joints)")
    sub.add_argument("--joint", action="append", metavar="J[,J...]",
                     help="the joints commanded, '<joint>' or '<robot>/<joint>' (repeatable; "
                          "default: every joint of the robot, in its order)")
    sub.add_argument("--mode", default=None, metavar="M[,M...]",
                     help="keep (a mimic follower's), off, velocity, position or effort; needed "
                          "to command joints")
    sub.add_argument("--position", default=None, metavar="Q,...",
                     help="position: the target coordinate, rad or m (needed by position)")
    sub.add_argument("--velocity", default=None, metavar="V,...",
                     help="velocity: the target rate, rad/s or m/s (needed by velocity); position: "
                          "the rate the damping pulls to (default 0)")
    sub.add_argument("--effort", default=None, metavar="E,...",
                     help="effort: N*m or N (needed by effort); position and velocity: the "
                          "feed-forward effort added (default 0)")
    sub.add_argument("--stiffness", default=None, metavar="K,...",
                     help="position: N*m/rad or N/m (default 0; not both 0 with --damping)")
    sub.add_argument("--damping", default=None, metavar="D,...",
                     help="position: N*m*s/rad or N*s/m (default 0)")
    sub.add_argument("--max-effort", dest="max_effort", default=None, metavar="E,...",
                     help="N*m or N: velocity: the motor's largest effort (default 0: the joint's "
                          "effort limit); position: the drive's cap (default 0: uncapped)")
    sub.add_argument("--at-step", type=int, default=-1, metavar="K",
                     help="the step from which it acts (default -1: the next)")
    sub.add_argument("--state-rate", type=float, default=0.0, metavar="HZ",
                     help="how often the server publishes the robot's state from now on (default 0: "
                          "as it is; -1: with every world state)")
    sub.add_argument("--steps", type=int, default=0, metavar="N",
                     help="while paused: take N steps after applying it and wait for the robot's "
                          "state after the last (default 0)")

    sub = verb("plot", cmd_plot, "plot an LCM log: one panel per dynamic body against simulated time, "
                                 "wrenches and commands marked")
    sub.add_argument("log", help="LCM log (lcm-logger or rbserver --record)")
    sub.add_argument("-o", "--output", required=True, help="output image (PNG)")
    sub.add_argument("--bodies", nargs="+", metavar="NAME",
                     help="bodies to plot (default: every dynamic body)")
    sub.add_argument("--quantity", choices=["position", "velocity", "energy"], default="position",
                     help="x, y, z position (m), velocity (m/s) or kinetic energy (J) (default position)")
    sub.add_argument("--dpi", type=int, default=100, help="image resolution (default 100)")
    return parser


# Options whose value is a comma list of numbers: argparse would take a
# value such as "-0.5,1" for an option, so it is joined to its option.
_NUMBER_LIST_OPTIONS = ("--position", "--velocity", "--effort", "--stiffness", "--damping", "--max-effort")


def _join_number_lists(argv):
    out = []
    for argument in argv:
        if (out and out[-1] in _NUMBER_LIST_OPTIONS and argument[:1] == "-"
                and argument[1:2] in tuple("0123456789.")):
            out[-1] += "=" + argument
        else:
            out.append(argument)
    return out


def main(argv=None):
    args = build_parser().parse_args(_join_number_lists(sys.argv[1:] if argv is None else argv))
    try:
        args.function(args)
        for client in _clients:
            conflict = client.instance_conflict()
            if conflict:
                print("rbsim %s: warning: %s" % (args.verb, conflict), file=sys.stderr)
                break
    except CliError as exc:
        print("rbsim %s: %s" % (args.verb, exc), file=sys.stderr)
        return exc.status
    except TimeoutError as exc:
        print("rbsim %s: timeout: %s" % (args.verb, exc), file=sys.stderr)
        return EXIT_TIMEOUT
    except (OSError, RuntimeError, ValueError) as exc:
        print("rbsim %s: error: %s" % (args.verb, exc), file=sys.stderr)
        return EXIT_ERROR
    return EXIT_OK
