"""What a browser may send, checked before anything is done with it.

Every message is one JSON object in a text frame with a "type":

  {"type": "ready"}                       the page took the last state frame: send the next
  {"type": "command", "id": N, "command": "pause" | "resume" | "step" | "reset"
      | "set_real_time_factor", "num_steps": int, "real_time_factor": number}
  {"type": "wrench", "id": N, "body": name, "force": [fx, fy, fz] (N, world),
      "point": [x, y, z] (m, world), "duration": s}
  {"type": "replay", "id": N, "action": "play" | "pause" | "seek" | "speed",
      "index": int (seek: the row of the log's timeline), "speed": number}

A message that is not that (binary, not JSON, not an object, an unknown type or
field of the wrong type) raises BrowserMessageError: the bridge closes that
connection, since a page of ours never sends one. Values that are well-typed
but out of range (a STEP of 0 steps, a negative real-time factor) are passed
on: rbserver judges them and its ack carries the reason to the page.
"""

import json
import math

MAX_MESSAGE_BYTES = 4096
COMMANDS = ("pause", "resume", "step", "reset", "set_real_time_factor")
REPLAY_ACTIONS = ("play", "pause", "seek", "speed")


class BrowserMessageError(ValueError):
    pass


def _reject_constant(name):
    raise BrowserMessageError("non-finite number %s" % name)


def _integer(message, key, low=-(2 ** 62), high=2 ** 62):
    value = message.get(key)
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise BrowserMessageError("%r must be an integer in [%d, %d]" % (key, low, high))
    return value


def _number(message, key):
    value = message.get(key)
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise BrowserMessageError("%r must be a finite number" % key)
    return float(value)


def _vector3(message, key):
    value = message.get(key)
    if not isinstance(value, list) or len(value) != 3:
        raise BrowserMessageError("%r must be a list of 3 numbers" % key)
    return [_number({"v": v}, "v") for v in value]


def parse(data):
    """One browser message (str or bytes as received) -> a checked dict."""
    if not isinstance(data, str):
        raise BrowserMessageError("binary frames are not accepted")
    if len(data) > MAX_MESSAGE_BYTES:
        raise BrowserMessageError("message of %d bytes (at most %d)" % (len(data), MAX_MESSAGE_BYTES))
    try:
        message = json.loads(data, parse_constant=_reject_constant)
    except (ValueError, RecursionError) as error:
        raise BrowserMessageError("not JSON: %s" % error) from None
    if not isinstance(message, dict):
        raise BrowserMessageError("not a JSON object")
    kind = message.get("type")
    if kind == "ready":
        return {"type": "ready"}
    if kind == "command":
        out = {"type": "command", "id": _integer(message, "id", 0)}
        command = message.get("command")
        if command not in COMMANDS:
            raise BrowserMessageError("unknown command %r" % (command,))
        out["command"] = command
        if command == "step":
            out["num_steps"] = _integer(message, "num_steps")
        if command == "set_real_time_factor":
            out["real_time_factor"] = _number(message, "real_time_factor")
        return out
    if kind == "wrench":
        body = message.get("body")
        if not isinstance(body, str) or not 0 < len(body) <= 256:
            raise BrowserMessageError("'body' must be a name of 1 to 256 characters")
        return {"type": "wrench", "id": _integer(message, "id", 0), "body": body,
                "force": _vector3(message, "force"), "point": _vector3(message, "point"),
                "duration": _number(message, "duration")}
    if kind == "replay":
        action = message.get("action")
        if action not in REPLAY_ACTIONS:
            raise BrowserMessageError("unknown replay action %r" % (action,))
        out = {"type": "replay", "id": _integer(message, "id", 0), "action": action}
        if action == "seek":
            out["index"] = _integer(message, "index")
        if action == "speed":
            out["speed"] = _number(message, "speed")
        return out
    raise BrowserMessageError("unknown message type %r" % (kind,))
