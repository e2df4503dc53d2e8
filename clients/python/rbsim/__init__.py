"""rbsim: Python client for the rbsim rigid-body simulation server (LCM).

This package also serves the lcm-gen message types (``rbsim.world_state_t``,
``rbsim.wrench_t`` ...). As in lcm-gen's own ``__init__.py``, the package
attribute ``rbsim.<type>`` is the message class (the generated code relies on
that: it calls ``rbsim.body_state_t._decode_one``).

Installed (``pip install --no-build-isolation ./clients/python``), the types
are modules of this package, generated at install time. Run from the
repository instead, they are a build output (``build/lcmtypes/python/rbsim/``)
whose directory is appended to this package's ``__path__``, looked up, in order, from
  1. ``$RBSIM_LCMTYPES_PYTHON_DIR`` (a directory holding the generated ``rbsim/``),
  2. ``$RBSIM_BUILD_DIR/lcmtypes/python``,
  3. ``<repository>/build/lcmtypes/python``.

Hand-written modules:
  ``rbsim.lcm_ctypes``  ctypes wrapper over liblcm.so.1 (transport, event logs)
  ``rbsim.client``      :class:`Client`: state, status, world, joints, wrenches, commands, acks
  ``rbsim.robot``       :class:`Robot`: one robot's commands and state at control rate (lock-step too)
  ``rbsim.sensors``     :class:`SensorReader`: a world's sensors (IMU, contact, force-torque, range, lidar)
  ``rbsim.log``         :func:`load_log`: LCM logs as numpy arrays
  ``rbsim.cli``         the ``python3 -m rbsim`` command line
"""

import importlib as _importlib
import os as _os

__version__ = "0.1.0"

# The lcm-gen message types of package rbsim (lcmtypes/rbsim/*.lcm).
_GENERATED_TYPES = (
    "ack_t",
    "body_description_t",
    "body_state_t",
    "command_t",
    "compound_part_t",
    "contact_sensor_t",
    "contact_t",
    "contacts_t",
    "force_torque_t",
    "imu_t",
    "joint_command_t",
    "joint_description_t",
    "joint_state_t",
    "joints_t",
    "range_scan_t",
    "robot_command_t",
    "robot_state_t",
    "status_t",
    "visual_t",
    "world_state_t",
    "world_t",
    "wrench_t",
)


def _generated_dir_candidates():
    """The directories (each holding a generated ``rbsim/``) to look in, in order."""
    explicit = _os.environ.get("RBSIM_LCMTYPES_PYTHON_DIR")
    if explicit:
        return [explicit]
    build = _os.environ.get("RBSIM_BUILD_DIR")
    if build:
        return [_os.path.join(build, "lcmtypes", "python")]
    here = _os.path.dirname(_os.path.abspath(__file__))
    repo = _os.path.dirname(_os.path.dirname(_os.path.dirname(here)))
    return [_os.path.join(repo, "build", "lcmtypes", "python")]


def _find_generated_package():
    """Returns the generated ``rbsim`` directory, or raises ImportError."""
    here = _os.path.dirname(_os.path.abspath(__file__))
    if _os.path.isfile(_os.path.join(here, "world_state_t.py")):
        return here  # installed: the types are modules of this package
    candidates = _generated_dir_candidates()
    for base in candidates:
        package = _os.path.join(base, "rbsim")
        if _os.path.isfile(_os.path.join(package, "world_state_t.py")):
            return package
    raise ImportError(
        "rbsim: the generated LCM Python types were not found in "
        + ", ".join(repr(_os.path.join(c, "rbsim")) for c in candidates)
        + ". Build the project first: cmake --build build "
        "(or set RBSIM_BUILD_DIR / RBSIM_LCMTYPES_PYTHON_DIR), or install the package: "
        "pip install --no-build-isolation ./clients/python"
    )


_generated = _find_generated_package()
if _generated not in __path__:
    __path__.append(_generated)

# Import every type module first, then bind the classes: importing a module
# binds `rbsim.<name>` to the module, the generated code needs the class.
_modules = {name: _importlib.import_module(__name__ + "." + name) for name in _GENERATED_TYPES}
for _name, _module in _modules.items():
    globals()[_name] = getattr(_module, _name)
del _name, _module, _modules


def _message_repr(message, _limit=4):
    """``ack_t(client='py-host-1', seq=3, accepted=True, ...)``: every field, by
    name; lists of more than a few nested messages are summarised by count."""
    parts = []
    for field in message.__slots__:
        value = getattr(message, field)
        if isinstance(value, list) and len(value) > _limit and value and hasattr(value[0], "__slots__"):
            text = "[%d x %s]" % (len(value), type(value[0]).__name__)
        elif isinstance(value, (tuple, list)) and all(isinstance(v, float) for v in value):
            text = "(" + ", ".join("%.10g" % v for v in value) + ")"
        elif isinstance(value, float):
            text = "%.10g" % value
        else:
            text = repr(value)
        parts.append("%s=%s" % (field, text))
    return "%s(%s)" % (type(message).__name__, ", ".join(parts))


for _name in _GENERATED_TYPES:
    globals()[_name].__repr__ = _message_repr
del _name


def __getattr__(name):
    """Lazy access to the main entry points: rbsim.Client, rbsim.Robot, rbsim.load_log,
    and the client's exceptions (rbsim.RbsimError, rbsim.UnknownNameError,
    rbsim.Rejected)."""
    if name == "Client":
        from .client import Client

        return Client
    if name == "Robot":
        from .robot import Robot

        return Robot
    if name in ("RbsimError", "UnknownNameError", "Rejected"):
        from . import client

        return getattr(client, name)
    if name == "load_log":
        from .log import load_log

        return load_log
    raise AttributeError("module 'rbsim' has no attribute %r" % name)


__all__ = list(_GENERATED_TYPES) + ["Client", "Robot", "load_log", "RbsimError", "UnknownNameError", "Rejected"]
