"""Which Host headers the server answers: its own names and address only.

A page may talk to the server only if it came from the server.  A browser
sends Origin with a WebSocket, and the server compares it with the Host the
request was sent to; but a page of any web site whose name the site makes
resolve to 127.0.0.1 (DNS rebinding) sends its own name in both.  So the
Host itself is checked first, on every request: it must name this server
(the address it listens on; "localhost" when that is a loopback or every
address; this machine's names when it listens beyond it; --allow-host
names), with the port it listens on.  An IP address needs no DNS, so when
the server listens on every address any of the machine's IP addresses is
accepted with its port.
"""
import ipaddress
import socket


def split(host):
    """(name, port) of a Host header ("localhost:8080", "[::1]:80"; port
    80 when absent), the name lower case; None when it is not one."""
    host = host.strip()
    if host.startswith("["):
        end = host.find("]")
        if end < 0:
            return None
        name, rest = host[1:end], host[end + 1:]
        if rest and not rest.startswith(":"):
            return None
        port = rest[1:] if rest else "80"
    else:
        name, _, port = host.partition(":")
        port = port if _ else "80"
    if not name or not port.isascii() or not port.isdigit() or len(port) > 5:
        return None
    return name.lower().rstrip("."), int(port)


def _ip(name):
    try:
        return ipaddress.ip_address(name)
    except ValueError:
        return None


class AllowedHosts:
    def __init__(self, bound, port, allow=()):
        """bound: the address or name the server listens on (--host);
        port: the port it listens on; allow: more NAME or NAME:PORT."""
        self.port = port
        self.names = set()               # (name, port)
        bound_ip = _ip(bound)
        self.any_ip = bound_ip is not None and bound_ip.is_unspecified
        loopback = bound in ("localhost",) or (bound_ip is not None and bound_ip.is_loopback)
        for name in [bound] + (["localhost", "127.0.0.1", "::1"] if loopback or self.any_ip else []):
            self.names.add((name.lower().rstrip("."), port))
        if not loopback:                  # reachable from elsewhere: by this machine's names too
            for name in {socket.gethostname(), socket.getfqdn()}:
                self.names.add((name.lower().rstrip("."), port))
        for a in allow:
            got = split(a) if ":" in a.replace("::", "") or a.startswith("[") else (a.lower().rstrip("."), port)
            if got is None:
                raise ValueError(f"--allow-host {a!r}: expected NAME or NAME:PORT")
            self.names.add(got)

    def why_not(self, host):
        """None if a request with this Host header is for this server, else why not."""
        got = split(host or "")
        if got is None:
            return f"Host {host!r} is not a host name"
        if got in self.names or (self.any_ip and got[1] == self.port and _ip(got[0]) is not None):
            return None
        return (f"Host {host!r} is not this server's name ({self.shown()}); a page from another site "
                "may not use it (pass --allow-host NAME[:PORT] for a name or tunnel of your own)")

    def shown(self):
        return ", ".join(sorted(f"[{n}]:{p}" if ":" in n else f"{n}:{p}" for n, p in self.names))
