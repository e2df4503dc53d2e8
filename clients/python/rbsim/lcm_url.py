"""Why LCM could not open a URL, as far as the URL itself tells: a malformed
``udpm://`` URL is named as such, and only a well-formed one gets the hint
about a multicast route (LCM fails on both the same way). The same rules as
the C++ client's ``explainLcmOpenFailure`` (clients/cpp/src/lcm_url.cpp).

URL form (LCM's udpm provider): ``udpm://GROUP:PORT?ttl=N&recv_buf_size=B``,
GROUP an IPv4 multicast address (224.0.0.0 to 239.255.255.255).
"""

import ipaddress
from typing import Optional

__all__ = ["url_problem", "explain_open_failure"]

ROUTE_HINT = "is there a route for multicast? e.g. `ip route add 224.0.0.0/4 dev lo`"
_KNOWN_PROVIDERS = ("udpm", "memq", "file", "tcpq", "mpudpm")


def url_problem(url: str) -> Optional[str]:
    """What is wrong with ``url`` by itself, or None if it looks well formed."""
    provider, separator, rest = url.partition("://")
    if not separator:
        return "not an LCM URL (expected PROVIDER://..., e.g. udpm://239.255.76.67:7667?ttl=0)"
    if provider not in _KNOWN_PROVIDERS:
        return "unknown LCM provider '%s' (udpm, memq, file, tcpq or mpudpm)" % provider
    if provider != "udpm":
        return None
    address, _, options = rest.partition("?")
    host, colon, port = address.rpartition(":")
    if not colon:
        host, port = address, "7667"
    try:
        group = ipaddress.IPv4Address(host)
    except ValueError:
        return "udpm address '%s' is not an IPv4 address" % host
    if not group.is_multicast:
        return "udpm address %s is not a multicast group (224.0.0.0 to 239.255.255.255)" % host
    if not port.isdigit() or not 0 < int(port) < 65536:
        return "udpm port '%s' is not a number from 1 to 65535" % port
    for option in filter(None, options.split("&")):
        key, equals, value = option.partition("=")
        if key == "ttl" and not (equals and value.isdigit() and int(value) <= 255):
            return "ttl '%s' is not a number from 0 to 255" % value
        if key == "recv_buf_size" and not (equals and value.isdigit()):
            return "recv_buf_size '%s' is not a number of bytes" % value
    return None


def explain_open_failure(url: str) -> str:
    """One sentence for "LCM could not open ``url``"."""
    problem = url_problem(url)
    if problem:
        return "cannot open LCM with URL '%s': %s" % (url, problem)
    if url.startswith("udpm://"):
        return "cannot open LCM with URL '%s' (%s)" % (url, ROUTE_HINT)
    return "cannot open LCM with URL '%s'" % url
