"""rbview's bridge: LCM (or an LCM log) on one side, browsers over a WebSocket on the other.

Modules:
  ``wire``       untrusted LCM bytes -> numpy arrays and JSON-ready dicts
  ``frames``     the binary state frame the page draws from (layout documented there)
  ``browser``    validation of what browsers send (commands, wrenches, replay controls)
  ``live``       the live source: subscribes to the server's channels, sends commands
  ``replay``     the log source: an LCM log played, paused, scrubbed at a speed
  ``server``     HTTP for the bundled page and the WebSocket, newest-state-only per client
  ``__main__``   the command line (``clients/web/rbview --help``)
"""
