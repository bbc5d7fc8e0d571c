"""swarm-fake-epuck: e-puck1 stand-ins on pseudo-terminals."""
