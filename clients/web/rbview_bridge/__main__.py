"""rbview: the browser viewer's bridge. ``clients/web/rbview --help``."""

import argparse
import asyncio
import ipaddress
import logging
import os
import signal
import sys

from . import locate


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog="rbview",
        description="Serves rbsim's 3D viewer page and streams the simulation to it over a WebSocket. "
                    "Open the printed URL in a browser.")
    parser.add_argument("--url", default=None,
                        help="LCM URL of the bus (default $LCM_DEFAULT_URL or "
                             "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152)")
    parser.add_argument("--prefix", default="RBSIM_", help="channel prefix of the world (default RBSIM_)")
    parser.add_argument("--bind", default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1: this host only; 0.0.0.0 opens it "
                             "to the network, with no authentication)")
    parser.add_argument("--port", type=int, default=8765, help="TCP port (default 8765; 0 picks a free one)")
    parser.add_argument("--read-only", action="store_true", help="watch only: the page's controls are off")
    parser.add_argument("--log", metavar="FILE", default=None,
                        help="replay an LCM log (rbserver --record or lcm-logger) instead of the live bus")
    parser.add_argument("--page", default=None,
                        help="the built page (default BUILD/clients/web/dist, BUILD being $RBSIM_BUILD_DIR, "
                             "else the build tree rbview is started in, else build/ of the source tree)")
    parser.add_argument("--port-file", default=None, help="write the listening port to this file (for tests)")
    parser.add_argument("--meshes", metavar="DIR", default=None,
                        help="serve the robots' visual meshes from DIR, the directory of the world file rbserver "
                             "runs (the 'world/' mesh URLs of world_t; without it robots are drawn from their "
                             "collision shapes)")
    parser.add_argument("--spawn-meshes", metavar="DIR", default=None,
                        help="serve spawned robots' visual meshes from DIR, rbserver's spawn directory (the "
                             "'spawn/' mesh URLs; default: the --meshes directory, as rbserver's default)")
    args = parser.parse_args(argv)
    try:
        ipaddress.ip_address(args.bind)
    except ValueError:
        parser.error("--bind %r: not an IP address" % args.bind)
    if not 0 <= args.port <= 65535:
        parser.error("--port %d: not in 0..65535" % args.port)
    if not args.prefix.replace("_", "a").isalnum() or len(args.prefix) > 40:
        parser.error("--prefix %r: use at most 40 letters, digits and '_'" % args.prefix)
    if args.log is not None and not os.path.isfile(args.log):
        parser.error("--log %s: no such file" % args.log)
    return args


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    logging.basicConfig(level=logging.INFO, format="rbview: %(levelname)s: %(message)s")
    try:
        build, how = locate.locate()
    except locate.NotFound as error:
        print("rbview: %s" % error, file=sys.stderr)
        return 2
    # The rbsim package (clients/python) takes the message types from there.
    os.environ["RBSIM_BUILD_DIR"] = build
    logging.getLogger("rbview").info("build %s (%s)", build, how)
    try:
        from . import server  # after argument checks: imports the lcm-gen types
    except ImportError as error:
        # A missing Debian package (python3-websockets, python3-numpy): say which.
        print("rbview: %s (scripts/install_deps.sh installs what rbview needs)" % error, file=sys.stderr)
        return 2

    if not ipaddress.ip_address(args.bind).is_loopback:
        logging.getLogger("rbview").warning(
            "listening on %s: anyone who can reach this port can watch%s (no authentication)",
            args.bind, "" if args.read_only else " and drive the simulation; consider --read-only")
    page = args.page or os.path.join(build, locate.PAGE_SUBDIR)
    try:
        from .meshes import MeshFiles
        mesh_files = MeshFiles({"world": args.meshes, "spawn": args.spawn_meshes or args.meshes})
        static = server.StaticFiles(page, mesh_files)
    except OSError as error:
        print("rbview: %s" % error, file=sys.stderr)
        return 2

    loop = asyncio.new_event_loop()
    asyncio.set_event_loop(loop)
    hub = server.Hub(loop, read_only=args.read_only, mode="replay" if args.log else "live")
    try:
        if args.log:
            from .replay import LogSource
            source = LogSource(hub, args.log, args.prefix)
        else:
            from rbsim.client import default_url
            from .live import LiveSource
            source = LiveSource(hub, args.url or default_url(), args.prefix)
    except Exception as error:
        print("rbview: %s" % error, file=sys.stderr)
        return 2
    hub.source = source

    def ready(port):
        if args.port_file:
            with open(args.port_file + ".tmp", "w") as f:
                f.write("%d\n" % port)
            os.replace(args.port_file + ".tmp", args.port_file)
        host = args.bind if ":" not in args.bind else "[%s]" % args.bind
        print("rbview: open http://%s:%d/ in a browser" % (host, port), flush=True)

    task = loop.create_task(server.serve(hub, static, args.bind, args.port, ready))
    for signum in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(signum, task.cancel)
    try:
        loop.run_until_complete(task)
    except asyncio.CancelledError:
        pass
    except OSError as error:
        print("rbview: cannot listen on %s:%d: %s" % (args.bind, args.port, error), file=sys.stderr)
        return 2
    finally:
        source.close()
        loop.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
