"""swarm-live: a live view of a swarm in the browser (server.py).

view.py turns telemetry messages into what the page shows, replay.py plays
an LCM log at any speed with pause and seek, bus.py follows a live LCM bus;
static/ is the page (plain HTML and JavaScript on a canvas).
"""
