"""swarm-evolve: evolving a controller's parameters on the sweep engine."""
