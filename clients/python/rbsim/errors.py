"""The client's own exceptions, each with its reason in its message.

``RbsimError`` is the base of all of them. ``UnknownNameError`` is raised by
every lookup by name (``state["box"]``, ``sim.joint_state("elbow")``,
``world.joint("hip")``): it names what is unknown and the closest known
names, as the server's refusals do ("did you mean 'arm/joint2'?"), and it is
a ``KeyError`` too, so ``except KeyError`` keeps working.
"""

from typing import Iterable, List, Sequence

__all__ = ["RbsimError", "UnknownNameError", "closest_names"]

# A name longer than this gets no suggestions (the server's limit too,
# server/bridge/closest_names.h): a guess at it costs more than it tells.
_MAX_SUGGESTED_NAME_LENGTH = 128


class RbsimError(Exception):
    """Base of the exceptions the rbsim client raises of its own."""


def _distance(a: str, b: str, bound: int) -> int:
    """Levenshtein distance of a and b ignoring case, or bound + 1 once it
    is sure to exceed bound (a row's smallest entry never shrinks)."""
    if abs(len(a) - len(b)) > bound:
        return bound + 1
    a, b = a.lower(), b.lower()
    row = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        diagonal, row[0] = row[0], i
        for j, cb in enumerate(b, 1):
            above = row[j]
            row[j] = min(above + 1, row[j - 1] + 1, diagonal + (ca != cb))
            diagonal = above
        if min(row) > bound:
            return bound + 1
    return row[-1]


def closest_names(name: str, known: Iterable[str], count: int = 3) -> List[str]:
    """Up to ``count`` of ``known`` within max(2, len(name) // 3) edits of
    ``name`` (case ignored), closest first, ties alphabetically."""
    if not isinstance(name, str) or len(name) > _MAX_SUGGESTED_NAME_LENGTH or count <= 0:
        return []
    bound = max(2, len(name) // 3)
    near = sorted((d, k) for k in set(known) if isinstance(k, str) for d in [_distance(name, k, bound)] if d <= bound)
    return [k for _, k in near[:count]]


def _did_you_mean(names: Sequence[str]) -> str:
    if not names:
        return ""
    quoted = ["'%s'" % n for n in names]
    listed = quoted[0] if len(quoted) == 1 else ", ".join(quoted[:-1]) + " or " + quoted[-1]
    return " (did you mean %s?)" % listed


class UnknownNameError(RbsimError, KeyError):
    """A lookup by a name that is not there.

    Attributes: ``kind`` ("body", "joint"), ``name`` (what was asked for),
    ``where`` (e.g. "the state of step 12"), ``suggestions`` (the closest
    known names, closest first; maybe empty).
    """

    def __init__(self, kind: str, name, known: Iterable[str] = (), where: str = ""):
        self.kind, self.name, self.where = kind, name, where
        self.suggestions = closest_names(name, known)
        message = "unknown %s %r" % (kind, name) if not isinstance(name, str) else "unknown %s '%s'" % (kind, name)
        if where:
            message += " in " + where
        super().__init__(message + _did_you_mean(self.suggestions))

    # KeyError's str() is the repr of its key; ours is a sentence.
    def __str__(self):
        return self.args[0]
