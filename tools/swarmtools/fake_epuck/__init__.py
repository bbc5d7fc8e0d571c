"""swarm-fake-epuck: e-puck1 stand-ins on pseudo-terminals (cli.py has the
command line; server.FakeEpucks is the tests' way in)."""
