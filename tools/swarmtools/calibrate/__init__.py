"""The calibration kit: fit the simulator's sensor models to a lab's own e-pucks
(docs/how-to/calibrate.md)."""
